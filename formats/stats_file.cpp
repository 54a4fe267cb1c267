#include "formats/stats_file.hpp"

#include <cmath>
#include <cstring>

#include "common/cf.hpp"
#include "common/error.hpp"
#include "common/units.hpp"

namespace flotsam::stats_file {

namespace {
using Dims = std::vector<const char*>;
const Dims group_section = {dim::group, dim::section}, group_section_speed = {dim::group, dim::section, dim::speed};
const Dims param_section = {dim::group, dim::param_set, dim::section},
           param_section_speed = {dim::group, dim::param_set, dim::section, dim::speed};
const Dims param_time = {dim::group, dim::param_set, dim::time};
const Dims member_section = {dim::member, dim::section}, group_yaw_bin = {dim::group, dim::yaw_bin};
const Dims group_region = {dim::group, dim::region}, param_region = {dim::group, dim::param_set, dim::region};
const Dims group_map = {dim::group, dim::y, dim::x}, map = {dim::y, dim::x};
const Dims group_building = {dim::group, dim::building}, per_building = {dim::building};
}  // namespace

const std::vector<std::string>& dimension_names() {
    static const std::vector<std::string> names = {dim::group, dim::param_set, dim::section, dim::region, dim::speed, dim::yaw_bin,
                                                   dim::bnds,  dim::time,      dim::member,  dim::building, dim::x,      dim::y};
    return names;
}

const Variable group_body{"group_body", NC_CHAR, {dim::group}, "", "body of the group, or the GIS source (layer/feature id) of its bodies", false};
const Variable group_variant{
    "group_variant", NC_CHAR, {dim::group}, "", "model variant of the group (friction + collision)", false};
const Variable group_members{"group_members", NC_INT, {dim::group}, "", "trajectories in the group", false};
const Variable param_members{
    "param_members", NC_INT, {dim::group, dim::param_set}, "", "trajectories of the group with this parameter set", false};
const Variable section_name{"section_name", NC_CHAR, {dim::section}, "", "cross-section name", false};
const Variable section_x{"section_x", NC_DOUBLE, {dim::section}, "m", "x of the north-south cross-section", false};
const Variable section_y_min{"section_y_min", NC_DOUBLE, {dim::section}, "m", "south end of the cross-section", false};
const Variable section_y_max{"section_y_max", NC_DOUBLE, {dim::section}, "m", "north end of the cross-section", false};
const Variable region_name{"region_name", NC_CHAR, {dim::region}, "", "region name", false};

const PassageVariables passage{
    {"passage_count", NC_INT, group_section, "", "trajectories passing the section (all members of the group)", false},
    {"passage_y_mean", NC_DOUBLE, group_section, "m", "mean y of first passage (all members of the group)", true},
    {"passage_y_median", NC_DOUBLE, group_section, "m", "median y of first passage (all members of the group)", true},
    {"passage_y_std", NC_DOUBLE, group_section, "m", "standard deviation (n-1) of the passage y (all members of the group)", true},
    {"passage_speed_mean", NC_DOUBLE, group_section, "m s-1", "mean body speed at passage (all members of the group)", true},
    {"passage_speed_median", NC_DOUBLE, group_section, "m s-1", "median body speed at passage (all members of the group)", true},
    {"passage_speed_std", NC_DOUBLE, group_section, "m s-1",
     "standard deviation (n-1) of the passage speed (all members of the group)", true},
    {"passage_speed_bandwidth", NC_DOUBLE, group_section, "m s-1",
     "Gaussian KDE bandwidth (Silverman's rule) (all members of the group)", true},
    {"passage_speed_kde", NC_DOUBLE, group_section_speed, "s m-1",
     "Gaussian kernel density of the passage speed (all members of the group)", false},
};
const PassageVariables passage_by_param{
    {"passage_count_by_param", NC_INT, param_section, "",
     "trajectories passing the section (members of the group with this parameter set)", false},
    {"passage_y_mean_by_param", NC_DOUBLE, param_section, "m",
     "mean y of first passage (members of the group with this parameter set)", true},
    {"passage_y_median_by_param", NC_DOUBLE, param_section, "m",
     "median y of first passage (members of the group with this parameter set)", true},
    {"passage_y_std_by_param", NC_DOUBLE, param_section, "m",
     "standard deviation (n-1) of the passage y (members of the group with this parameter set)", true},
    {"passage_speed_mean_by_param", NC_DOUBLE, param_section, "m s-1",
     "mean body speed at passage (members of the group with this parameter set)", true},
    {"passage_speed_median_by_param", NC_DOUBLE, param_section, "m s-1",
     "median body speed at passage (members of the group with this parameter set)", true},
    {"passage_speed_std_by_param", NC_DOUBLE, param_section, "m s-1",
     "standard deviation (n-1) of the passage speed (members of the group with this parameter set)", true},
    {"passage_speed_bandwidth_by_param", NC_DOUBLE, param_section, "m s-1",
     "Gaussian KDE bandwidth (Silverman's rule) (members of the group with this parameter set)", true},
    {"passage_speed_kde_by_param", NC_DOUBLE, param_section_speed, "s m-1",
     "Gaussian kernel density of the passage speed (members of the group with this parameter set)", false},
};
const Variable speed{"speed", NC_DOUBLE, {dim::speed}, "m s-1", "speed axis of the passage speed densities", false};
const Variable member_passage_time{"member_passage_time", NC_DOUBLE, member_section, "s", "time of first passage", true};
const Variable member_passage_y{"member_passage_y", NC_DOUBLE, member_section, "m", "y of first passage", true};
const Variable member_passage_speed{"member_passage_speed",        NC_DOUBLE, member_section, "m s-1",
                                    "body speed at first passage", true};

const Variable yaw_bin{"yaw_bin", NC_DOUBLE, {dim::yaw_bin}, "degree", "bin centre", false};
const Variable yaw_bin_bounds{"yaw_bin_bounds", NC_DOUBLE, {dim::yaw_bin, dim::bnds}, "degree", "bin edges", false};
const Variable max_rotation_histogram{
    "max_rotation_histogram",
    NC_INT,
    group_yaw_bin,
    "",
    "members per bin of the largest rotation from the heading at motion start, within yaw_window_s",
    false};
const Variable max_yaw_to_motion_histogram{
    "max_yaw_to_motion_histogram",
    NC_INT,
    group_yaw_bin,
    "",
    "members per bin of the largest angle of the long axis against the direction of motion, within yaw_window_s",
    false};

const Variable member_id{"member_id", NC_INT, {dim::member}, "", "member id in the sweep", false};
const Variable member_group{"member_group", NC_INT, {dim::member}, "", "group index", false};
const Variable member_param_set{"member_param_set", NC_INT, {dim::member}, "", "parameter set index", false};
const Variable member_flow{"member_flow", NC_INT, {dim::member}, "", "flow index in the sweep", false};
const Variable member_motion_start{
    "member_motion_start", NC_DOUBLE, {dim::member}, "s", "first output time at least motion_threshold_m from the start", true};
const Variable member_max_rotation{"member_max_rotation",
                                   NC_DOUBLE,
                                   {dim::member},
                                   "degree",
                                   "largest rotation within yaw_window_s of motion start, counter-clockwise positive",
                                   true};
const Variable member_max_yaw_to_motion{"member_max_yaw_to_motion",
                                        NC_DOUBLE,
                                        {dim::member},
                                        "degree",
                                        "largest long-axis angle against the velocity within yaw_window_s",
                                        true};
const Variable member_motion_direction{
    "member_motion_direction",
    NC_DOUBLE,
    {dim::member},
    "degree",
    "direction from the start to the position yaw_window_s after motion start, from +x counter-clockwise",
    true};

const Variable member_max_rotation_from_start{
    "member_max_rotation_from_start",
    NC_DOUBLE,
    {dim::member},
    "degree",
    "largest rotation from the initial heading within yaw_window_s of the run's start (paper Fig. 16a), counter-clockwise "
    "positive",
    true};
const Variable member_movement_direction{
    "member_movement_direction",
    NC_DOUBLE,
    {dim::member},
    "degree",
    "direction from the initial location to the position yaw_window_s after the run's start, from east counter-clockwise: "
    "north-east positive (paper Fig. 16c); undefined below motion_threshold_m",
    true};
const Variable max_rotation_from_start_histogram{
    "max_rotation_from_start_histogram",
    NC_INT,
    group_yaw_bin,
    "",
    "members per bin of the largest rotation from the initial heading within yaw_window_s of the run's start",
    false};
const Variable max_rotation_from_start_count{
    "max_rotation_from_start_count", NC_INT, {dim::group}, "", "members with a largest rotation from the start", false};
const Variable max_rotation_from_start_median{"max_rotation_from_start_median",
                                              NC_DOUBLE,
                                              {dim::group},
                                              "degree",
                                              "median of the largest rotation from the initial heading over the group",
                                              true};
const Variable max_rotation_from_start_mean{"max_rotation_from_start_mean",
                                            NC_DOUBLE,
                                            {dim::group},
                                            "degree",
                                            "mean of the largest rotation from the initial heading over the group",
                                            true};
const Variable max_rotation_from_start_min{"max_rotation_from_start_min",
                                           NC_DOUBLE,
                                           {dim::group},
                                           "degree",
                                           "smallest of the largest rotation from the initial heading over the group",
                                           true};
const Variable max_rotation_from_start_max{"max_rotation_from_start_max",
                                           NC_DOUBLE,
                                           {dim::group},
                                           "degree",
                                           "largest of the largest rotation from the initial heading over the group",
                                           true};
const Variable rotation_direction_correlation{
    "rotation_direction_correlation",
    NC_DOUBLE,
    {dim::group},
    "1",
    "Pearson correlation of member_max_rotation_from_start and member_movement_direction over the group (paper Fig. 16c)",
    true};

const Variable member_region{"member_region", NC_INT, {dim::member}, "", "region index at arrival_time_s (-1: none)", false};
const Variable region_count{"region_count", NC_INT, group_region, "", "members inside the region at arrival_time_s", false};
const Variable region_count_by_param{"region_count_by_param",
                                     NC_INT,
                                     param_region,
                                     "",
                                     "members with this parameter set inside the region at arrival_time_s",
                                     false};

const Variable distance_mean{
    "distance_mean", NC_DOUBLE, param_time, "m", "mean distance of the centre from its start (over flows and perturbations)", true};
const Variable distance_std{"distance_std", NC_DOUBLE, param_time, "m", "standard deviation (n-1) of that distance", true};
const Variable relative_error{"relative_error",
                              NC_DOUBLE,
                              param_time,
                              "1",
                              "R(t) = (distance_mean - distance_mean of the control set) / distance_mean of the control set",
                              true};

const Variable building_id{"building_id", NC_INT, per_building, "", "the scene's building_id of the building", false};
const BuildingVariables building{
    {"building_hit_probability", NC_FLOAT, group_building, "1", "fraction of the group's trajectories that hit the building", false},
    {"building_first_hit_time", NC_DOUBLE, group_building, "s", "earliest impact on the building over the group", true},
    {"building_impact_count", NC_INT, group_building, "", "impacts on the building over the group", false},
    {"building_impact_speed_median", NC_DOUBLE, group_building, "m s-1", "median impact speed over the group's impacts", true},
    {"building_impact_speed_p90", NC_DOUBLE, group_building, "m s-1", "90th percentile of the impact speed (type 7)", true},
    {"building_impact_speed_max", NC_DOUBLE, group_building, "m s-1", "largest impact speed over the group's impacts", true},
    {"building_impact_force_median", NC_DOUBLE, group_building, "N", "median impact force over the group's impacts", true},
    {"building_impact_force_p90", NC_DOUBLE, group_building, "N", "90th percentile of the impact force (type 7)", true},
    {"building_impact_force_max", NC_DOUBLE, group_building, "N", "largest impact force over the group's impacts", true},
};
const BuildingVariables building_all{
    {"building_hit_probability_all", NC_FLOAT, per_building, "1", "fraction of all trajectories that hit the building", false},
    {"building_first_hit_time_all", NC_DOUBLE, per_building, "s", "earliest impact on the building", true},
    {"building_impact_count_all", NC_INT, per_building, "", "impacts on the building", false},
    {"building_impact_speed_median_all", NC_DOUBLE, per_building, "m s-1", "median impact speed", true},
    {"building_impact_speed_p90_all", NC_DOUBLE, per_building, "m s-1", "90th percentile of the impact speed (type 7)", true},
    {"building_impact_speed_max_all", NC_DOUBLE, per_building, "m s-1", "largest impact speed", true},
    {"building_impact_force_median_all", NC_DOUBLE, per_building, "N", "median impact force", true},
    {"building_impact_force_p90_all", NC_DOUBLE, per_building, "N", "90th percentile of the impact force (type 7)", true},
    {"building_impact_force_max_all", NC_DOUBLE, per_building, "N", "largest impact force", true},
};

const Variable pass_probability{
    "pass_probability", NC_FLOAT, group_map, "1", "fraction of the group's trajectories whose centre passes the cell", false};
const Variable max_debris_speed{
    "max_debris_speed", NC_FLOAT, group_map, "m s-1", "largest body speed in the cell over the group", true};
const Variable pass_probability_all{
    "pass_probability_all", NC_FLOAT, map, "1", "fraction of all trajectories whose centre passes the cell", false};
const Variable max_debris_speed_all{
    "max_debris_speed_all", NC_FLOAT, map, "m s-1", "largest body speed in the cell over all trajectories", true};

namespace {

// The file's variables in order: those of the schema, and the names of the others (no
// Variable).
struct Entry {
    std::string name;
    const Variable* variable;
};

std::vector<Entry> entries() {
    std::vector<Entry> e;
    auto add = [&](std::initializer_list<const Variable*> vars) {
        for (const Variable* v : vars) e.push_back({v->name, v});
    };
    auto add_names = [&](std::initializer_list<const char*> names) {
        for (const char* n : names) e.push_back({n, nullptr});
    };
    auto add_passages = [&](const PassageVariables& p) {
        add({&p.count, &p.y_mean, &p.y_median, &p.y_std, &p.speed_mean, &p.speed_median, &p.speed_std, &p.speed_bandwidth,
             &p.speed_kde});
    };
    add({&group_body, &group_variant, &group_members});
    add_names({param_set_label, param_set_is_control});
    add({&param_members, &section_name, &section_x, &section_y_min, &section_y_max, &region_name});
    add_passages(passage);
    add_passages(passage_by_param);
    add({&speed, &member_passage_time, &member_passage_y, &member_passage_speed});
    add({&yaw_bin, &yaw_bin_bounds, &max_rotation_histogram, &max_yaw_to_motion_histogram});
    add({&member_id, &member_group, &member_param_set, &member_flow});
    add({&member_motion_start, &member_max_rotation, &member_max_yaw_to_motion, &member_motion_direction});
    add({&member_max_rotation_from_start, &member_movement_direction, &max_rotation_from_start_histogram,
         &max_rotation_from_start_count, &max_rotation_from_start_median, &max_rotation_from_start_mean,
         &max_rotation_from_start_min, &max_rotation_from_start_max, &rotation_direction_correlation});
    add({&member_region, &region_count, &region_count_by_param});
    add_names({time});
    add({&distance_mean, &distance_std, &relative_error});
    add({&building_id});
    auto add_buildings = [&](const BuildingVariables& b) {
        add({&b.hit_probability, &b.first_hit_time, &b.impact_count, &b.speed_median, &b.speed_p90, &b.speed_max, &b.force_median,
             &b.force_p90, &b.force_max});
    };
    add_buildings(building);
    add_buildings(building_all);
    add_names({x, y});
    add({&pass_probability, &max_debris_speed, &pass_probability_all, &max_debris_speed_all});
    return e;
}

}  // namespace

const std::vector<const Variable*>& variables() {
    static const std::vector<const Variable*> list = [] {
        std::vector<const Variable*> l;
        for (const Entry& e : entries())
            if (e.variable) l.push_back(e.variable);
        return l;
    }();
    return list;
}

const std::vector<std::string>& variable_names() {
    static const std::vector<std::string> names = [] {
        std::vector<std::string> n;
        for (const Entry& e : entries()) n.push_back(e.name);
        return n;
    }();
    return names;
}

const std::vector<std::string>& attribute_names() {
    static const std::vector<std::string> names = {attribute::title,
                                                   attribute::source,
                                                   attribute::sweep_file,
                                                   attribute::scene_file,
                                                   attribute::scene_buildings_sha256,
                                                   attribute::history,
                                                   attribute::yaw_window,
                                                   attribute::yaw_min_speed,
                                                   attribute::motion_threshold,
                                                   attribute::arrival_time,
                                                   attribute::r_min_distance,
                                                   attribute::kde_bandwidth_rule,
                                                   attribute::kde_floor,
                                                   attribute::control_param_set,
                                                   attribute::map_coarsen};
    return names;
}

std::vector<std::string> csv_paths(const std::string& dir) {
    std::vector<std::string> paths;
    for (const char* name : {csv::sections, csv::speed_kde, csv::yaw_histogram, csv::rotation_from_start, csv::regions,
                             csv::distance, csv::members, csv::buildings})
        paths.push_back(dir + "/" + name);
    return paths;
}

Range range_of(const Variable& v) {
    const std::string name = v.name, unit = v.units;
    const auto has = [&](const char* part) { return name.find(part) != std::string::npos; };
    const double far = 1e8;  // [m] no projected coordinate reaches it
    if (unit == "1") {
        if (has("probability")) return Range::closed(0.0, 1.0, "1");
        if (has("correlation")) return Range::closed(-1.0, 1.0, "1");
        return Range::any("1");
    }
    if (unit == "m") return has("_std") || has("distance") ? Range::closed(0.0, far, "m") : Range::closed(-far, far, "m");
    if (unit == "m s-1") return Range::closed(0.0, 1000.0, "m s-1");
    if (unit == "s m-1" || unit == "N") return Range::non_negative(unit);
    if (unit == "degree") return Range::closed(-1e9, 1e9, "degree");
    if (unit == "s") return Range::any("s");
    if (name == member_region.name) return Range::at_least(-1.0);
    return Range::at_least(0.0);  // counts and indices
}

namespace {

std::vector<std::string> names_of(const std::vector<const char*>& dims) { return {dims.begin(), dims.end()}; }

// The values of `v` as stored, checked for their place, unit and range; NaN where missing.
std::vector<double> checked_values(const nc::File& f, const Variable& v) {
    const int id = f.var(v.name);
    const std::string label = std::string("variable '") + v.name + "'";
    if (f.value_dims(id) != names_of(v.dims)) {
        std::string want;
        for (const char* d : v.dims) want += (want.empty() ? "" : ", ") + std::string(d);
        fail(f.path(), label, "must be on dimensions (" + want + ")");
    }
    if (v.type == NC_CHAR) return {};
    const double factor = units::factor_to(f, id, v.units);
    std::vector<double> values = f.get_double(id);
    const std::optional<double> fill = f.att_double(id, "_FillValue");
    const Range range = range_of(v);
    for (std::size_t k = 0; k < values.size(); ++k) {
        const double raw = values[k];
        const bool missing = std::isfinite(raw) && (std::fabs(raw) >= 0.5 * cf::fill_value || (fill && raw == *fill));
        if (missing && v.fill) {
            values[k] = std::nan("");
            continue;
        }
        if (missing) fail(f.path(), label, "value at flat index " + std::to_string(k) + " is the fill value: this statistic is never missing");
        values[k] = raw * factor;
        if (const std::string problem = range_problem(values[k], range); !problem.empty())
            fail(f.path(), label, "value at flat index " + std::to_string(k) + ": " + problem);
    }
    return values;
}

}  // namespace

nc::File open_checked(const std::string& path, const std::string& option) {
    nc::File f = nc::File::open_read(path);
    cf::require_kind(f, {kind}, option);
    for (const Variable* v : {&pass_probability, &max_debris_speed, &group_body, &group_variant})
        if (!f.has_var(v->name)) fail(path, std::string("variable '") + v->name + "'", "missing: not a file written by `flotsam stats`");
    for (const Variable* v : variables())
        if (f.has_var(v->name)) (void)checked_values(f, *v);
    (void)map_grid(f);
    if (const auto c = f.att_double(NC_GLOBAL, attribute::map_coarsen))
        check_range(std::string("attribute '") + attribute::map_coarsen + "'", *c, Range::count(1, 1e6), path);
    return f;
}

std::vector<double> read_values(const nc::File& f, const Variable& v) { return checked_values(f, v); }

Grid map_grid(const nc::File& f) {
    std::vector<double> xs = nc::read_finite(f, x), ys = nc::read_finite(f, y);
    const double fx = units::length_factor(f, f.var(x)), fy = units::length_factor(f, f.var(y));
    for (double& a : xs) a *= fx;
    for (double& a : ys) a *= fy;
    return grid_from_coordinates(xs, ys, f.path());
}

}  // namespace flotsam::stats_file
