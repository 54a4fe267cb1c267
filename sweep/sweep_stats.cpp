#include "sweep/sweep_stats.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "common/columns.hpp"
#include "common/error.hpp"
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

// Groups (source × variant, in the sweep's table order), the per-member table and the
// members per (group, parameter set). A source is the GIS feature the bodies came from
// (a yard's bodies are one group, named "layer/fid"), else the body itself.
void group_members(SweepStats& s, const SweepResult& sw) {
    const std::size_t nm = sw.members.size();
    s.member_group.assign(nm, -1);
    std::vector<std::string> source_of(sw.bodies), sources;
    for (std::size_t b = 0; b < sw.bodies.size(); ++b) {
        if (b < sw.body_sources.size() && !sw.body_sources[b].empty()) source_of[b] = sw.body_sources[b];
        if (std::find(sources.begin(), sources.end(), source_of[b]) == sources.end()) sources.push_back(source_of[b]);
    }
    for (const std::string& source : sources)
        for (std::size_t v = 0; v < sw.variants.size(); ++v) {
            SweepStats::Group g{source, sw.variants[v], {}};
            for (std::size_t m = 0; m < nm; ++m)
                if (source_of[std::size_t(sw.members[m].body)] == source && sw.members[m].variant == int(v)) {
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

// Impacts per building: over the members given, the share that hit it, the first impact,
// and the median, 90th percentile and largest speed and force of its impacts.
std::vector<SweepStats::BuildingSummary> building_summaries(const SweepResult& sw, const std::vector<int>& members,
                                                           const std::vector<std::int32_t>& ids) {
    const double missing = std::nan("");
    std::vector<SweepStats::BuildingSummary> out(ids.size());
    std::vector<std::vector<double>> speeds(ids.size()), forces(ids.size());
    std::vector<int> hit(ids.size(), 0);
    std::vector<double> first(ids.size(), missing);
    for (int m : members) {
        std::vector<char> hit_here(ids.size(), 0);
        for (const Impact& i : sw.members[std::size_t(m)].impacts) {
            const auto it = std::lower_bound(ids.begin(), ids.end(), i.building);
            if (it == ids.end() || *it != i.building) continue;  // not a building of this scene
            const std::size_t b = std::size_t(it - ids.begin());
            speeds[b].push_back(i.speed);
            forces[b].push_back(i.force);
            hit_here[b] = 1;
            if (std::isnan(first[b]) || i.time < first[b]) first[b] = i.time;
        }
        for (std::size_t b = 0; b < ids.size(); ++b) hit[b] += hit_here[b];
    }
    for (std::size_t b = 0; b < ids.size(); ++b) {
        auto& q = out[b];
        q.hit_probability = members.empty() ? 0.0 : double(hit[b]) / double(members.size());
        q.first_hit_time = first[b];
        q.impacts = int(speeds[b].size());
        std::sort(speeds[b].begin(), speeds[b].end());
        std::sort(forces[b].begin(), forces[b].end());
        q.speed_median = quantile_sorted(speeds[b], 0.5);
        q.speed_p90 = quantile_sorted(speeds[b], 0.9);
        q.speed_max = speeds[b].empty() ? nan : speeds[b].back();
        q.force_median = quantile_sorted(forces[b], 0.5);
        q.force_p90 = quantile_sorted(forces[b], 0.9);
        q.force_max = forces[b].empty() ? nan : forces[b].back();
    }
    return out;
}

void building_impacts(SweepStats& s, const SweepResult& sw, const Scene& scene) {
    const std::vector<std::int32_t> ids = scene_building_ids(scene);
    s.building_ids.assign(ids.begin(), ids.end());
    std::sort(s.building_ids.begin(), s.building_ids.end());
    s.building_ids.erase(std::unique(s.building_ids.begin(), s.building_ids.end()), s.building_ids.end());
    if (!s.building_ids.empty() && s.building_ids.front() == 0) s.building_ids.erase(s.building_ids.begin());
    for (const auto& g : s.groups) s.building.push_back(building_summaries(sw, g.members, s.building_ids));
    std::vector<int> all(sw.members.size());
    for (std::size_t m = 0; m < all.size(); ++m) all[m] = int(m);
    s.building_all = building_summaries(sw, all, s.building_ids);
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
    building_impacts(s, sw, scene);
    return s;
}

}  // namespace flotsam::sweep
