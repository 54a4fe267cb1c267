// The sweep's CSV tables: one row per trajectory (the summary), one per impact on a
// building.
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "common/atomic_file.hpp"
#include "common/csv.hpp"
#include "debris/impacts.hpp"
#include "sweep/sweep_file.hpp"
#include "sweep/trajectory_kernels.hpp"

namespace flotsam::sweep {

std::string impacts_path_for(const std::string& nc_path) {
    std::filesystem::path p(nc_path);
    p.replace_extension("");
    return p.string() + "_impacts.csv";
}

void write_impacts_summary_csv(const std::string& path, const SweepResult& r) {
    std::vector<std::string> labels;
    for (const auto& m : r.members) labels.push_back(trajectory_label(r, m));
    write_impacts_csv(path, file_impacts(r), labels);
}

std::string summary_path_for(const std::string& nc_path) {
    std::filesystem::path p(nc_path);
    p.replace_extension(".csv");
    return p.string();
}

void write_summary_csv(const std::string& path, const SweepResult& r) {
    std::string s = "member,flow,flow_path,body,start_name,variant,param_set,param_label,perturbation";
    for (const auto& p : debris::body_coefficient_settings()) {
        s += ',';
        s += p.variable();
    }
    s += ",x0_m,y0_m,heading0_deg,motion_start_s,final_x_m,final_y_m,final_yaw_deg,net_displacement_m,travel_distance_m,"
         "max_speed_m_s,time_of_max_speed_s,collision_steps,unresolved_collisions,axis_shift_steps,largest_residual_overlap_m,"
         "jammed_steps,"
         "run,body_contact_steps,largest_body_overlap_m\n";
    char buf[512];
    for (const auto& m : r.members) {
        const debris::Track& t = m.track;
        const int k0 = t.x.empty() ? -1 : motion_start_index(t.x, t.y, motion_threshold * body_scale(m.def.length));
        double vmax = 0.0, tmax = r.time.empty() ? 0.0 : r.time.front();
        for (std::size_t k = 0; k < t.u.size(); ++k) {
            const double sp = std::hypot(t.u[k], t.v[k]);
            if (sp > vmax) {
                vmax = sp;
                tmax = r.time[k];
            }
        }
        const bool any = !t.x.empty();
        s += std::to_string(m.id) + "," + std::to_string(m.flow) + "," + csv_field(r.flows[std::size_t(m.flow)]) + "," +
             csv_field(m.body_name) + "," + csv_field(m.start_name) + "," + m.variant_name + "," + std::to_string(m.param_set) +
             "," + csv_field(r.params[std::size_t(m.param_set)].label) + "," + std::to_string(m.perturbation);
        for (const auto& p : debris::body_coefficient_settings()) {
            std::snprintf(buf, sizeof buf, ",%.10g", p.number(m.def));
            s += buf;
        }
        std::snprintf(buf, sizeof buf, ",%.10g,%.10g,%.10g,", m.def.x, m.def.y, m.heading0_deg);
        s += buf;
        if (k0 >= 0) {
            std::snprintf(buf, sizeof buf, "%.10g", r.time[std::size_t(k0)]);
            s += buf;
        }  // empty: never moved
        std::snprintf(buf, sizeof buf, ",%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%d,%d,%d,%.4g,%d,%d,%d,%.4g\n",
                      any ? t.x.back() : m.def.x, any ? t.y.back() : m.def.y, any ? t.yaw_deg.back() : m.heading0_deg,
                      any ? std::hypot(t.x.back() - t.x.front(), t.y.back() - t.y.front()) : 0.0, any ? path_length(t.x, t.y) : 0.0,
                      vmax, tmax, int(m.counts.collisions), int(m.counts.unresolved), int(m.counts.axis_shifts),
                      m.counts.max_residual_overlap, int(m.counts.jams), m.run, int(m.counts.body_contacts),
                      m.counts.max_body_overlap);
        s += buf;
    }
    write_text_atomic(path, s);
}

}  // namespace flotsam::sweep
