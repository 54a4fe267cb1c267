#include "formats/trajectory_file.hpp"

#include <cmath>

#include "common/cf.hpp"
#include "common/checks.hpp"
#include "common/error.hpp"
#include "common/units.hpp"

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

namespace {

std::string at(std::size_t b, std::size_t k) {
    return "trajectory " + std::to_string(b) + ", time index " + std::to_string(k);
}

// The time axis: one-dimensional on "time", converted to s, finite, increasing.
std::vector<double> read_time_axis(const nc::File& f) {
    const int v = f.var("time");
    if (f.dim_names(v) != std::vector<std::string>{"time"})
        fail(f.path(), "variable 'time'", "must be one-dimensional on dimension 'time'");
    std::vector<double> t = nc::read_finite(f, "time");
    const double factor = units::time_factor(f, v);
    for (std::size_t k = 0; k < t.size(); ++k) {
        t[k] *= factor;
        if (k > 0 && !(t[k] > t[k - 1]))
            fail(f.path(), "variable 'time'",
                 "must increase (at index " + std::to_string(k) + ": " + number_text(t[k - 1]) + " s, then " +
                     number_text(t[k]) + " s)");
    }
    return t;
}

}  // namespace

TrackReader::TrackReader(const nc::File& f, bool complete)
    : f_(f),
      x_{"x", -1, 1.0, max_track_coordinate, "a position"},
      y_{"y", -1, 1.0, max_track_coordinate, "a position"},
      yaw_{"yaw", -1, 1.0, max_track_yaw, "a heading"},
      u_{"u", -1, 1.0, max_track_speed, "a speed"},
      v_{"v", -1, 1.0, max_track_speed, "a speed"},
      omega_{"omega", -1, 1.0, max_track_yaw_rate, "a yaw rate"} {
    time_ = read_time_axis(f);
    if (!f.has_dim("trajectory")) fail(f.path(), "dimension 'trajectory'", "missing: not a flotsam trajectory or sweep file");
    trajectories_ = f.dim_length("trajectory");
    const std::size_t nt = time_.size();
    auto track_var = [&](const char* name, bool required) {
        if (!required && !f.has_var(name)) return -1;
        const int id = f.var(name);
        if (f.dim_names(id) != std::vector<std::string>{"trajectory", "time"} ||
            f.shape(id) != std::vector<std::size_t>{trajectories_, nt})
            fail(f.path(), std::string("variable '") + name + "'",
                 "must have dimensions (trajectory, time) = (" + std::to_string(trajectories_) + ", " + std::to_string(nt) + ")");
        return id;
    };
    for (Series* s : {&x_, &y_, &yaw_, &u_, &v_, &omega_}) {
        s->var = track_var(s->name, complete || s == &x_ || s == &y_);
        if (s->var < 0) continue;
        s->factor = s == &x_ || s == &y_   ? units::length_factor(f, s->var)
                    : s == &yaw_           ? units::angle_factor(f, s->var)
                    : s == &omega_         ? units::angular_speed_factor(f, s->var)
                                           : units::speed_factor(f, s->var);
    }
    if (u_.var < 0 || v_.var < 0) u_.var = v_.var = -1;  // a speed is both components or none
    status_ = track_var("status", complete);
}

void TrackReader::read_series(const Series& s, std::size_t b, std::vector<double>& out) const {
    const std::size_t nt = time_.size();
    out.assign(nt, 0.0);
    if (nt == 0) return;
    f_.get_slab(s.var, {b, 0}, {1, nt}, out.data());
    for (std::size_t k = 0; k < nt; ++k) {
        const double raw = out[k], value = raw * s.factor;
        if (!std::isfinite(raw) || std::fabs(raw) >= 0.5 * cf::fill_value)
            fail(f_.path(), std::string("variable '") + s.name + "'",
                 at(b, k) + ": " + number_text(raw) + " is not " + s.what + " (NaN, infinite or a fill value)");
        if (!(std::fabs(value) <= s.bound))
            fail(f_.path(), std::string("variable '") + s.name + "'",
                 at(b, k) + ": " + number_text(value) + " is not " + s.what + " (beyond +-" + number_text(s.bound) + ")");
        out[k] = value;
    }
}

Track TrackReader::read(std::size_t b) const {
    Track t;
    read_series(x_, b, t.x);
    read_series(y_, b, t.y);
    for (const auto& [s, out] : {std::pair{&yaw_, &t.yaw_deg}, std::pair{&u_, &t.u}, std::pair{&v_, &t.v}, std::pair{&omega_, &t.omega}})
        if (s->var >= 0) read_series(*s, b, *out);
    // No step between samples faster than any debris moves: a position off by a kilometre
    // at one sample, or a time axis in the wrong unit, shows here.
    for (std::size_t k = 1; k < t.x.size(); ++k) {
        const double speed = std::hypot(t.x[k] - t.x[k - 1], t.y[k] - t.y[k - 1]) / (time_[k] - time_[k - 1]);
        if (!(speed <= max_track_speed))
            fail(f_.path(), "variables 'x', 'y'",
                 at(b, k) + ": the body moves " + number_text(std::hypot(t.x[k] - t.x[k - 1], t.y[k] - t.y[k - 1])) +
                     " m in " + number_text(time_[k] - time_[k - 1]) + " s (" + number_text(speed) +
                     " m/s, more than the " + number_text(max_track_speed) + " m/s of any debris)");
    }
    if (status_ >= 0 && !time_.empty()) {
        std::vector<double> raw(time_.size());
        f_.get_slab(status_, {b, 0}, {1, time_.size()}, raw.data());
        for (std::size_t k = 0; k < raw.size(); ++k) {
            // Five flag bits; a byte beyond them is no status.
            if (!(raw[k] >= 0 && raw[k] <= 31))
                fail(f_.path(), "variable 'status'",
                     at(b, k) + ": " + number_text(raw[k]) +
                         " is not a combination of the flags 1, 2, 4, 8, 16 (released moving grounded colliding pivoting)");
            t.status.push_back(std::int8_t(raw[k]));
        }
    }
    return t;
}

void check_track_within(const std::string& path, std::size_t trajectory, const Track& track, double x_min, double x_max,
                        double y_min, double y_max, const std::string& what) {
    for (std::size_t k = 0; k < track.x.size(); ++k)
        if (!(track.x[k] >= x_min && track.x[k] <= x_max && track.y[k] >= y_min && track.y[k] <= y_max))
            fail(path, "variables 'x', 'y'",
                 at(trajectory, k) + ": (" + coordinate_text(track.x[k]) + ", " + coordinate_text(track.y[k]) +
                     ") m lies outside " + what + " (x " + coordinate_text(x_min) + " to " + coordinate_text(x_max) + ", y " +
                     coordinate_text(y_min) + " to " + coordinate_text(y_max) +
                     " m), where its bodies moved: the file does not belong with it, or its positions are wrong");
}

namespace {

// The per-trajectory variables in the file's order: one-dimensional on trajectory, numbers
// finite.
std::vector<TrajectoryColumn> read_columns(const nc::File& f, std::size_t ntraj) {
    std::vector<TrajectoryColumn> columns;
    int nvars = 0;
    f.check(nc_inq_nvars(f.id(), &nvars), "number of variables");
    for (int id = 0; id < nvars; ++id) {
        const auto dims = f.value_dims(id);  // a string column's: without its string length
        if (dims.empty() || dims[0] != "trajectory" || (dims.size() == 2 && dims[1] == "time")) continue;
        const std::string name = f.var_name(id);
        if (dims.size() != 1 || f.value_shape(id)[0] != ntraj)
            fail(f.path(), "variable '" + name + "'", "must be one-dimensional on dimension 'trajectory'");
        nc_type type{};
        f.check(nc_inq_vartype(f.id(), id, &type), "variable '" + name + "'");
        if (type == NC_CHAR) type = NC_STRING;  // strings either way: a character array, or NC_STRING in older files
        TrajectoryColumn c{name, type, {}, {}};
        if (type == NC_STRING) {
            c.text = f.get_strings(id);
        } else {
            c.number = f.get_double(id);
            for (std::size_t b = 0; b < c.number.size(); ++b)
                if (!std::isfinite(c.number[b]) || std::fabs(c.number[b]) >= 0.5 * cf::fill_value)
                    fail(f.path(), "variable '" + name + "'",
                         "trajectory " + std::to_string(b) + ": " + number_text(c.number[b]) +
                             " is not a number (NaN, infinite or a fill value)");
        }
        columns.push_back(std::move(c));
    }
    return columns;
}

}  // namespace

TrajectoryTable read_trajectory_table(const std::string& path, const std::function<void(const nc::File&, std::size_t)>& check_columns) {
    const nc::File f = nc::File::open_read(path);
    cf::require_kind(f, {"trajectories", "sweep"}, "--trajectories");
    for (const char* v : {"x", "y", "time", "trajectory_id"})
        if (!f.has_var(v)) fail(path, std::string("variable '") + v + "'", "missing: not a flotsam trajectory or sweep file");
    if (f.value_dims(f.var("trajectory_id")) != std::vector<std::string>{"trajectory"})
        fail(path, "variable 'trajectory_id'", "must be one-dimensional on dimension 'trajectory'");
    TrajectoryTable t;
    t.path = path;
    t.kind = cf::kind_of(f);
    const TrackReader reader(f, false);
    t.time = reader.time();
    for (std::size_t b = 0; b < reader.size(); ++b) t.tracks.push_back(reader.read(b));
    t.columns = read_columns(f, reader.size());
    if (check_columns) check_columns(f, reader.size());
    t.crs = cf::read_crs(f, "yaw");
    t.scene_buildings_sha256 = f.att_text(NC_GLOBAL, "scene_buildings_sha256").value_or("");
    return t;
}

}  // namespace flotsam::debris
