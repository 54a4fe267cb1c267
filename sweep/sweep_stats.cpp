#include "sweep/sweep_stats.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>

#include "common/atomic_file.hpp"
#include "common/cf.hpp"
#include "common/error.hpp"
#include "common/netcdf.hpp"
#include "sweep/trajectory_kernels.hpp"

namespace flotsam::sweep {

StatsDef default_stats_def() { return StatsDef{}; }

namespace {

const double nan = std::nan("");

SectionSummary summarise(std::vector<double> ys, std::vector<double> speeds, double kde_floor) {
    SectionSummary s;
    s.count = int(ys.size());
    std::sort(ys.begin(), ys.end());
    s.y_mean = mean_of(ys);
    s.y_median = quantile_sorted(ys, 0.5);
    s.y_std = std_of(ys);
    s.bandwidth = silverman_bandwidth(speeds, kde_floor);
    std::sort(speeds.begin(), speeds.end());
    s.speed_mean = mean_of(speeds);
    s.speed_median = quantile_sorted(speeds, 0.5);
    s.speed_std = std_of(speeds);
    return s;
}

void fill_kde(SectionSummary& s, const std::vector<double>& speeds, const std::vector<double>& axis) {
    s.kde.assign(axis.size(), 0.0);
    if (speeds.empty()) return;
    for (std::size_t k = 0; k < axis.size(); ++k) s.kde[k] = gaussian_kde(speeds, s.bandwidth, axis[k]);
}

// Marks the cells the centre path of one track crosses (sampled every quarter cell),
// with the largest speed there.
void rasterise(const debris::Track& t, const Grid& g, int stamp, std::vector<int>& last, std::vector<int>& count,
               std::vector<float>& vmax) {
    const double ds = 0.25 * std::min(g.dx, g.dy);
    auto visit = [&](double x, double y, double speed) {
        if (!g.contains(x, y)) return;
        const std::size_t c = g.index(g.cell_i(x), g.cell_j(y));
        if (last[c] != stamp) {
            last[c] = stamp;
            ++count[c];
        }
        if (std::isnan(vmax[c]) || float(speed) > vmax[c]) vmax[c] = float(speed);
    };
    for (std::size_t k = 0; k < t.x.size(); ++k) {
        const double s1 = std::hypot(t.u[k], t.v[k]);
        if (k == 0) {
            visit(t.x[0], t.y[0], s1);
            continue;
        }
        const double s0 = std::hypot(t.u[k - 1], t.v[k - 1]);
        const double len = std::hypot(t.x[k] - t.x[k - 1], t.y[k] - t.y[k - 1]);
        const int n = std::max(1, int(std::ceil(len / ds)));
        for (int q = 1; q <= n; ++q) {
            const double w = double(q) / n;
            visit(t.x[k - 1] + w * (t.x[k] - t.x[k - 1]), t.y[k - 1] + w * (t.y[k] - t.y[k - 1]), s0 + w * (s1 - s0));
        }
    }
}

}  // namespace

SweepStats compute_stats(const SweepResult& sw, const Scene& scene, const StatsDef& def) {
    if (sw.members.empty()) fail(sw.spec_file, "members", "the sweep holds no trajectories");
    if (sw.shard.count != 1)
        fail("--sweep", "shard " + std::to_string(sw.shard.index) + "/" + std::to_string(sw.shard.count),
             "a part of a sweep: merge the parts first (flotsam sweep merge)");
    if (def.map_coarsen < 1) fail("--map-coarsen", std::to_string(def.map_coarsen), "must be >= 1");
    SweepStats s;
    s.params = sw.params;
    for (std::size_t p = 0; p < sw.params.size(); ++p)
        if (sw.params[p].is_control && s.control < 0) s.control = int(p);
    s.sections = scene.sections;
    s.crs = scene.crs;
    for (const auto& r : scene.regions) s.regions.push_back(r.name);
    s.time = sw.time;
    const std::size_t nm = sw.members.size(), ns = s.sections.size(), np = s.params.size(), nr = s.regions.size(),
                      nt = s.time.size();

    // Groups: body × variant, in the sweep's table order.
    s.member_group.assign(nm, -1);
    for (std::size_t b = 0; b < sw.bodies.size(); ++b)
        for (std::size_t v = 0; v < sw.variants.size(); ++v) {
            SweepStats::Group g{sw.bodies[b], sw.variants[v], {}};
            for (std::size_t m = 0; m < nm; ++m)
                if (sw.members[m].body == int(b) && sw.members[m].variant == int(v)) {
                    g.members.push_back(int(m));
                    s.member_group[m] = int(s.groups.size());
                }
            if (!g.members.empty()) s.groups.push_back(g);
        }
    const std::size_t ng = s.groups.size();

    // Per member: motion start, yaw, passages, region at the arrival time.
    s.motion_start.assign(nm, nan);
    s.max_rotation.assign(nm, nan);
    s.max_yaw_to_motion.assign(nm, nan);
    s.motion_direction.assign(nm, nan);
    s.passage_time.assign(nm, std::vector<double>(ns, nan));
    s.passage_y = s.passage_time;
    s.passage_speed = s.passage_time;
    s.region_at_arrival.assign(nm, -1);
    for (const auto& m : sw.members) {
        s.member_id.push_back(m.id);
        s.member_param_set.push_back(m.param_set);
        s.member_flow.push_back(m.flow);
    }
    for (std::size_t m = 0; m < nm; ++m) {
        const debris::Track& t = sw.members[m].track;
        if (t.x.empty()) continue;
        const double scale = body_scale(sw.members[m].length);
        const int k0 = motion_start_index(t.x, t.y, motion_threshold * scale);
        if (k0 >= 0) {
            const double tm = s.time[std::size_t(k0)];
            s.motion_start[m] = tm;
            s.max_rotation[m] = max_rotation(s.time, t.yaw_deg, k0, def.yaw_window);
            s.max_yaw_to_motion[m] =
                max_yaw_to_motion(s.time, t.yaw_deg, t.u, t.v, k0, def.yaw_window, def.yaw_min_speed * std::sqrt(scale));
            const double xe = sample_at(s.time, t.x, tm + def.yaw_window), ye = sample_at(s.time, t.y, tm + def.yaw_window);
            s.motion_direction[m] = std::atan2(ye - t.y[0], xe - t.x[0]) * 180.0 / std::numbers::pi;
        }
        for (std::size_t c = 0; c < ns; ++c) {
            const Section& sec = s.sections[c];
            if (const auto p = first_passage(s.time, t.x, t.y, t.u, t.v, sec.x, sec.y_min, sec.y_max)) {
                s.passage_time[m][c] = p->time;
                s.passage_y[m][c] = p->y;
                s.passage_speed[m][c] = p->speed;
            }
        }
        const double xa = sample_at(s.time, t.x, def.arrival_time), ya = sample_at(s.time, t.y, def.arrival_time);
        for (std::size_t r = 0; r < nr; ++r)
            if (scene.regions[r].contains(xa, ya)) {
                s.region_at_arrival[m] = int(r);
                break;
            }
    }

    // Sections: summaries per group and per (group, parameter set), then one speed axis
    // for every density.
    auto collect = [&](const std::vector<int>& members, int param, std::size_t c, std::vector<double>& ys,
                       std::vector<double>& sp) {
        ys.clear();
        sp.clear();
        for (int m : members) {
            if (param >= 0 && sw.members[std::size_t(m)].param_set != param) continue;
            if (std::isnan(s.passage_y[std::size_t(m)][c])) continue;
            ys.push_back(s.passage_y[std::size_t(m)][c]);
            sp.push_back(s.passage_speed[std::size_t(m)][c]);
        }
    };
    std::vector<double> ys, sp;
    double top = 0.0;
    s.section.assign(ng, std::vector<SectionSummary>(ns));
    s.section_by_param.assign(ng, std::vector<std::vector<SectionSummary>>(np, std::vector<SectionSummary>(ns)));
    // The group's body sets the scale of its thresholds (trajectory_kernels.hpp).
    auto group_scale = [&](std::size_t g) { return body_scale(sw.members[std::size_t(s.groups[g].members.front())].length); };
    for (std::size_t g = 0; g < ng; ++g)
        for (std::size_t c = 0; c < ns; ++c) {
            const double kde_floor = def.kde_floor * std::sqrt(group_scale(g));
            collect(s.groups[g].members, -1, c, ys, sp);
            s.section[g][c] = summarise(ys, sp, kde_floor);
            for (double v : sp) top = std::max(top, v + 3.0 * s.section[g][c].bandwidth);
            for (std::size_t p = 0; p < np; ++p) {
                collect(s.groups[g].members, int(p), c, ys, sp);
                s.section_by_param[g][p][c] = summarise(ys, sp, kde_floor);
                for (double v : sp) top = std::max(top, v + 3.0 * s.section_by_param[g][p][c].bandwidth);
            }
        }
    if (!(top > 0)) top = 1.0;
    const int nk = std::max(2, def.kde_points);
    for (int k = 0; k < nk; ++k) s.speed.push_back(top * k / (nk - 1));
    for (std::size_t g = 0; g < ng; ++g)
        for (std::size_t c = 0; c < ns; ++c) {
            collect(s.groups[g].members, -1, c, ys, sp);
            fill_kde(s.section[g][c], sp, s.speed);
            for (std::size_t p = 0; p < np; ++p) {
                collect(s.groups[g].members, int(p), c, ys, sp);
                fill_kde(s.section_by_param[g][p][c], sp, s.speed);
            }
        }

    // Yaw histograms: bins over [−180, 180], values beyond in the end bins.
    const int nb = std::max(1, int(std::lround(360.0 / def.yaw_bin_width)));
    for (int b = 0; b <= nb; ++b) s.yaw_edges.push_back(-180.0 + 360.0 * b / nb);
    auto bin_of = [&](double a) { return std::clamp(int(std::floor((a + 180.0) / 360.0 * nb)), 0, nb - 1); };
    s.rotation_hist.assign(ng, std::vector<int>(std::size_t(nb), 0));
    s.yaw_motion_hist = s.rotation_hist;
    for (std::size_t m = 0; m < nm; ++m) {
        const int g = s.member_group[m];
        if (!std::isnan(s.max_rotation[m])) ++s.rotation_hist[std::size_t(g)][std::size_t(bin_of(s.max_rotation[m]))];
        if (!std::isnan(s.max_yaw_to_motion[m])) ++s.yaw_motion_hist[std::size_t(g)][std::size_t(bin_of(s.max_yaw_to_motion[m]))];
    }

    // Regions at the arrival time.
    s.region_count.assign(ng, std::vector<int>(nr, 0));
    s.region_count_by_param.assign(ng, std::vector<std::vector<int>>(np, std::vector<int>(nr, 0)));
    for (std::size_t m = 0; m < nm; ++m) {
        const int r = s.region_at_arrival[m];
        if (r < 0) continue;
        const std::size_t g = std::size_t(s.member_group[m]);
        ++s.region_count[g][std::size_t(r)];
        ++s.region_count_by_param[g][std::size_t(sw.members[m].param_set)][std::size_t(r)];
    }

    // Distance from the start, mean over the group's members with each parameter set (all
    // flows and perturbations), and R(t) against the control set.
    s.distance_mean.assign(ng, std::vector<std::vector<double>>(np, std::vector<double>(nt, nan)));
    s.distance_std = s.distance_mean;
    s.relative_error = s.distance_mean;
    s.param_members.assign(ng, std::vector<int>(np, 0));
    std::vector<double> d;
    for (std::size_t g = 0; g < ng; ++g) {
        for (std::size_t p = 0; p < np; ++p) {
            std::vector<int> ms;
            for (int m : s.groups[g].members)
                if (sw.members[std::size_t(m)].param_set == int(p)) ms.push_back(m);
            s.param_members[g][p] = int(ms.size());
            if (ms.empty()) continue;
            for (std::size_t k = 0; k < nt; ++k) {
                d.clear();
                for (int m : ms) {
                    const debris::Track& t = sw.members[std::size_t(m)].track;
                    d.push_back(std::hypot(t.x[k] - t.x[0], t.y[k] - t.y[0]));
                }
                s.distance_mean[g][p][k] = mean_of(d);
                s.distance_std[g][p][k] = std_of(d);
            }
        }
        if (s.control < 0) continue;
        const auto& dc = s.distance_mean[g][std::size_t(s.control)];
        const double r_min = def.r_min_distance * group_scale(g);
        for (std::size_t p = 0; p < np; ++p)
            for (std::size_t k = 0; k < nt; ++k)
                if (dc[k] >= r_min && !std::isnan(s.distance_mean[g][p][k]))
                    s.relative_error[g][p][k] = (s.distance_mean[g][p][k] - dc[k]) / dc[k];
    }

    // Maps on the scene grid (coarsened): probability of passing a cell, largest speed there.
    const Grid& sg = scene.grid;
    const int c = def.map_coarsen;
    s.map = Grid{(sg.nx + c - 1) / c,
                 (sg.ny + c - 1) / c,
                 sg.x_min_edge() + 0.5 * c * sg.dx,
                 sg.y_min_edge() + 0.5 * c * sg.dy,
                 c * sg.dx,
                 c * sg.dy};
    const std::size_t ncell = s.map.size();
    std::vector<int> last(ncell, -1), count_all(ncell, 0);
    s.max_speed_all.assign(ncell, nan);
    s.pass_probability.assign(ng, std::vector<float>(ncell, 0.0f));
    s.max_speed.assign(ng, std::vector<float>(ncell, float(nan)));
    for (std::size_t g = 0; g < ng; ++g) {
        std::vector<int> count(ncell, 0);
        for (int m : s.groups[g].members) {
            rasterise(sw.members[std::size_t(m)].track, s.map, m, last, count, s.max_speed[g]);
        }
        for (std::size_t k = 0; k < ncell; ++k) {
            s.pass_probability[g][k] = float(double(count[k]) / double(s.groups[g].members.size()));
            count_all[k] += count[k];
            if (!std::isnan(s.max_speed[g][k]) && (std::isnan(s.max_speed_all[k]) || s.max_speed[g][k] > s.max_speed_all[k]))
                s.max_speed_all[k] = s.max_speed[g][k];
        }
    }
    s.pass_probability_all.resize(ncell);
    for (std::size_t k = 0; k < ncell; ++k) s.pass_probability_all[k] = float(double(count_all[k]) / double(nm));
    return s;
}

// ---------------------------------------------------------------------------------------
// Output

void write_stats_file(const std::string& path, const SweepStats& s, const StatsDef& def, const std::string& sweep_file,
                      const std::string& scene_file, const std::string& history) {
    ensure_parent_dir(path);
    AtomicOutput out(path);
    {
        nc::File f = nc::File::create(out.temp_path());
        const std::size_t ng = s.groups.size(), np = s.params.size(), ns = s.sections.size(), nr = s.regions.size(),
                          nt = s.time.size(), nm = s.member_group.size(), nk = s.speed.size(), nb = s.yaw_edges.size() - 1;
        const int dg = f.def_dim("group", ng), dp = f.def_dim("param_set", np), dsec = f.def_dim("section", ns),
                  dreg = f.def_dim("region", nr), dsp = f.def_dim("speed", nk), dyaw = f.def_dim("yaw_bin", nb),
                  dbnd = f.def_dim("bnds", 2), dt = f.def_dim("time", nt), dm = f.def_dim("member", nm),
                  dx = f.def_dim("x", std::size_t(s.map.nx)), dy = f.def_dim("y", std::size_t(s.map.ny));
        const std::string grid_mapping = cf::grid_mapping_of(s.crs);
        // Variables over (..., y, x) are maps: they name the grid mapping.
        auto var = [&](const std::string& name, nc_type type, std::vector<int> dims, const char* units,
                       const std::string& long_name, bool fill = false) {
            const bool map = dims.size() >= 2 && dims[dims.size() - 2] == dy && dims.back() == dx;
            return cf::def_var(f, {.name = name,
                                   .type = type,
                                   .dims = std::move(dims),
                                   .units = units,
                                   .long_name = long_name,
                                   .fill = fill,
                                   .grid_mapping = map ? grid_mapping : std::string()});
        };
        // Tables.
        const int vgb = var("group_body", NC_STRING, {dg}, "", "body of the group");
        const int vgv = var("group_variant", NC_STRING, {dg}, "", "model variant of the group (friction + collision)");
        const int vgm = var("group_members", NC_INT, {dg}, "", "trajectories in the group");
        const ParameterSetVariables set_vars = define_parameter_set_variables(f, dp);
        const int vpm = var("param_members", NC_INT, {dg, dp}, "", "trajectories of the group with this parameter set");
        const int vsn = var("section_name", NC_STRING, {dsec}, "", "cross-section name");
        const int vsx = var("section_x", NC_DOUBLE, {dsec}, "m", "x of the north-south cross-section");
        const int vsy0 = var("section_y_min", NC_DOUBLE, {dsec}, "m", "south end of the cross-section");
        const int vsy1 = var("section_y_max", NC_DOUBLE, {dsec}, "m", "north end of the cross-section");
        const int vrn = var("region_name", NC_STRING, {dreg}, "", "region name");

        // Sections.
        struct SecVars {
            int count, ym, ymed, ystd, sm, smed, sstd, bw, kde;
        };
        auto sec_vars = [&](const std::string& suffix, std::vector<int> dims, const std::string& what) {
            SecVars v{};
            auto kdims = dims;
            kdims.push_back(dsp);
            v.count = var("passage_count" + suffix, NC_INT, dims, "", "trajectories passing the section" + what);
            v.ym = var("passage_y_mean" + suffix, NC_DOUBLE, dims, "m", "mean y of first passage" + what, true);
            v.ymed = var("passage_y_median" + suffix, NC_DOUBLE, dims, "m", "median y of first passage" + what, true);
            v.ystd = var("passage_y_std" + suffix, NC_DOUBLE, dims, "m", "standard deviation (n-1) of the passage y" + what, true);
            v.sm = var("passage_speed_mean" + suffix, NC_DOUBLE, dims, "m s-1", "mean body speed at passage" + what, true);
            v.smed = var("passage_speed_median" + suffix, NC_DOUBLE, dims, "m s-1", "median body speed at passage" + what, true);
            v.sstd = var("passage_speed_std" + suffix, NC_DOUBLE, dims, "m s-1",
                         "standard deviation (n-1) of the passage speed" + what, true);
            v.bw = var("passage_speed_bandwidth" + suffix, NC_DOUBLE, dims, "m s-1",
                       "Gaussian KDE bandwidth (Silverman's rule)" + what, true);
            v.kde =
                var("passage_speed_kde" + suffix, NC_DOUBLE, kdims, "s m-1", "Gaussian kernel density of the passage speed" + what);
            return v;
        };
        const SecVars va = sec_vars("", {dg, dsec}, " (all members of the group)");
        const SecVars vb = sec_vars("_by_param", {dg, dp, dsec}, " (members of the group with this parameter set)");
        const int vspeed = var("speed", NC_DOUBLE, {dsp}, "m s-1", "speed axis of the passage speed densities");
        const int vmt = var("member_passage_time", NC_DOUBLE, {dm, dsec}, "s", "time of first passage", true);
        const int vmy = var("member_passage_y", NC_DOUBLE, {dm, dsec}, "m", "y of first passage", true);
        const int vms = var("member_passage_speed", NC_DOUBLE, {dm, dsec}, "m s-1", "body speed at first passage", true);

        // Yaw.
        const int vyb = var("yaw_bin", NC_DOUBLE, {dyaw}, "degree", "bin centre");
        f.put_att(vyb, "bounds", std::string("yaw_bin_bounds"));
        const int vybb = var("yaw_bin_bounds", NC_DOUBLE, {dyaw, dbnd}, "degree", "bin edges");
        const int vhr = var("max_rotation_histogram", NC_INT, {dg, dyaw}, "",
                            "members per bin of the largest rotation from the heading at motion start, within yaw_window_s");
        const int vhm =
            var("max_yaw_to_motion_histogram", NC_INT, {dg, dyaw}, "",
                "members per bin of the largest angle of the long axis against the direction of motion, within yaw_window_s");
        const int vmid = var("member_id", NC_INT, {dm}, "", "member id in the sweep");
        const int vmg = var("member_group", NC_INT, {dm}, "", "group index");
        const int vmp = var("member_param_set", NC_INT, {dm}, "", "parameter set index");
        const int vmf = var("member_flow", NC_INT, {dm}, "", "flow index in the sweep");
        const int vm0 =
            var("member_motion_start", NC_DOUBLE, {dm}, "s", "first output time at least motion_threshold_m from the start", true);
        const int vmr = var("member_max_rotation", NC_DOUBLE, {dm}, "degree",
                            "largest rotation within yaw_window_s of motion start, counter-clockwise positive", true);
        const int vmy2 = var("member_max_yaw_to_motion", NC_DOUBLE, {dm}, "degree",
                             "largest long-axis angle against the velocity within yaw_window_s", true);
        const int vmd =
            var("member_motion_direction", NC_DOUBLE, {dm}, "degree",
                "direction from the start to the position yaw_window_s after motion start, from +x counter-clockwise", true);
        const int vmreg = var("member_region", NC_INT, {dm}, "", "region index at arrival_time_s (-1: none)");

        // Regions.
        const int vrc = var("region_count", NC_INT, {dg, dreg}, "", "members inside the region at arrival_time_s");
        const int vrcp = var("region_count_by_param", NC_INT, {dg, dp, dreg}, "",
                             "members with this parameter set inside the region at arrival_time_s");

        // Distance and R(t).
        const int vt = cf::def_time(f, dt, "time", "time");
        const int vdm = var("distance_mean", NC_DOUBLE, {dg, dp, dt}, "m",
                            "mean distance of the centre from its start (over flows and perturbations)", true);
        const int vds = var("distance_std", NC_DOUBLE, {dg, dp, dt}, "m", "standard deviation (n-1) of that distance", true);
        const int vre = var("relative_error", NC_DOUBLE, {dg, dp, dt}, "1",
                            "R(t) = (distance_mean - distance_mean of the control set) / distance_mean of the control set", true);

        // Maps.
        const cf::XYAxes map_axes = cf::def_xy(f, dx, dy, "map cell centre");
        cf::def_crs(f, s.crs);
        const int vpp = var("pass_probability", NC_FLOAT, {dg, dy, dx}, "1",
                            "fraction of the group's trajectories whose centre passes the cell");
        const int vmx =
            var("max_debris_speed", NC_FLOAT, {dg, dy, dx}, "m s-1", "largest body speed in the cell over the group", true);
        const int vppa =
            var("pass_probability_all", NC_FLOAT, {dy, dx}, "1", "fraction of all trajectories whose centre passes the cell");
        const int vmxa =
            var("max_debris_speed_all", NC_FLOAT, {dy, dx}, "m s-1", "largest body speed in the cell over all trajectories", true);

        cf::put_conventions(f);
        f.put_att(NC_GLOBAL, "title", std::string("flotsam sweep statistics"));
        f.put_att(NC_GLOBAL, "source", std::string("flotsam stats"));
        f.put_att(NC_GLOBAL, "sweep_file", sweep_file);
        f.put_att(NC_GLOBAL, "scene_file", scene_file);
        f.put_att(NC_GLOBAL, "history", history);
        f.put_att(NC_GLOBAL, "yaw_window_s", def.yaw_window);
        f.put_att(NC_GLOBAL, "yaw_min_speed_m_s", def.yaw_min_speed);
        f.put_att(NC_GLOBAL, "motion_threshold_m", motion_threshold);
        f.put_att(NC_GLOBAL, "arrival_time_s", def.arrival_time);
        f.put_att(NC_GLOBAL, "r_min_distance_m", def.r_min_distance);
        f.put_att(NC_GLOBAL, "kde_bandwidth_rule",
                  std::string("Silverman: h = 0.9 min(std, IQR/1.34) n^(-1/5); std alone when IQR = 0; max(0.1 |mean|, kde_floor) "
                              "when no spread"));
        f.put_att(NC_GLOBAL, "kde_floor_m_s", def.kde_floor);
        f.put_att(NC_GLOBAL, "control_param_set", s.control);
        f.put_att(NC_GLOBAL, "map_coarsen", def.map_coarsen);
        f.enddef();

        std::vector<std::string> gb, gv;
        std::vector<int> gm;
        for (const auto& g : s.groups) {
            gb.push_back(g.body);
            gv.push_back(g.variant);
            gm.push_back(int(g.members.size()));
        }
        f.put(vgb, gb);
        f.put(vgv, gv);
        f.put(vgm, gm);
        put_parameter_sets(f, set_vars, s.params);
        std::vector<int> pm;
        for (const auto& row : s.param_members) pm.insert(pm.end(), row.begin(), row.end());
        f.put(vpm, pm);
        std::vector<std::string> sn, rn = s.regions;
        std::vector<double> sx, sy0, sy1;
        for (const auto& c : s.sections) {
            sn.push_back(c.name);
            sx.push_back(c.x);
            sy0.push_back(c.y_min);
            sy1.push_back(c.y_max);
        }
        f.put(vsn, sn);
        f.put(vsx, sx);
        f.put(vsy0, sy0);
        f.put(vsy1, sy1);
        f.put(vrn, rn);

        auto put_sections = [&](const SecVars& v, const std::vector<const SectionSummary*>& list) {
            std::vector<int> count;
            std::vector<double> ym, ymed, ystd, sm, smed, sstd, bw, kde;
            for (const SectionSummary* q : list) {
                count.push_back(q->count);
                ym.push_back(q->y_mean);
                ymed.push_back(q->y_median);
                ystd.push_back(q->y_std);
                sm.push_back(q->speed_mean);
                smed.push_back(q->speed_median);
                sstd.push_back(q->speed_std);
                bw.push_back(q->bandwidth);
                kde.insert(kde.end(), q->kde.begin(), q->kde.end());
            }
            f.put(v.count, count);
            f.put(v.ym, cf::filled(ym));
            f.put(v.ymed, cf::filled(ymed));
            f.put(v.ystd, cf::filled(ystd));
            f.put(v.sm, cf::filled(sm));
            f.put(v.smed, cf::filled(smed));
            f.put(v.sstd, cf::filled(sstd));
            f.put(v.bw, cf::filled(bw));
            f.put(v.kde, kde);
        };
        std::vector<const SectionSummary*> la, lb;
        for (std::size_t g = 0; g < ng; ++g)
            for (std::size_t c = 0; c < ns; ++c) la.push_back(&s.section[g][c]);
        for (std::size_t g = 0; g < ng; ++g)
            for (std::size_t p = 0; p < np; ++p)
                for (std::size_t c = 0; c < ns; ++c) lb.push_back(&s.section_by_param[g][p][c]);
        put_sections(va, la);
        put_sections(vb, lb);
        f.put(vspeed, s.speed);
        auto flat = [](const std::vector<std::vector<double>>& a) {
            std::vector<double> o;
            for (const auto& r : a) o.insert(o.end(), r.begin(), r.end());
            return o;
        };
        f.put(vmt, cf::filled(flat(s.passage_time)));
        f.put(vmy, cf::filled(flat(s.passage_y)));
        f.put(vms, cf::filled(flat(s.passage_speed)));

        std::vector<double> centres, bounds;
        for (std::size_t b = 0; b < nb; ++b) {
            centres.push_back(0.5 * (s.yaw_edges[b] + s.yaw_edges[b + 1]));
            bounds.push_back(s.yaw_edges[b]);
            bounds.push_back(s.yaw_edges[b + 1]);
        }
        f.put(vyb, centres);
        f.put(vybb, bounds);
        std::vector<int> hr, hm;
        for (std::size_t g = 0; g < ng; ++g) {
            hr.insert(hr.end(), s.rotation_hist[g].begin(), s.rotation_hist[g].end());
            hm.insert(hm.end(), s.yaw_motion_hist[g].begin(), s.yaw_motion_hist[g].end());
        }
        f.put(vhr, hr);
        f.put(vhm, hm);
        f.put(vmid, s.member_id);
        f.put(vmg, s.member_group);
        f.put(vmp, s.member_param_set);
        f.put(vmf, s.member_flow);
        f.put(vm0, cf::filled(s.motion_start));
        f.put(vmr, cf::filled(s.max_rotation));
        f.put(vmy2, cf::filled(s.max_yaw_to_motion));
        f.put(vmd, cf::filled(s.motion_direction));
        f.put(vmreg, s.region_at_arrival);

        std::vector<int> rc, rcp;
        for (std::size_t g = 0; g < ng; ++g) {
            rc.insert(rc.end(), s.region_count[g].begin(), s.region_count[g].end());
            for (std::size_t p = 0; p < np; ++p)
                rcp.insert(rcp.end(), s.region_count_by_param[g][p].begin(), s.region_count_by_param[g][p].end());
        }
        f.put(vrc, rc);
        f.put(vrcp, rcp);
        f.put(vt, s.time);
        std::vector<double> dmv, dsv, rev;
        for (std::size_t g = 0; g < ng; ++g)
            for (std::size_t p = 0; p < np; ++p) {
                dmv.insert(dmv.end(), s.distance_mean[g][p].begin(), s.distance_mean[g][p].end());
                dsv.insert(dsv.end(), s.distance_std[g][p].begin(), s.distance_std[g][p].end());
                rev.insert(rev.end(), s.relative_error[g][p].begin(), s.relative_error[g][p].end());
            }
        f.put(vdm, cf::filled(dmv));
        f.put(vds, cf::filled(dsv));
        f.put(vre, cf::filled(rev));
        f.put(map_axes.x, s.map.xs());
        f.put(map_axes.y, s.map.ys());
        std::vector<float> pp, mx;
        for (std::size_t g = 0; g < ng; ++g) {
            pp.insert(pp.end(), s.pass_probability[g].begin(), s.pass_probability[g].end());
            mx.insert(mx.end(), s.max_speed[g].begin(), s.max_speed[g].end());
        }
        f.put(vpp, pp);
        f.put(vmx, cf::filled(mx));
        f.put(vppa, s.pass_probability_all);
        f.put(vmxa, cf::filled(s.max_speed_all));
        f.close();
    }
    out.commit();
}

namespace {

std::string num(double v) {
    if (std::isnan(v)) return "";
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.10g", v);
    return buf;
}

}  // namespace

void write_stats_csv(const std::string& dir, const SweepStats& s, const SweepResult& sw) {
    std::filesystem::create_directories(dir);
    const std::size_t ng = s.groups.size(), np = s.params.size(), ns = s.sections.size();
    {
        std::string t =
            "body,variant,param_label,section,x_m,count,y_mean_m,y_median_m,y_std_m,speed_mean_m_s,speed_median_m_s,speed_std_m_s,"
            "kde_bandwidth_m_s\n";
        std::string k = "body,variant,param_label,section,speed_m_s,density_s_m\n";
        auto row = [&](const SweepStats::Group& g, const std::string& label, std::size_t c, const SectionSummary& q) {
            t += g.body + "," + g.variant + "," + label + "," + s.sections[c].name + "," + num(s.sections[c].x) + "," +
                 std::to_string(q.count) + "," + num(q.y_mean) + "," + num(q.y_median) + "," + num(q.y_std) + "," +
                 num(q.speed_mean) + "," + num(q.speed_median) + "," + num(q.speed_std) + "," + num(q.bandwidth) + "\n";
            if (q.count == 0) return;
            for (std::size_t i = 0; i < s.speed.size(); ++i)
                k += g.body + "," + g.variant + "," + label + "," + s.sections[c].name + "," + num(s.speed[i]) + "," +
                     num(q.kde[i]) + "\n";
        };
        for (std::size_t g = 0; g < ng; ++g) {
            for (std::size_t c = 0; c < ns; ++c) row(s.groups[g], "all", c, s.section[g][c]);
            for (std::size_t p = 0; p < np; ++p)
                for (std::size_t c = 0; c < ns; ++c) row(s.groups[g], s.params[p].label, c, s.section_by_param[g][p][c]);
        }
        write_text_atomic(dir + "/sections.csv", t);
        write_text_atomic(dir + "/speed_kde.csv", k);
    }
    {
        std::string t = "body,variant,bin_min_deg,bin_max_deg,max_rotation_count,max_yaw_to_motion_count\n";
        for (std::size_t g = 0; g < ng; ++g)
            for (std::size_t b = 0; b + 1 < s.yaw_edges.size(); ++b)
                t += s.groups[g].body + "," + s.groups[g].variant + "," + num(s.yaw_edges[b]) + "," + num(s.yaw_edges[b + 1]) +
                     "," + std::to_string(s.rotation_hist[g][b]) + "," + std::to_string(s.yaw_motion_hist[g][b]) + "\n";
        write_text_atomic(dir + "/yaw_histogram.csv", t);
    }
    {
        std::string t = "body,variant,param_label,region,count,members\n";
        for (std::size_t g = 0; g < ng; ++g) {
            for (std::size_t r = 0; r < s.regions.size(); ++r)
                t += s.groups[g].body + "," + s.groups[g].variant + ",all," + s.regions[r] + "," +
                     std::to_string(s.region_count[g][r]) + "," + std::to_string(s.groups[g].members.size()) + "\n";
            for (std::size_t p = 0; p < np; ++p)
                for (std::size_t r = 0; r < s.regions.size(); ++r)
                    t += s.groups[g].body + "," + s.groups[g].variant + "," + s.params[p].label + "," + s.regions[r] + "," +
                         std::to_string(s.region_count_by_param[g][p][r]) + "," + std::to_string(s.param_members[g][p]) + "\n";
        }
        write_text_atomic(dir + "/regions.csv", t);
    }
    {
        std::string t = "body,variant,param_label,time_s,distance_mean_m,distance_std_m,relative_error\n";
        for (std::size_t g = 0; g < ng; ++g)
            for (std::size_t p = 0; p < np; ++p) {
                if (s.param_members[g][p] == 0) continue;
                for (std::size_t k = 0; k < s.time.size(); ++k)
                    t += s.groups[g].body + "," + s.groups[g].variant + "," + s.params[p].label + "," + num(s.time[k]) + "," +
                         num(s.distance_mean[g][p][k]) + "," + num(s.distance_std[g][p][k]) + "," + num(s.relative_error[g][p][k]) +
                         "\n";
            }
        write_text_atomic(dir + "/distance.csv", t);
    }
    {
        std::string t =
            "member,body,variant,param_label,flow,perturbation,motion_start_s,max_rotation_deg,max_yaw_to_motion_deg,"
            "motion_direction_deg,region_at_arrival";
        for (const auto& c : s.sections) t += "," + c.name + "_time_s," + c.name + "_y_m," + c.name + "_speed_m_s";
        t += "\n";
        for (std::size_t m = 0; m < s.member_group.size(); ++m) {
            const MemberRecord& r = sw.members[m];
            t += std::to_string(r.id) + "," + r.body_name + "," + r.variant_name + "," + s.params[std::size_t(r.param_set)].label +
                 "," + std::to_string(r.flow) + "," + std::to_string(r.perturbation) + "," + num(s.motion_start[m]) + "," +
                 num(s.max_rotation[m]) + "," + num(s.max_yaw_to_motion[m]) + "," + num(s.motion_direction[m]) + "," +
                 (s.region_at_arrival[m] >= 0 ? s.regions[std::size_t(s.region_at_arrival[m])] : std::string());
            for (std::size_t c = 0; c < ns; ++c)
                for (double v : {s.passage_time[m][c], s.passage_y[m][c], s.passage_speed[m][c]}) {
                    t += ',';
                    t += num(v);
                }
            t += "\n";
        }
        write_text_atomic(dir + "/members.csv", t);
    }
}

}  // namespace flotsam::sweep
