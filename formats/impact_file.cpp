#include "formats/impact_file.hpp"

#include <cmath>
#include <cstdio>

#include "common/atomic_file.hpp"
#include "common/csv.hpp"
#include "common/error.hpp"

namespace flotsam {

const std::vector<std::string>& impact_variable_names() {
    static const std::vector<std::string> names = {"impact_time",  "impact_trajectory", "impact_building", "impact_x",
                                                   "impact_y",     "impact_speed",      "impact_force",    "impact_mass"};
    return names;
}

std::vector<int> define_impact_variables(nc::File& f, std::size_t count, const cf::GridMapping& crs, const std::string& formula) {
    if (count == 0) return {};
    const int d = f.def_dim("impact", count);
    std::vector<int> v;
    v.push_back(cf::def_time(f, d, "impact_time", "time the impact was resolved (the end of the step)", false));
    v.push_back(cf::def_var(f, {.name = "impact_trajectory", .type = NC_INT, .dims = {d}, .long_name = "index of the body (dimension trajectory)"}));
    v.push_back(cf::def_var(f, {.name = "impact_building", .type = NC_INT, .dims = {d}, .long_name = "building hit (the scene's building_id)"}));
    const std::string gm = cf::grid_mapping_of(crs);
    v.push_back(cf::def_var(f, {.name = "impact_x", .dims = {d}, .units = "m", .long_name = "x of the contact point (east)", .grid_mapping = gm}));
    v.push_back(cf::def_var(f, {.name = "impact_y", .dims = {d}, .units = "m", .long_name = "y of the contact point (north)", .grid_mapping = gm}));
    v.push_back(cf::def_var(
        f, {.name = "impact_speed", .dims = {d}, .units = "m s-1", .long_name = "approach speed along the contact normal before the impulse"}));
    v.push_back(cf::def_var(f, {.name = "impact_force", .dims = {d}, .units = "N", .long_name = "impact force estimate"}));
    f.put_att(v.back(), "formula", formula);
    v.push_back(cf::def_var(f, {.name = "impact_mass", .dims = {d}, .units = "kg", .long_name = "mass of the body"}));
    return v;
}

void put_impacts(nc::File& f, const std::vector<int>& vars, const std::vector<Impact>& impacts) {
    if (vars.empty()) return;
    std::vector<double> t, x, y, speed, force, mass;
    std::vector<int> traj, building;
    for (const Impact& i : impacts) {
        t.push_back(i.time);
        traj.push_back(i.trajectory);
        building.push_back(i.building);
        x.push_back(i.x);
        y.push_back(i.y);
        speed.push_back(i.speed);
        force.push_back(i.force);
        mass.push_back(i.mass);
    }
    f.put(vars[0], t);
    f.put(vars[1], traj);
    f.put(vars[2], building);
    f.put(vars[3], x);
    f.put(vars[4], y);
    f.put(vars[5], speed);
    f.put(vars[6], force);
    f.put(vars[7], mass);
}

std::vector<Impact> read_impacts(const nc::File& f, std::size_t trajectories) {
    if (!f.has_dim("impact")) return {};
    const std::size_t n = f.dim_length("impact");
    for (const auto& name : impact_variable_names()) {
        if (!f.has_var(name)) fail(f.path(), "variable '" + name + "'", "missing (the file has an 'impact' dimension)");
        if (f.dim_names(f.var(name)) != std::vector<std::string>{"impact"})
            fail(f.path(), "variable '" + name + "'", "must be one-dimensional on dimension 'impact'");
    }
    const auto t = nc::read_finite(f, "impact_time"), x = nc::read_finite(f, "impact_x"), y = nc::read_finite(f, "impact_y");
    const auto speed = nc::read_finite(f, "impact_speed"), force = nc::read_finite(f, "impact_force"),
               mass = nc::read_finite(f, "impact_mass");
    const auto traj = f.get_int(f.var("impact_trajectory")), building = f.get_int(f.var("impact_building"));
    std::vector<Impact> out(n);
    for (std::size_t k = 0; k < n; ++k) {
        const std::string row = "impact " + std::to_string(k);
        if (traj[k] < 0 || std::size_t(traj[k]) >= trajectories)
            fail(f.path(), "variable 'impact_trajectory'",
                 row + ": " + std::to_string(traj[k]) + " is outside [0, " + std::to_string(trajectories) + ") (the trajectories)");
        if (building[k] < 1) fail(f.path(), "variable 'impact_building'", row + ": " + std::to_string(building[k]) + " is no building id (>= 1)");
        if (!(speed[k] >= 0.0) || !(force[k] >= 0.0) || !(mass[k] > 0.0))
            fail(f.path(), "variables 'impact_speed', 'impact_force', 'impact_mass'", row + ": negative (or zero mass)");
        out[k] = {t[k], traj[k], building[k], x[k], y[k], speed[k], force[k], mass[k]};
    }
    return out;
}

void write_impacts_csv(const std::string& path, const std::vector<Impact>& impacts, const std::vector<std::string>& labels) {
    std::string s = "trajectory,label,building,time_s,x_m,y_m,speed_m_s,force_N,mass_kg\n";
    char buf[256];
    for (const Impact& i : impacts) {
        const std::string label = std::size_t(i.trajectory) < labels.size() ? labels[std::size_t(i.trajectory)] : "";
        s += std::to_string(i.trajectory) + "," + csv_field(label) + "," + std::to_string(i.building);
        std::snprintf(buf, sizeof buf, ",%.10g,%.10g,%.10g,%.10g,%.10g,%.10g\n", i.time, i.x, i.y, i.speed, i.force, i.mass);
        s += buf;
    }
    write_text_atomic(path, s);
}

}  // namespace flotsam
