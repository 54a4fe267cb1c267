#include "formats/trajectory_file.hpp"

#include "formats/flow_file.hpp"

namespace flotsam::debris {

TrackVariables define_track_variables(nc::File& f, int dtraj, int dtime) {
    TrackVariables vars{};
    vars.time = f.def_var("time", NC_DOUBLE, {dtime});
    f.put_att(vars.time, "standard_name", std::string("time"));
    f.put_att(vars.time, "units", std::string(flow_names::time_units));
    f.put_att(vars.time, "calendar", std::string("standard"));
    f.put_att(vars.time, "axis", std::string("T"));
    auto coordinate = [&](const char* name, const char* standard_name, const char* long_name, const char* axis) {
        const int v = f.def_var(name, NC_DOUBLE, {dtraj, dtime});
        f.put_att(v, "standard_name", std::string(standard_name));
        f.put_att(v, "units", std::string("m"));
        f.put_att(v, "long_name", std::string(long_name));
        f.put_att(v, "axis", std::string(axis));
        return v;
    };
    auto field = [&](const char* name, const char* units, const char* long_name) {
        const int v = f.def_var(name, NC_DOUBLE, {dtraj, dtime});
        f.put_att(v, "units", std::string(units));
        f.put_att(v, "long_name", std::string(long_name));
        f.put_att(v, "coordinates", std::string("time x y"));
        return v;
    };
    vars.x = coordinate("x", "projection_x_coordinate", "x of the body centre (east)", "X");
    vars.y = coordinate("y", "projection_y_coordinate", "y of the body centre (north)", "Y");
    vars.yaw = field("yaw", "degree", "heading of the long axis from +x, counter-clockwise, unwrapped");
    vars.u = field("u", "m s-1", "x velocity of the body centre");
    vars.v = field("v", "m s-1", "y velocity of the body centre");
    vars.omega = field("omega", "rad s-1", "yaw rate, counter-clockwise (about the contact centroid while pivoting)");
    vars.status = f.def_var("status", NC_BYTE, {dtraj, dtime});
    f.put_att(vars.status, "long_name", std::string("body state flags"));
    f.put_att(vars.status, "flag_masks",
              std::vector<std::int8_t>{flag_released, flag_moving, flag_grounded, flag_colliding, flag_pivoting});
    f.put_att(vars.status, "flag_meanings", std::string("released moving grounded colliding pivoting"));
    f.put_att(
        vars.status, "comment",
        std::string("released: the depth at the centre has exceeded the draft; grounded: friction acts; colliding: touched an "
                    "obstacle since the previous output; pivoting: rotating about the contact centroid (axis shift)"));
    f.put_att(vars.status, "coordinates", std::string("time x y"));
    return vars;
}

void put_track(nc::File& f, const TrackVariables& vars, std::size_t index, const Track& t) {
    const std::size_t nt = t.x.size();
    const std::vector<std::size_t> start = {index, 0}, count = {1, nt};
    f.put_slab(vars.x, start, count, t.x.data());
    f.put_slab(vars.y, start, count, t.y.data());
    f.put_slab(vars.yaw, start, count, t.yaw_deg.data());
    f.put_slab(vars.u, start, count, t.u.data());
    f.put_slab(vars.v, start, count, t.v.data());
    f.put_slab(vars.omega, start, count, t.omega.data());
    f.put_slab(vars.status, start, count, t.status.data());
}

}  // namespace flotsam::debris
