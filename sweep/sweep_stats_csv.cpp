// The statistics as a folder of CSV tables, one per statistic (columns in docs/sweep.md).
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "common/atomic_file.hpp"
#include "formats/stats_file.hpp"
#include "sweep/sweep_stats.hpp"

namespace flotsam::sweep {

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
    write_text_atomic(dir + "/" + stats_file::csv::sections, t);
    write_text_atomic(dir + "/" + stats_file::csv::speed_kde, k);
}

void write_yaw_csv(const std::string& dir, const SweepStats& s) {
    std::string t =
        "body,variant,bin_min_deg,bin_max_deg,max_rotation_count,max_yaw_to_motion_count,max_rotation_from_start_count\n";
    for (std::size_t g = 0; g < s.groups.size(); ++g)
        for (std::size_t b = 0; b + 1 < s.yaw_edges.size(); ++b)
            t += group_key(s.groups[g]) + "," + num(s.yaw_edges[b]) + "," + num(s.yaw_edges[b + 1]) + "," +
                 std::to_string(s.rotation_hist[g][b]) + "," + std::to_string(s.yaw_motion_hist[g][b]) + "," +
                 std::to_string(s.rotation_from_start_hist[g][b]) + "\n";
    write_text_atomic(dir + "/" + stats_file::csv::yaw_histogram, t);
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
    write_text_atomic(dir + "/" + stats_file::csv::rotation_from_start, t);
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
    write_text_atomic(dir + "/" + stats_file::csv::regions, t);
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
    write_text_atomic(dir + "/" + stats_file::csv::distance, t);
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
    write_text_atomic(dir + "/" + stats_file::csv::members, t);
}

}  // namespace

// buildings.csv: one row per group × building hit, then per building over all
// trajectories (body and variant "all").
void write_buildings_csv(const std::string& dir, const SweepStats& s) {
    std::string t = "body,variant,building,hit_probability,first_hit_time_s,impacts,speed_median_m_s,speed_p90_m_s,speed_max_m_s,"
                    "force_median_N,force_p90_N,force_max_N\n";
    auto row = [&](const std::string& key, std::size_t b, const SweepStats::BuildingSummary& q) {
        if (q.impacts == 0) return;
        t += key + "," + std::to_string(s.building_ids[b]) + "," + num(q.hit_probability) + "," + num(q.first_hit_time) + "," +
             std::to_string(q.impacts) + "," + num(q.speed_median) + "," + num(q.speed_p90) + "," + num(q.speed_max) + "," +
             num(q.force_median) + "," + num(q.force_p90) + "," + num(q.force_max) + "\n";
    };
    for (std::size_t g = 0; g < s.groups.size(); ++g)
        for (std::size_t b = 0; b < s.building_ids.size(); ++b) row(group_key(s.groups[g]), b, s.building[g][b]);
    for (std::size_t b = 0; b < s.building_ids.size(); ++b) row("all,all", b, s.building_all[b]);
    write_text_atomic(dir + "/" + stats_file::csv::buildings, t);
}

void write_stats_csv(const std::string& dir, const SweepStats& s, const SweepResult& sw) {
    std::filesystem::create_directories(dir);
    write_sections_csv(dir, s);
    write_yaw_csv(dir, s);
    write_rotation_csv(dir, s);
    write_regions_csv(dir, s);
    write_distance_csv(dir, s);
    write_members_csv(dir, s, sw);
    write_buildings_csv(dir, s);
}

}  // namespace flotsam::sweep
