#include "sweep/sweep_stats.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <numbers>

#include "common/atomic_file.hpp"
#include "common/cf.hpp"
#include "common/columns.hpp"
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

// ---------------------------------------------------------------------------------------
// The statistics, one function each. Each fills its part of SweepStats from the sweep
// (and the parts filled before it: the groups, and the per-member values).

// Groups (body × variant, in the sweep's table order), the per-member table and the
// members per (group, parameter set).
void group_members(SweepStats& s, const SweepResult& sw) {
    const std::size_t nm = sw.members.size();
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
    s.member_id = column<int>(sw.members, &MemberRecord::id);
    s.member_param_set = column<int>(sw.members, &MemberRecord::param_set);
    s.member_flow = column<int>(sw.members, &MemberRecord::flow);
    s.param_members.assign(s.groups.size(), std::vector<int>(s.params.size(), 0));
    for (std::size_t g = 0; g < s.groups.size(); ++g)
        for (int m : s.groups[g].members) ++s.param_members[g][std::size_t(sw.members[std::size_t(m)].param_set)];
}

// Per member: motion start, and the yaw within yaw_window of it.
void yaw_per_member(SweepStats& s, const SweepResult& sw, const StatsDef& def) {
    const std::size_t nm = sw.members.size();
    s.motion_start.assign(nm, nan);
    s.max_rotation.assign(nm, nan);
    s.max_yaw_to_motion.assign(nm, nan);
    s.motion_direction.assign(nm, nan);
    for (std::size_t m = 0; m < nm; ++m) {
        const debris::Track& t = sw.members[m].track;
        if (t.x.empty()) continue;
        const double scale = body_scale(sw.members[m].def.length);  // thresholds follow the body (trajectory_kernels.hpp)
        const int k0 = motion_start_index(t.x, t.y, motion_threshold * scale);
        if (k0 < 0) continue;
        const double tm = s.time[std::size_t(k0)];
        s.motion_start[m] = tm;
        s.max_rotation[m] = max_rotation(s.time, t.yaw_deg, k0, def.yaw_window);
        s.max_yaw_to_motion[m] =
            max_yaw_to_motion(s.time, t.yaw_deg, t.u, t.v, k0, def.yaw_window, def.yaw_min_speed * std::sqrt(scale));
        const double xe = sample_at(s.time, t.x, tm + def.yaw_window), ye = sample_at(s.time, t.y, tm + def.yaw_window);
        s.motion_direction[m] = std::atan2(ye - t.y[0], xe - t.x[0]) * 180.0 / std::numbers::pi;
    }
}

// The bin of angle a among nb equal bins over [−180, 180] [degree]; beyond: the end bins.
std::size_t yaw_bin(double a, int nb) { return std::size_t(std::clamp(int(std::floor((a + 180.0) / 360.0 * nb)), 0, nb - 1)); }

// Histograms of the per-member yaw: bins over [−180, 180], values beyond in the end bins.
void yaw_histograms(SweepStats& s, const StatsDef& def) {
    const int nb = std::max(1, int(std::lround(360.0 / def.yaw_bin_width)));
    for (int b = 0; b <= nb; ++b) s.yaw_edges.push_back(-180.0 + 360.0 * b / nb);
    s.rotation_hist.assign(s.groups.size(), std::vector<int>(std::size_t(nb), 0));
    s.yaw_motion_hist = s.rotation_hist;
    for (std::size_t m = 0; m < s.member_group.size(); ++m) {
        const std::size_t g = std::size_t(s.member_group[m]);
        if (!std::isnan(s.max_rotation[m])) ++s.rotation_hist[g][yaw_bin(s.max_rotation[m], nb)];
        if (!std::isnan(s.max_yaw_to_motion[m])) ++s.yaw_motion_hist[g][yaw_bin(s.max_yaw_to_motion[m], nb)];
    }
}

// Per member, the paper's Fig. 16 quantities over [t0, t0 + yaw_window] with t0 the
// run's start: the largest rotation from the initial heading, and the direction of
// movement from the initial location.
void rotation_from_start_per_member(SweepStats& s, const SweepResult& sw, const StatsDef& def) {
    const std::size_t nm = sw.members.size();
    s.max_rotation_from_start.assign(nm, nan);
    s.movement_direction.assign(nm, nan);
    for (std::size_t m = 0; m < nm; ++m) {
        const debris::Track& t = sw.members[m].track;
        if (t.x.empty()) continue;
        s.max_rotation_from_start[m] = max_rotation(s.time, t.yaw_deg, 0, def.yaw_window);
        s.movement_direction[m] = movement_direction(s.time, t.x, t.y, s.time.front() + def.yaw_window);
    }
}

// Per group: the histogram of the largest rotation from the start (bins of
// yaw_histograms), its median, mean and range, and its correlation with the movement
// direction (Fig. 16c).
void rotation_from_start_summaries(SweepStats& s) {
    const int nb = int(s.yaw_edges.size()) - 1;
    s.rotation_from_start_hist.assign(s.groups.size(), std::vector<int>(std::size_t(nb), 0));
    s.rotation_from_start.assign(s.groups.size(), {});
    for (std::size_t g = 0; g < s.groups.size(); ++g) {
        std::vector<double> rotation, direction;
        for (int m : s.groups[g].members) {
            const double r = s.max_rotation_from_start[std::size_t(m)];
            if (std::isnan(r)) continue;
            ++s.rotation_from_start_hist[g][yaw_bin(r, nb)];
            rotation.push_back(r);
            direction.push_back(s.movement_direction[std::size_t(m)]);
        }
        SweepStats::RotationSummary& q = s.rotation_from_start[g];
        q.count = int(rotation.size());
        q.direction_correlation = pearson_correlation(rotation, direction);
        q.mean = mean_of(rotation);
        std::sort(rotation.begin(), rotation.end());
        q.median = quantile_sorted(rotation, 0.5);
        q.min = rotation.empty() ? nan : rotation.front();
        q.max = rotation.empty() ? nan : rotation.back();
    }
}

// Per member: the first passage of each section.
void passages_per_member(SweepStats& s, const SweepResult& sw) {
    const std::size_t nm = sw.members.size(), ns = s.sections.size();
    s.passage_time.assign(nm, std::vector<double>(ns, nan));
    s.passage_y = s.passage_time;
    s.passage_speed = s.passage_time;
    for (std::size_t m = 0; m < nm; ++m) {
        const debris::Track& t = sw.members[m].track;
        if (t.x.empty()) continue;
        for (std::size_t c = 0; c < ns; ++c) {
            const Section& sec = s.sections[c];
            if (const auto p = first_passage(s.time, t.x, t.y, t.u, t.v, sec.x, sec.y_min, sec.y_max)) {
                s.passage_time[m][c] = p->time;
                s.passage_y[m][c] = p->y;
                s.passage_speed[m][c] = p->speed;
            }
        }
    }
}

// The passage positions and speeds at section c of the members among `members` with
// parameter set `param` (−1: any).
void collect_passages(const SweepStats& s, const SweepResult& sw, const std::vector<int>& members, int param, std::size_t c,
                      std::vector<double>& ys, std::vector<double>& speeds) {
    ys.clear();
    speeds.clear();
    for (int m : members) {
        if (param >= 0 && sw.members[std::size_t(m)].param_set != param) continue;
        if (std::isnan(s.passage_y[std::size_t(m)][c])) continue;
        ys.push_back(s.passage_y[std::size_t(m)][c]);
        speeds.push_back(s.passage_speed[std::size_t(m)][c]);
    }
}

// The Froude scale of a group's thresholds: its body's (trajectory_kernels.hpp).
double group_scale(const SweepStats& s, const SweepResult& sw, std::size_t g) {
    return body_scale(sw.members[std::size_t(s.groups[g].members.front())].def.length);
}

// Calls f(summary, ys, speeds, group) for every section summary: per group, then per
// (group, parameter set).
template <class F>
void for_each_section_summary(SweepStats& s, const SweepResult& sw, F f) {
    std::vector<double> ys, speeds;
    for (std::size_t g = 0; g < s.groups.size(); ++g)
        for (std::size_t c = 0; c < s.sections.size(); ++c) {
            collect_passages(s, sw, s.groups[g].members, -1, c, ys, speeds);
            f(s.section[g][c], ys, speeds, g);
            for (std::size_t p = 0; p < s.params.size(); ++p) {
                collect_passages(s, sw, s.groups[g].members, int(p), c, ys, speeds);
                f(s.section_by_param[g][p][c], ys, speeds, g);
            }
        }
}

// Count, mean, median and standard deviation of the passage position and speed.
void section_summaries(SweepStats& s, const SweepResult& sw, const StatsDef& def) {
    const std::size_t ng = s.groups.size(), np = s.params.size(), ns = s.sections.size();
    s.section.assign(ng, std::vector<SectionSummary>(ns));
    s.section_by_param.assign(ng, std::vector<std::vector<SectionSummary>>(np, std::vector<SectionSummary>(ns)));
    for_each_section_summary(
        s, sw, [&](SectionSummary& q, const std::vector<double>& ys, const std::vector<double>& speeds, std::size_t g) {
            q = summarise(ys, speeds, def.kde_floor * std::sqrt(group_scale(s, sw, g)));
        });
}

// Kernel densities of the passage speed, all on one speed axis that reaches 3
// bandwidths beyond the fastest passage.
void speed_densities(SweepStats& s, const SweepResult& sw, const StatsDef& def) {
    double top = 0.0;
    for_each_section_summary(s, sw,
                             [&](SectionSummary& q, const std::vector<double>&, const std::vector<double>& speeds, std::size_t) {
                                 for (double v : speeds) top = std::max(top, v + 3.0 * q.bandwidth);
                             });
    if (!(top > 0)) top = 1.0;
    const int nk = std::max(2, def.kde_points);
    for (int k = 0; k < nk; ++k) s.speed.push_back(top * k / (nk - 1));
    for_each_section_summary(s, sw,
                             [&](SectionSummary& q, const std::vector<double>&, const std::vector<double>& speeds, std::size_t) {
                                 fill_kde(q, speeds, s.speed);
                             });
}

// Per member: the first region that holds the position at the arrival time.
void regions_per_member(SweepStats& s, const SweepResult& sw, const Scene& scene, const StatsDef& def) {
    s.region_at_arrival.assign(sw.members.size(), -1);
    for (std::size_t m = 0; m < sw.members.size(); ++m) {
        const debris::Track& t = sw.members[m].track;
        if (t.x.empty()) continue;
        const double xa = sample_at(s.time, t.x, def.arrival_time), ya = sample_at(s.time, t.y, def.arrival_time);
        for (std::size_t r = 0; r < scene.regions.size(); ++r)
            if (scene.regions[r].contains(xa, ya)) {
                s.region_at_arrival[m] = int(r);
                break;
            }
    }
}

// Members per region at the arrival time, per group and per (group, parameter set).
void region_counts(SweepStats& s, const SweepResult& sw) {
    const std::size_t ng = s.groups.size(), np = s.params.size(), nr = s.regions.size();
    s.region_count.assign(ng, std::vector<int>(nr, 0));
    s.region_count_by_param.assign(ng, std::vector<std::vector<int>>(np, std::vector<int>(nr, 0)));
    for (std::size_t m = 0; m < s.region_at_arrival.size(); ++m) {
        const int r = s.region_at_arrival[m];
        if (r < 0) continue;
        const std::size_t g = std::size_t(s.member_group[m]);
        ++s.region_count[g][std::size_t(r)];
        ++s.region_count_by_param[g][std::size_t(sw.members[m].param_set)][std::size_t(r)];
    }
}

// Distance from the start, mean over the group's members with each parameter set (all
// flows and perturbations), and R(t) against the control set.
void distance_statistics(SweepStats& s, const SweepResult& sw, const StatsDef& def) {
    const std::size_t ng = s.groups.size(), np = s.params.size(), nt = s.time.size();
    s.distance_mean.assign(ng, std::vector<std::vector<double>>(np, std::vector<double>(nt, nan)));
    s.distance_std = s.distance_mean;
    s.relative_error = s.distance_mean;
    std::vector<double> d;
    for (std::size_t g = 0; g < ng; ++g) {
        for (std::size_t p = 0; p < np; ++p) {
            std::vector<const debris::Track*> tracks;
            for (int m : s.groups[g].members)
                if (sw.members[std::size_t(m)].param_set == int(p)) tracks.push_back(&sw.members[std::size_t(m)].track);
            if (tracks.empty()) continue;
            for (std::size_t k = 0; k < nt; ++k) {
                d.clear();
                for (const debris::Track* t : tracks) d.push_back(std::hypot(t->x[k] - t->x[0], t->y[k] - t->y[0]));
                s.distance_mean[g][p][k] = mean_of(d);
                s.distance_std[g][p][k] = std_of(d);
            }
        }
        if (s.control < 0) continue;
        const auto& dc = s.distance_mean[g][std::size_t(s.control)];
        const double r_min = def.r_min_distance * group_scale(s, sw, g);
        for (std::size_t p = 0; p < np; ++p)
            for (std::size_t k = 0; k < nt; ++k)
                if (dc[k] >= r_min && !std::isnan(s.distance_mean[g][p][k]))
                    s.relative_error[g][p][k] = (s.distance_mean[g][p][k] - dc[k]) / dc[k];
    }
}

// Maps on the scene grid (coarsened): probability of passing a cell, largest speed there.
void pass_maps(SweepStats& s, const SweepResult& sw, const Scene& scene, const StatsDef& def) {
    const Grid& sg = scene.grid;
    const int c = def.map_coarsen;
    s.map = Grid{(sg.nx + c - 1) / c,
                 (sg.ny + c - 1) / c,
                 sg.x_min_edge() + 0.5 * c * sg.dx,
                 sg.y_min_edge() + 0.5 * c * sg.dy,
                 c * sg.dx,
                 c * sg.dy};
    const std::size_t ncell = s.map.size(), ng = s.groups.size();
    std::vector<int> last(ncell, -1), count_all(ncell, 0);
    s.max_speed_all.assign(ncell, nan);
    s.pass_probability.assign(ng, std::vector<float>(ncell, 0.0f));
    s.max_speed.assign(ng, std::vector<float>(ncell, float(nan)));
    for (std::size_t g = 0; g < ng; ++g) {
        std::vector<int> count(ncell, 0);
        for (int m : s.groups[g].members) rasterise(sw.members[std::size_t(m)].track, s.map, m, last, count, s.max_speed[g]);
        for (std::size_t k = 0; k < ncell; ++k) {
            s.pass_probability[g][k] = float(double(count[k]) / double(s.groups[g].members.size()));
            count_all[k] += count[k];
            if (!std::isnan(s.max_speed[g][k]) && (std::isnan(s.max_speed_all[k]) || s.max_speed[g][k] > s.max_speed_all[k]))
                s.max_speed_all[k] = s.max_speed[g][k];
        }
    }
    s.pass_probability_all.resize(ncell);
    for (std::size_t k = 0; k < ncell; ++k) s.pass_probability_all[k] = float(double(count_all[k]) / double(sw.members.size()));
}

}  // namespace

SweepStats compute_stats(const SweepResult& sw, const Scene& scene, const StatsDef& def) {
    if (sw.members.empty())
        fail(sw.path.empty() ? "--sweep" : sw.path, "dimension 'trajectory'",
             "the sweep file holds no trajectories (0 members): statistics need at least one");
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
    s.scene_buildings_sha256 = scene_buildings_sha256(scene);
    for (const auto& r : scene.regions) s.regions.push_back(r.name);
    s.time = sw.time;

    group_members(s, sw);
    yaw_per_member(s, sw, def);
    yaw_histograms(s, def);
    rotation_from_start_per_member(s, sw, def);
    rotation_from_start_summaries(s);
    passages_per_member(s, sw);
    section_summaries(s, sw, def);
    speed_densities(s, sw, def);
    regions_per_member(s, sw, scene, def);
    region_counts(s, sw);
    distance_statistics(s, sw, def);
    pass_maps(s, sw, scene, def);
    return s;
}

// ---------------------------------------------------------------------------------------
// The statistics file: one function per statistic defines its variables and returns the
// step that writes their values once the file leaves define mode. The variables are
// defined in the order of the calls in write_stats_file (the file's layout).

namespace {

struct StatsDims {
    int group, param_set, section, region, speed, yaw_bin, bnds, time, member, x, y;
    std::string grid_mapping;  // of the maps (over ..., y, x); "" without a CRS
};

using PutValues = std::function<void()>;

int def_stats_var(nc::File& f, const std::string& name, nc_type type, std::vector<int> dims, const char* units,
                  const std::string& long_name, bool fill = false) {
    return cf::def_var(f,
                       {.name = name, .type = type, .dims = std::move(dims), .units = units, .long_name = long_name, .fill = fill});
}

// Strings, as a character array as long as the longest of `values`.
int def_stats_text(nc::File& f, const std::string& name, int dim, const std::vector<std::string>& values,
                   const std::string& long_name) {
    return cf::def_var(f, {.name = name, .type = NC_CHAR, .dims = {dim}, .long_name = long_name, .text_length = cf::longest(values)});
}

// Groups, parameter sets, sections and regions.
PutValues define_tables(nc::File& f, const StatsDims& d, const SweepStats& s) {
    const int vgb = def_stats_text(f, "group_body", d.group, column<std::string>(s.groups, &SweepStats::Group::body), "body of the group");
    const int vgv = def_stats_text(f, "group_variant", d.group, column<std::string>(s.groups, &SweepStats::Group::variant),
                                   "model variant of the group (friction + collision)");
    const int vgm = def_stats_var(f, "group_members", NC_INT, {d.group}, "", "trajectories in the group");
    const ParameterSetVariables set_vars = define_parameter_set_variables(f, d.param_set, s.params);
    const int vpm =
        def_stats_var(f, "param_members", NC_INT, {d.group, d.param_set}, "", "trajectories of the group with this parameter set");
    const int vsn = def_stats_text(f, "section_name", d.section, column<std::string>(s.sections, &Section::name), "cross-section name");
    const int vsx = def_stats_var(f, "section_x", NC_DOUBLE, {d.section}, "m", "x of the north-south cross-section");
    const int vsy0 = def_stats_var(f, "section_y_min", NC_DOUBLE, {d.section}, "m", "south end of the cross-section");
    const int vsy1 = def_stats_var(f, "section_y_max", NC_DOUBLE, {d.section}, "m", "north end of the cross-section");
    const int vrn = def_stats_text(f, "region_name", d.region, s.regions, "region name");
    return [=, &f, &s] {
        f.put(vgb, column<std::string>(s.groups, &SweepStats::Group::body));
        f.put(vgv, column<std::string>(s.groups, &SweepStats::Group::variant));
        f.put(vgm, column<int>(s.groups, [](const SweepStats::Group& g) { return g.members.size(); }));
        put_parameter_sets(f, set_vars, s.params);
        f.put(vpm, flatten(s.param_members));
        f.put(vsn, column<std::string>(s.sections, &Section::name));
        f.put(vsx, column<double>(s.sections, &Section::x));
        f.put(vsy0, column<double>(s.sections, &Section::y_min));
        f.put(vsy1, column<double>(s.sections, &Section::y_max));
        f.put(vrn, s.regions);
    };
}

// One set of section-summary variables (passage_count<suffix>, ...) over `dims`.
PutValues define_section_summaries(nc::File& f, const StatsDims& d, const std::string& suffix, std::vector<int> dims,
                                   const std::string& what, std::vector<const SectionSummary*> list) {
    auto var = [&](const std::string& name, nc_type type, std::vector<int> vd, const char* units, const std::string& long_name,
                   bool fill = false) {
        return def_stats_var(f, name + suffix, type, std::move(vd), units, long_name + what, fill);
    };
    auto kdims = dims;
    kdims.push_back(d.speed);
    const int count = var("passage_count", NC_INT, dims, "", "trajectories passing the section");
    const int ym = var("passage_y_mean", NC_DOUBLE, dims, "m", "mean y of first passage", true);
    const int ymed = var("passage_y_median", NC_DOUBLE, dims, "m", "median y of first passage", true);
    const int ystd = var("passage_y_std", NC_DOUBLE, dims, "m", "standard deviation (n-1) of the passage y", true);
    const int sm = var("passage_speed_mean", NC_DOUBLE, dims, "m s-1", "mean body speed at passage", true);
    const int smed = var("passage_speed_median", NC_DOUBLE, dims, "m s-1", "median body speed at passage", true);
    const int sstd = var("passage_speed_std", NC_DOUBLE, dims, "m s-1", "standard deviation (n-1) of the passage speed", true);
    const int bw = var("passage_speed_bandwidth", NC_DOUBLE, dims, "m s-1", "Gaussian KDE bandwidth (Silverman's rule)", true);
    const int kde = var("passage_speed_kde", NC_DOUBLE, kdims, "s m-1", "Gaussian kernel density of the passage speed");
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
    const PutValues put_a = define_section_summaries(f, d, "", {d.group, d.section}, " (all members of the group)", by_group);
    const PutValues put_b = define_section_summaries(f, d, "_by_param", {d.group, d.param_set, d.section},
                                                     " (members of the group with this parameter set)", by_param);
    const int vspeed = def_stats_var(f, "speed", NC_DOUBLE, {d.speed}, "m s-1", "speed axis of the passage speed densities");
    const int vmt = def_stats_var(f, "member_passage_time", NC_DOUBLE, {d.member, d.section}, "s", "time of first passage", true);
    const int vmy = def_stats_var(f, "member_passage_y", NC_DOUBLE, {d.member, d.section}, "m", "y of first passage", true);
    const int vms =
        def_stats_var(f, "member_passage_speed", NC_DOUBLE, {d.member, d.section}, "m s-1", "body speed at first passage", true);
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
    const int vyb = def_stats_var(f, "yaw_bin", NC_DOUBLE, {d.yaw_bin}, "degree", "bin centre");
    f.put_att(vyb, "bounds", std::string("yaw_bin_bounds"));
    const int vybb = def_stats_var(f, "yaw_bin_bounds", NC_DOUBLE, {d.yaw_bin, d.bnds}, "degree", "bin edges");
    const int vhr = def_stats_var(f, "max_rotation_histogram", NC_INT, {d.group, d.yaw_bin}, "",
                                  "members per bin of the largest rotation from the heading at motion start, within yaw_window_s");
    const int vhm =
        def_stats_var(f, "max_yaw_to_motion_histogram", NC_INT, {d.group, d.yaw_bin}, "",
                      "members per bin of the largest angle of the long axis against the direction of motion, within yaw_window_s");
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
    const int vmid = def_stats_var(f, "member_id", NC_INT, {d.member}, "", "member id in the sweep");
    const int vmg = def_stats_var(f, "member_group", NC_INT, {d.member}, "", "group index");
    const int vmp = def_stats_var(f, "member_param_set", NC_INT, {d.member}, "", "parameter set index");
    const int vmf = def_stats_var(f, "member_flow", NC_INT, {d.member}, "", "flow index in the sweep");
    return [=, &f, &s] {
        f.put(vmid, s.member_id);
        f.put(vmg, s.member_group);
        f.put(vmp, s.member_param_set);
        f.put(vmf, s.member_flow);
    };
}

// Each member's motion start and yaw after it.
PutValues define_member_yaw(nc::File& f, const StatsDims& d, const SweepStats& s) {
    const int vm0 = def_stats_var(f, "member_motion_start", NC_DOUBLE, {d.member}, "s",
                                  "first output time at least motion_threshold_m from the start", true);
    const int vmr = def_stats_var(f, "member_max_rotation", NC_DOUBLE, {d.member}, "degree",
                                  "largest rotation within yaw_window_s of motion start, counter-clockwise positive", true);
    const int vmy2 = def_stats_var(f, "member_max_yaw_to_motion", NC_DOUBLE, {d.member}, "degree",
                                   "largest long-axis angle against the velocity within yaw_window_s", true);
    const int vmd =
        def_stats_var(f, "member_motion_direction", NC_DOUBLE, {d.member}, "degree",
                      "direction from the start to the position yaw_window_s after motion start, from +x counter-clockwise", true);
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
    const int vmr = def_stats_var(f, "member_max_rotation_from_start", NC_DOUBLE, {d.member}, "degree",
                                  "largest rotation from the initial heading within yaw_window_s of the run's start (paper Fig. "
                                  "16a), counter-clockwise positive",
                                  true);
    const int vmd =
        def_stats_var(f, "member_movement_direction", NC_DOUBLE, {d.member}, "degree",
                      "direction from the initial location to the position yaw_window_s after the run's start, from "
                      "east counter-clockwise: north-east positive (paper Fig. 16c); undefined below motion_threshold_m",
                      true);
    const int vh = def_stats_var(f, "max_rotation_from_start_histogram", NC_INT, {d.group, d.yaw_bin}, "",
                                 "members per bin of the largest rotation from the initial heading within yaw_window_s of the "
                                 "run's start");
    const int vn =
        def_stats_var(f, "max_rotation_from_start_count", NC_INT, {d.group}, "", "members with a largest rotation from the start");
    auto summary = [&](const char* name, const char* what) {
        return def_stats_var(f, std::string("max_rotation_from_start_") + name, NC_DOUBLE, {d.group}, "degree",
                             std::string(what) + " of the largest rotation from the initial heading over the group", true);
    };
    const int vmed = summary("median", "median"), vmean = summary("mean", "mean"), vmin = summary("min", "smallest"),
              vmax = summary("max", "largest");
    const int vr = def_stats_var(f, "rotation_direction_correlation", NC_DOUBLE, {d.group}, "1",
                                 "Pearson correlation of member_max_rotation_from_start and member_movement_direction over the "
                                 "group (paper Fig. 16c)",
                                 true);
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
    const int vmreg = def_stats_var(f, "member_region", NC_INT, {d.member}, "", "region index at arrival_time_s (-1: none)");
    const int vrc =
        def_stats_var(f, "region_count", NC_INT, {d.group, d.region}, "", "members inside the region at arrival_time_s");
    const int vrcp = def_stats_var(f, "region_count_by_param", NC_INT, {d.group, d.param_set, d.region}, "",
                                   "members with this parameter set inside the region at arrival_time_s");
    return [=, &f, &s] {
        f.put(vmreg, s.region_at_arrival);
        f.put(vrc, flatten(s.region_count));
        f.put(vrcp, flatten(s.region_count_by_param));
    };
}

// Distance from the start and R(t) per (group, parameter set).
PutValues define_distance(nc::File& f, const StatsDims& d, const SweepStats& s) {
    const int vt = cf::def_time(f, d.time, "time", "time");
    const std::vector<int> dims = {d.group, d.param_set, d.time};
    const int vdm = def_stats_var(f, "distance_mean", NC_DOUBLE, dims, "m",
                                  "mean distance of the centre from its start (over flows and perturbations)", true);
    const int vds = def_stats_var(f, "distance_std", NC_DOUBLE, dims, "m", "standard deviation (n-1) of that distance", true);
    const int vre =
        def_stats_var(f, "relative_error", NC_DOUBLE, dims, "1",
                      "R(t) = (distance_mean - distance_mean of the control set) / distance_mean of the control set", true);
    return [=, &f, &s] {
        f.put(vt, s.time);
        f.put(vdm, cf::filled(flatten(s.distance_mean)));
        f.put(vds, cf::filled(flatten(s.distance_std)));
        f.put(vre, cf::filled(flatten(s.relative_error)));
    };
}

// The probability and largest-speed maps.
PutValues define_maps(nc::File& f, const StatsDims& d, const SweepStats& s) {
    const cf::XYAxes axes = cf::def_xy(f, d.x, d.y, "map cell centre");
    cf::def_crs(f, s.crs);
    // Maps name the grid mapping, so GIS tools place them.
    auto map = [&](const std::string& name, std::vector<int> dims, const char* units, const std::string& long_name, bool fill) {
        return cf::def_var(f, {.name = name,
                               .type = NC_FLOAT,
                               .dims = std::move(dims),
                               .units = units,
                               .long_name = long_name,
                               .fill = fill,
                               .grid_mapping = d.grid_mapping});
    };
    const int vpp = map("pass_probability", {d.group, d.y, d.x}, "1",
                        "fraction of the group's trajectories whose centre passes the cell", false);
    const int vmx = map("max_debris_speed", {d.group, d.y, d.x}, "m s-1", "largest body speed in the cell over the group", true);
    const int vppa =
        map("pass_probability_all", {d.y, d.x}, "1", "fraction of all trajectories whose centre passes the cell", false);
    const int vmxa = map("max_debris_speed_all", {d.y, d.x}, "m s-1", "largest body speed in the cell over all trajectories", true);
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
    cf::put_conventions(f);
    cf::put_kind(f, "stats");
    f.put_att(NC_GLOBAL, "title", std::string("flotsam sweep statistics"));
    f.put_att(NC_GLOBAL, "source", std::string("flotsam stats"));
    f.put_att(NC_GLOBAL, "sweep_file", sweep_file);
    f.put_att(NC_GLOBAL, "scene_file", scene_file);
    f.put_att(NC_GLOBAL, "scene_buildings_sha256", s.scene_buildings_sha256);
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
}

}  // namespace

void write_stats_file(const std::string& path, const SweepStats& s, const StatsDef& def, const std::string& sweep_file,
                      const std::string& scene_file, const std::string& history) {
    ensure_parent_dir(path);
    AtomicOutput out(path);
    {
        nc::File f = nc::File::create(out.temp_path());
        const StatsDims d{f.def_dim("group", s.groups.size()),
                          f.def_dim("param_set", s.params.size()),
                          f.def_dim("section", s.sections.size()),
                          f.def_dim("region", s.regions.size()),
                          f.def_dim("speed", s.speed.size()),
                          f.def_dim("yaw_bin", s.yaw_edges.size() - 1),
                          f.def_dim("bnds", 2),
                          f.def_dim("time", s.time.size()),
                          f.def_dim("member", s.member_group.size()),
                          f.def_dim("x", std::size_t(s.map.nx)),
                          f.def_dim("y", std::size_t(s.map.ny)),
                          cf::grid_mapping_of(s.crs)};
        const std::vector<PutValues> puts = {
            define_tables(f, d, s),       define_passages(f, d, s),   define_yaw_histograms(f, d, s),
            define_member_table(f, d, s), define_member_yaw(f, d, s), define_rotation_from_start(f, d, s),
            define_regions(f, d, s),      define_distance(f, d, s),   define_maps(f, d, s)};
        put_settings(f, s, def, sweep_file, scene_file, history);
        f.enddef();
        for (const PutValues& put : puts) put();
        f.close();
    }
    out.commit();
}

// ---------------------------------------------------------------------------------------
// CSV tables, one function per statistic.

namespace {

std::string num(double v) {
    if (std::isnan(v)) return "";
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.10g", v);
    return buf;
}

std::string group_key(const SweepStats::Group& g) { return g.body + "," + g.variant; }

// sections.csv (one row per group × section with param_label "all", then per parameter
// set) and speed_kde.csv (long format).
void write_sections_csv(const std::string& dir, const SweepStats& s) {
    std::string t =
        "body,variant,param_label,section,x_m,count,y_mean_m,y_median_m,y_std_m,speed_mean_m_s,speed_median_m_s,speed_std_m_s,"
        "kde_bandwidth_m_s\n";
    std::string k = "body,variant,param_label,section,speed_m_s,density_s_m\n";
    auto row = [&](const SweepStats::Group& g, const std::string& label, std::size_t c, const SectionSummary& q) {
        const std::string key = group_key(g) + "," + label + "," + s.sections[c].name + ",";
        t += key + num(s.sections[c].x) + "," + std::to_string(q.count) + "," + num(q.y_mean) + "," + num(q.y_median) + "," +
             num(q.y_std) + "," + num(q.speed_mean) + "," + num(q.speed_median) + "," + num(q.speed_std) + "," + num(q.bandwidth) +
             "\n";
        if (q.count == 0) return;
        for (std::size_t i = 0; i < s.speed.size(); ++i) k += key + num(s.speed[i]) + "," + num(q.kde[i]) + "\n";
    };
    for (std::size_t g = 0; g < s.groups.size(); ++g) {
        for (std::size_t c = 0; c < s.sections.size(); ++c) row(s.groups[g], "all", c, s.section[g][c]);
        for (std::size_t p = 0; p < s.params.size(); ++p)
            for (std::size_t c = 0; c < s.sections.size(); ++c) row(s.groups[g], s.params[p].label, c, s.section_by_param[g][p][c]);
    }
    write_text_atomic(dir + "/sections.csv", t);
    write_text_atomic(dir + "/speed_kde.csv", k);
}

void write_yaw_csv(const std::string& dir, const SweepStats& s) {
    std::string t =
        "body,variant,bin_min_deg,bin_max_deg,max_rotation_count,max_yaw_to_motion_count,max_rotation_from_start_count\n";
    for (std::size_t g = 0; g < s.groups.size(); ++g)
        for (std::size_t b = 0; b + 1 < s.yaw_edges.size(); ++b)
            t += group_key(s.groups[g]) + "," + num(s.yaw_edges[b]) + "," + num(s.yaw_edges[b + 1]) + "," +
                 std::to_string(s.rotation_hist[g][b]) + "," + std::to_string(s.yaw_motion_hist[g][b]) + "," +
                 std::to_string(s.rotation_from_start_hist[g][b]) + "\n";
    write_text_atomic(dir + "/yaw_histogram.csv", t);
}

// rotation_from_start.csv: the paper's Fig. 16 per group.
void write_rotation_csv(const std::string& dir, const SweepStats& s) {
    std::string t =
        "body,variant,count,max_rotation_median_deg,max_rotation_mean_deg,max_rotation_min_deg,max_rotation_max_deg,"
        "direction_correlation\n";
    for (std::size_t g = 0; g < s.groups.size(); ++g) {
        const SweepStats::RotationSummary& q = s.rotation_from_start[g];
        t += group_key(s.groups[g]) + "," + std::to_string(q.count) + "," + num(q.median) + "," + num(q.mean) + "," + num(q.min) +
             "," + num(q.max) + "," + num(q.direction_correlation) + "\n";
    }
    write_text_atomic(dir + "/rotation_from_start.csv", t);
}

void write_regions_csv(const std::string& dir, const SweepStats& s) {
    std::string t = "body,variant,param_label,region,count,members\n";
    for (std::size_t g = 0; g < s.groups.size(); ++g) {
        for (std::size_t r = 0; r < s.regions.size(); ++r)
            t += group_key(s.groups[g]) + ",all," + s.regions[r] + "," + std::to_string(s.region_count[g][r]) + "," +
                 std::to_string(s.groups[g].members.size()) + "\n";
        for (std::size_t p = 0; p < s.params.size(); ++p)
            for (std::size_t r = 0; r < s.regions.size(); ++r)
                t += group_key(s.groups[g]) + "," + s.params[p].label + "," + s.regions[r] + "," +
                     std::to_string(s.region_count_by_param[g][p][r]) + "," + std::to_string(s.param_members[g][p]) + "\n";
    }
    write_text_atomic(dir + "/regions.csv", t);
}

void write_distance_csv(const std::string& dir, const SweepStats& s) {
    std::string t = "body,variant,param_label,time_s,distance_mean_m,distance_std_m,relative_error\n";
    for (std::size_t g = 0; g < s.groups.size(); ++g)
        for (std::size_t p = 0; p < s.params.size(); ++p) {
            if (s.param_members[g][p] == 0) continue;
            for (std::size_t k = 0; k < s.time.size(); ++k)
                t += group_key(s.groups[g]) + "," + s.params[p].label + "," + num(s.time[k]) + "," + num(s.distance_mean[g][p][k]) +
                     "," + num(s.distance_std[g][p][k]) + "," + num(s.relative_error[g][p][k]) + "\n";
        }
    write_text_atomic(dir + "/distance.csv", t);
}

// members.csv: one row per trajectory with its per-member statistics.
void write_members_csv(const std::string& dir, const SweepStats& s, const SweepResult& sw) {
    std::string t =
        "member,body,variant,param_label,flow,perturbation,motion_start_s,max_rotation_deg,max_yaw_to_motion_deg,"
        "motion_direction_deg,region_at_arrival";
    for (const auto& c : s.sections) t += "," + c.name + "_time_s," + c.name + "_y_m," + c.name + "_speed_m_s";
    t += ",max_rotation_from_start_deg,movement_direction_deg\n";
    for (std::size_t m = 0; m < s.member_group.size(); ++m) {
        const MemberRecord& r = sw.members[m];
        t += std::to_string(r.id) + "," + r.body_name + "," + r.variant_name + "," + s.params[std::size_t(r.param_set)].label +
             "," + std::to_string(r.flow) + "," + std::to_string(r.perturbation) + "," + num(s.motion_start[m]) + "," +
             num(s.max_rotation[m]) + "," + num(s.max_yaw_to_motion[m]) + "," + num(s.motion_direction[m]) + "," +
             (s.region_at_arrival[m] >= 0 ? s.regions[std::size_t(s.region_at_arrival[m])] : std::string());
        std::vector<double> values;
        for (std::size_t c = 0; c < s.sections.size(); ++c)
            values.insert(values.end(), {s.passage_time[m][c], s.passage_y[m][c], s.passage_speed[m][c]});
        values.insert(values.end(), {s.max_rotation_from_start[m], s.movement_direction[m]});
        for (double v : values) {
            t += ',';
            t += num(v);
        }
        t += '\n';
    }
    write_text_atomic(dir + "/members.csv", t);
}

}  // namespace

void write_stats_csv(const std::string& dir, const SweepStats& s, const SweepResult& sw) {
    std::filesystem::create_directories(dir);
    write_sections_csv(dir, s);
    write_yaw_csv(dir, s);
    write_rotation_csv(dir, s);
    write_regions_csv(dir, s);
    write_distance_csv(dir, s);
    write_members_csv(dir, s, sw);
}

}  // namespace flotsam::sweep
