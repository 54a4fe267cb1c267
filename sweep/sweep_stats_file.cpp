// The statistics file (formats/stats_file.hpp) from SweepStats: one function per statistic
// defines its variables and returns the step that writes their values once the file
// leaves define mode. The variables are defined in the order of the calls in
// write_stats_file (the file's layout).
#include <functional>
#include <map>

#include "common/atomic_file.hpp"
#include "common/cf.hpp"
#include "common/columns.hpp"
#include "common/netcdf.hpp"
#include "formats/stats_file.hpp"
#include "sweep/sweep_stats.hpp"
#include "sweep/trajectory_kernels.hpp"

namespace flotsam::sweep {

namespace {

namespace schema = stats_file;

struct StatsDims {
    std::map<std::string, int> id;  // by name (stats_file::dim)
    std::string grid_mapping;       // of the maps (over ..., y, x); "" without a CRS
};

using PutValues = std::function<void()>;

// Defines `v` as the schema gives it: strings (NC_CHAR) as long as `text_length`, maps
// naming `grid_mapping`.
int def(nc::File& f, const StatsDims& d, const schema::Variable& v, std::size_t text_length = 0,
        const std::string& grid_mapping = "") {
    std::vector<int> dims;
    for (const char* name : v.dims) dims.push_back(d.id.at(name));
    return cf::def_var(f, {.name = v.name,
                           .type = v.type,
                           .dims = std::move(dims),
                           .units = v.units,
                           .long_name = v.long_name,
                           .fill = v.fill,
                           .grid_mapping = grid_mapping,
                           .text_length = text_length});
}

// Strings, as a character array as long as the longest of `values`.
int def_text(nc::File& f, const StatsDims& d, const schema::Variable& v, const std::vector<std::string>& values) {
    return def(f, d, v, cf::longest(values));
}

// Groups, parameter sets, sections and regions.
PutValues define_tables(nc::File& f, const StatsDims& d, const SweepStats& s) {
    const auto bodies = column<std::string>(s.groups, &SweepStats::Group::body);
    const auto variants = column<std::string>(s.groups, &SweepStats::Group::variant);
    const auto section_names = column<std::string>(s.sections, &Section::name);
    const int vgb = def_text(f, d, schema::group_body, bodies);
    const int vgv = def_text(f, d, schema::group_variant, variants);
    const int vgm = def(f, d, schema::group_members);
    const ParameterSetVariables set_vars = define_parameter_set_variables(f, d.id.at(schema::dim::param_set), s.params);
    const int vpm = def(f, d, schema::param_members);
    const int vsn = def_text(f, d, schema::section_name, section_names);
    const int vsx = def(f, d, schema::section_x);
    const int vsy0 = def(f, d, schema::section_y_min);
    const int vsy1 = def(f, d, schema::section_y_max);
    const int vrn = def_text(f, d, schema::region_name, s.regions);
    return [=, &f, &s] {
        f.put(vgb, bodies);
        f.put(vgv, variants);
        f.put(vgm, column<int>(s.groups, [](const SweepStats::Group& g) { return g.members.size(); }));
        put_parameter_sets(f, set_vars, s.params);
        f.put(vpm, flatten(s.param_members));
        f.put(vsn, section_names);
        f.put(vsx, column<double>(s.sections, &Section::x));
        f.put(vsy0, column<double>(s.sections, &Section::y_min));
        f.put(vsy1, column<double>(s.sections, &Section::y_max));
        f.put(vrn, s.regions);
    };
}

// One set of section-summary variables (per group, or per group and parameter set).
PutValues define_passage_summaries(nc::File& f, const StatsDims& d, const schema::PassageVariables& v,
                                   std::vector<const SectionSummary*> list) {
    const int count = def(f, d, v.count);
    const int ym = def(f, d, v.y_mean), ymed = def(f, d, v.y_median), ystd = def(f, d, v.y_std);
    const int sm = def(f, d, v.speed_mean), smed = def(f, d, v.speed_median), sstd = def(f, d, v.speed_std);
    const int bw = def(f, d, v.speed_bandwidth);
    const int kde = def(f, d, v.speed_kde);
    return [=, &f] {
        auto field = [&](double SectionSummary::*m) {
            return cf::filled(column<double>(list, [m](const SectionSummary* q) { return q->*m; }));
        };
        f.put(count, column<int>(list, [](const SectionSummary* q) { return q->count; }));
        f.put(ym, field(&SectionSummary::y_mean));
        f.put(ymed, field(&SectionSummary::y_median));
        f.put(ystd, field(&SectionSummary::y_std));
        f.put(sm, field(&SectionSummary::speed_mean));
        f.put(smed, field(&SectionSummary::speed_median));
        f.put(sstd, field(&SectionSummary::speed_std));
        f.put(bw, field(&SectionSummary::bandwidth));
        f.put(kde, flatten(column<std::vector<double>>(list, [](const SectionSummary* q) { return q->kde; })));
    };
}

// Passages: section summaries with their speed densities, per group and per (group,
// parameter set); the speed axis; every member's passages.
PutValues define_passages(nc::File& f, const StatsDims& d, const SweepStats& s) {
    std::vector<const SectionSummary*> by_group, by_param;
    for (const auto& row : s.section)
        for (const auto& q : row) by_group.push_back(&q);
    for (const auto& block : s.section_by_param)
        for (const auto& row : block)
            for (const auto& q : row) by_param.push_back(&q);
    const PutValues put_a = define_passage_summaries(f, d, schema::passage, by_group);
    const PutValues put_b = define_passage_summaries(f, d, schema::passage_by_param, by_param);
    const int vspeed = def(f, d, schema::speed);
    const int vmt = def(f, d, schema::member_passage_time);
    const int vmy = def(f, d, schema::member_passage_y);
    const int vms = def(f, d, schema::member_passage_speed);
    return [=, &f, &s] {
        put_a();
        put_b();
        f.put(vspeed, s.speed);
        f.put(vmt, cf::filled(flatten(s.passage_time)));
        f.put(vmy, cf::filled(flatten(s.passage_y)));
        f.put(vms, cf::filled(flatten(s.passage_speed)));
    };
}

// Yaw histograms and their bins.
PutValues define_yaw_histograms(nc::File& f, const StatsDims& d, const SweepStats& s) {
    const int vyb = def(f, d, schema::yaw_bin);
    f.put_att(vyb, "bounds", std::string(schema::yaw_bin_bounds.name));
    const int vybb = def(f, d, schema::yaw_bin_bounds);
    const int vhr = def(f, d, schema::max_rotation_histogram);
    const int vhm = def(f, d, schema::max_yaw_to_motion_histogram);
    return [=, &f, &s] {
        std::vector<double> centres, bounds;
        for (std::size_t b = 0; b + 1 < s.yaw_edges.size(); ++b) {
            centres.push_back(0.5 * (s.yaw_edges[b] + s.yaw_edges[b + 1]));
            bounds.push_back(s.yaw_edges[b]);
            bounds.push_back(s.yaw_edges[b + 1]);
        }
        f.put(vyb, centres);
        f.put(vybb, bounds);
        f.put(vhr, flatten(s.rotation_hist));
        f.put(vhm, flatten(s.yaw_motion_hist));
    };
}

// What each member is: its id, group, parameter set and flow.
PutValues define_member_table(nc::File& f, const StatsDims& d, const SweepStats& s) {
    const int vmid = def(f, d, schema::member_id);
    const int vmg = def(f, d, schema::member_group);
    const int vmp = def(f, d, schema::member_param_set);
    const int vmf = def(f, d, schema::member_flow);
    return [=, &f, &s] {
        f.put(vmid, s.member_id);
        f.put(vmg, s.member_group);
        f.put(vmp, s.member_param_set);
        f.put(vmf, s.member_flow);
    };
}

// Each member's motion start and yaw after it.
PutValues define_member_yaw(nc::File& f, const StatsDims& d, const SweepStats& s) {
    const int vm0 = def(f, d, schema::member_motion_start);
    const int vmr = def(f, d, schema::member_max_rotation);
    const int vmy2 = def(f, d, schema::member_max_yaw_to_motion);
    const int vmd = def(f, d, schema::member_motion_direction);
    return [=, &f, &s] {
        f.put(vm0, cf::filled(s.motion_start));
        f.put(vmr, cf::filled(s.max_rotation));
        f.put(vmy2, cf::filled(s.max_yaw_to_motion));
        f.put(vmd, cf::filled(s.motion_direction));
    };
}

// The paper's Fig. 16 (from the run's start): per member, the histogram and the group
// summaries with the correlation.
PutValues define_rotation_from_start(nc::File& f, const StatsDims& d, const SweepStats& s) {
    const int vmr = def(f, d, schema::member_max_rotation_from_start);
    const int vmd = def(f, d, schema::member_movement_direction);
    const int vh = def(f, d, schema::max_rotation_from_start_histogram);
    const int vn = def(f, d, schema::max_rotation_from_start_count);
    const int vmed = def(f, d, schema::max_rotation_from_start_median), vmean = def(f, d, schema::max_rotation_from_start_mean),
              vmin = def(f, d, schema::max_rotation_from_start_min), vmax = def(f, d, schema::max_rotation_from_start_max);
    const int vr = def(f, d, schema::rotation_direction_correlation);
    return [=, &f, &s] {
        using Summary = SweepStats::RotationSummary;
        auto field = [&](double Summary::*m) { return cf::filled(column<double>(s.rotation_from_start, m)); };
        f.put(vmr, cf::filled(s.max_rotation_from_start));
        f.put(vmd, cf::filled(s.movement_direction));
        f.put(vh, flatten(s.rotation_from_start_hist));
        f.put(vn, column<int>(s.rotation_from_start, &Summary::count));
        f.put(vmed, field(&Summary::median));
        f.put(vmean, field(&Summary::mean));
        f.put(vmin, field(&Summary::min));
        f.put(vmax, field(&Summary::max));
        f.put(vr, field(&Summary::direction_correlation));
    };
}

// Each member's region at the arrival time, and the counts per region.
PutValues define_regions(nc::File& f, const StatsDims& d, const SweepStats& s) {
    const int vmreg = def(f, d, schema::member_region);
    const int vrc = def(f, d, schema::region_count);
    const int vrcp = def(f, d, schema::region_count_by_param);
    return [=, &f, &s] {
        f.put(vmreg, s.region_at_arrival);
        f.put(vrc, flatten(s.region_count));
        f.put(vrcp, flatten(s.region_count_by_param));
    };
}

// Distance from the start and R(t) per (group, parameter set).
PutValues define_distance(nc::File& f, const StatsDims& d, const SweepStats& s) {
    const int vt = cf::def_time(f, d.id.at(schema::dim::time), schema::time, "time");
    const int vdm = def(f, d, schema::distance_mean);
    const int vds = def(f, d, schema::distance_std);
    const int vre = def(f, d, schema::relative_error);
    return [=, &f, &s] {
        f.put(vt, s.time);
        f.put(vdm, cf::filled(flatten(s.distance_mean)));
        f.put(vds, cf::filled(flatten(s.distance_std)));
        f.put(vre, cf::filled(flatten(s.relative_error)));
    };
}

// Impacts per building: per (group, building) and over all trajectories per building.
PutValues define_buildings(nc::File& f, const StatsDims& d, const SweepStats& s) {
    const int vid = def(f, d, schema::building_id);
    struct Ids {
        int v[9];
    };
    const auto define = [&](const schema::BuildingVariables& b) {
        Ids ids{};
        const schema::Variable* vars[] = {&b.hit_probability, &b.first_hit_time, &b.impact_count, &b.speed_median, &b.speed_p90,
                                          &b.speed_max,       &b.force_median,   &b.force_p90,    &b.force_max};
        for (int k = 0; k < 9; ++k) ids.v[k] = def(f, d, *vars[k]);
        return ids;
    };
    const Ids per_group = define(schema::building), all = define(schema::building_all);
    const auto put = [&f](const Ids& ids, const std::vector<SweepStats::BuildingSummary>& q) {
        using B = SweepStats::BuildingSummary;
        f.put(ids.v[0], column<float>(q, [](const B& b) { return float(b.hit_probability); }));
        f.put(ids.v[1], cf::filled(column<double>(q, &B::first_hit_time)));
        f.put(ids.v[2], column<int>(q, &B::impacts));
        f.put(ids.v[3], cf::filled(column<double>(q, &B::speed_median)));
        f.put(ids.v[4], cf::filled(column<double>(q, &B::speed_p90)));
        f.put(ids.v[5], cf::filled(column<double>(q, &B::speed_max)));
        f.put(ids.v[6], cf::filled(column<double>(q, &B::force_median)));
        f.put(ids.v[7], cf::filled(column<double>(q, &B::force_p90)));
        f.put(ids.v[8], cf::filled(column<double>(q, &B::force_max)));
    };
    return [=, &f, &s] {
        f.put(vid, std::vector<int>(s.building_ids.begin(), s.building_ids.end()));
        std::vector<SweepStats::BuildingSummary> flat;  // (group, building), building fastest
        for (const auto& g : s.building) flat.insert(flat.end(), g.begin(), g.end());
        put(per_group, flat);
        put(all, s.building_all);
    };
}

// The probability and largest-speed maps.
PutValues define_maps(nc::File& f, const StatsDims& d, const SweepStats& s) {
    const cf::XYAxes axes = cf::def_xy(f, d.id.at(schema::dim::x), d.id.at(schema::dim::y), "map cell centre");
    cf::def_crs(f, s.crs);
    // Maps name the grid mapping, so GIS tools place them.
    auto map = [&](const schema::Variable& v) { return def(f, d, v, 0, d.grid_mapping); };
    const int vpp = map(schema::pass_probability);
    const int vmx = map(schema::max_debris_speed);
    const int vppa = map(schema::pass_probability_all);
    const int vmxa = map(schema::max_debris_speed_all);
    return [=, &f, &s] {
        f.put(axes.x, s.map.xs());
        f.put(axes.y, s.map.ys());
        f.put(vpp, flatten(s.pass_probability));
        f.put(vmx, cf::filled(flatten(s.max_speed)));
        f.put(vppa, s.pass_probability_all);
        f.put(vmxa, cf::filled(s.max_speed_all));
    };
}

// The inputs and every setting, as global attributes.
void put_settings(nc::File& f, const SweepStats& s, const StatsDef& def, const std::string& sweep_file,
                  const std::string& scene_file, const std::string& history) {
    namespace att = schema::attribute;
    cf::put_conventions(f);
    cf::put_kind(f, schema::kind);
    f.put_att(NC_GLOBAL, att::title, std::string("flotsam sweep statistics"));
    f.put_att(NC_GLOBAL, att::source, std::string("flotsam stats"));
    f.put_att(NC_GLOBAL, att::sweep_file, sweep_file);
    f.put_att(NC_GLOBAL, att::scene_file, scene_file);
    f.put_att(NC_GLOBAL, att::scene_buildings_sha256, s.scene_buildings_sha256);
    f.put_att(NC_GLOBAL, att::history, history);
    f.put_att(NC_GLOBAL, att::yaw_window, def.yaw_window);
    f.put_att(NC_GLOBAL, att::yaw_min_speed, def.yaw_min_speed);
    f.put_att(NC_GLOBAL, att::motion_threshold, motion_threshold);
    f.put_att(NC_GLOBAL, att::arrival_time, def.arrival_time);
    f.put_att(NC_GLOBAL, att::r_min_distance, def.r_min_distance);
    f.put_att(NC_GLOBAL, att::kde_bandwidth_rule,
              std::string("Silverman: h = 0.9 min(std, IQR/1.34) n^(-1/5); std alone when IQR = 0; max(0.1 |mean|, kde_floor) "
                          "when no spread"));
    f.put_att(NC_GLOBAL, att::kde_floor, def.kde_floor);
    f.put_att(NC_GLOBAL, att::control_param_set, s.control);
    f.put_att(NC_GLOBAL, att::map_coarsen, def.map_coarsen);
}

// The dimensions, in the order of stats_file::dimension_names().
StatsDims define_dimensions(nc::File& f, const SweepStats& s) {
    namespace dim = schema::dim;
    StatsDims d{{}, cf::grid_mapping_of(s.crs)};
    const std::pair<const char*, std::size_t> lengths[] = {{dim::group, s.groups.size()},
                                                           {dim::param_set, s.params.size()},
                                                           {dim::section, s.sections.size()},
                                                           {dim::region, s.regions.size()},
                                                           {dim::speed, s.speed.size()},
                                                           {dim::yaw_bin, s.yaw_edges.size() - 1},
                                                           {dim::bnds, 2},
                                                           {dim::time, s.time.size()},
                                                           {dim::member, s.member_group.size()},
                                                           {dim::building, s.building_ids.size()},
                                                           {dim::x, std::size_t(s.map.nx)},
                                                           {dim::y, std::size_t(s.map.ny)}};
    for (const auto& [name, length] : lengths) d.id[name] = f.def_dim(name, length);
    return d;
}

}  // namespace

void write_stats_file(const std::string& path, const SweepStats& s, const StatsDef& def, const std::string& sweep_file,
                      const std::string& scene_file, const std::string& history) {
    ensure_parent_dir(path);
    AtomicOutput out(path);
    {
        nc::File f = nc::File::create(out.temp_path());
        const StatsDims d = define_dimensions(f, s);
        const std::vector<PutValues> puts = {
            define_tables(f, d, s),       define_passages(f, d, s),   define_yaw_histograms(f, d, s),
            define_member_table(f, d, s), define_member_yaw(f, d, s), define_rotation_from_start(f, d, s),
            define_regions(f, d, s),      define_distance(f, d, s),   define_buildings(f, d, s),
            define_maps(f, d, s)};
        put_settings(f, s, def, sweep_file, scene_file, history);
        f.enddef();
        for (const PutValues& put : puts) put();
        f.close();
    }
    out.commit();
}

}  // namespace flotsam::sweep
