#include "formats/trajectory_file.hpp"

#include "common/cf.hpp"

namespace flotsam::debris {

TrackVariables define_track_variables(nc::File& f, int dtraj, int dtime, const cf::GridMapping& crs) {
    TrackVariables vars{};
    vars.time = cf::def_time(f, dtime);
    cf::def_crs(f, crs);
    const std::string grid_mapping = cf::grid_mapping_of(crs);
    auto coordinate = [&](const char* name, const char* standard_name, const char* long_name, const char* axis) {
        const int v = cf::def_var(
            f, {.name = name, .dims = {dtraj, dtime}, .units = "m", .standard_name = standard_name, .long_name = long_name});
        f.put_att(v, "axis", std::string(axis));
        return v;
    };
    auto field = [&](const char* name, const char* units, const char* long_name) {
        return cf::def_var(f, {.name = name,
                               .dims = {dtraj, dtime},
                               .units = units,
                               .long_name = long_name,
                               .coordinates = "time x y",
                               .grid_mapping = grid_mapping});
    };
    vars.x = coordinate("x", "projection_x_coordinate", "x of the body centre (east)", "X");
    vars.y = coordinate("y", "projection_y_coordinate", "y of the body centre (north)", "Y");
    vars.yaw = field("yaw", "degree", "heading of the long axis from +x, counter-clockwise, unwrapped");
    vars.u = field("u", "m s-1", "x velocity of the body centre over the last step (pivoting and collision moves included)");
    vars.v = field("v", "m s-1", "y velocity of the body centre over the last step (pivoting and collision moves included)");
    vars.omega = field("omega", "rad s-1", "yaw rate, counter-clockwise (about the contact centroid while pivoting)");
    vars.status = cf::def_var(f, {.name = "status", .type = NC_BYTE, .dims = {dtraj, dtime}, .long_name = "body state flags"});
    f.put_att(vars.status, "flag_masks",
              std::vector<std::int8_t>{flag_released, flag_moving, flag_grounded, flag_colliding, flag_pivoting});
    f.put_att(vars.status, "flag_meanings", std::string("released moving grounded colliding pivoting"));
    f.put_att(
        vars.status, "comment",
        std::string("released: the depth at the centre has exceeded the draft; grounded: friction acts; colliding: touched an "
                    "obstacle since the previous output; pivoting: rotating about the contact centroid (axis shift)"));
    f.put_att(vars.status, "coordinates", std::string("time x y"));
    if (!grid_mapping.empty()) f.put_att(vars.status, "grid_mapping", grid_mapping);
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
