#include "data/boundary_forcing.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <memory>
#include <optional>

#include "common/checks.hpp"
#include "common/error.hpp"
#include "common/netcdf.hpp"
#include "common/units.hpp"
#include "data/gdal_support.hpp"

namespace flotsam::data {

namespace {

const std::vector<std::string> level_names = {boundary_names::level, "sea_surface_height_above_geoid", "sea_surface_height",
                                              "sea_surface_elevation"};

// The side's edge line and its cells' positions along it, in the scene's frame.
struct SideLine {
    bool x_side = true;     // west or east: the line is x = edge, along y
    double edge = 0.0;      // [m] the line's x (or y)
    double cell_normal = 0.0, cell_along = 0.0;  // [m] cell size across and along the line
    std::vector<double> along;                   // [m] the edge cells' centres along it
};

SideLine side_line(const std::string& side, const Grid& g, const std::string& path) {
    SideLine s;
    if (side == "west" || side == "east") {
        s.x_side = true;
        s.edge = side == "west" ? g.x_min_edge() : g.x_max_edge();
        s.cell_normal = g.dx;
        s.cell_along = g.dy;
        s.along = g.ys();
    } else if (side == "south" || side == "north") {
        s.x_side = false;
        s.edge = side == "south" ? g.y_min_edge() : g.y_max_edge();
        s.cell_normal = g.dy;
        s.cell_along = g.dx;
        s.along = g.xs();
    } else {
        fail(path, "side '" + side + "'", "is not west, east, south or north");
    }
    return s;
}

std::optional<int> find_standard(const nc::File& f, const std::vector<std::string>& names) {
    for (const auto& n : names)
        if (auto v = f.find_by_standard_name(n)) return v;
    return std::nullopt;
}

// The file's variables and how its coordinates are given.
struct Source {
    int level = -1, u = -1, v = -1;  // u, v: -1 without velocity
    int depth = -1;                  // -1 without depth
    bool gridded = false;            // (time, y, x); else (time, station)
    int x = -1, y = -1;              // coordinate variables (1-D on the grid's axes, or per station)
    bool geographic = false;         // x, y are longitude and latitude [degrees]
    std::vector<double> time;        // [s]
};

bool is_longitude(const nc::File& f, int var) {
    const auto sn = f.att_text(var, "standard_name"), u = f.att_text(var, "units");
    return (sn && *sn == "longitude") || (u && (*u == "degrees_east" || *u == "degree_east"));
}
bool is_latitude(const nc::File& f, int var) {
    const auto sn = f.att_text(var, "standard_name"), u = f.att_text(var, "units");
    return (sn && *sn == "latitude") || (u && (*u == "degrees_north" || *u == "degree_north"));
}

// x and y of a station layout: the variables the level's `coordinates` attribute names
// that are longitude/latitude or projection coordinates, else variables named x/y or
// lon/lat on the station dimension.
void find_station_coordinates(const nc::File& f, Source& s, const std::string& station_dim) {
    std::vector<int> candidates;
    if (auto c = f.att_text(s.level, "coordinates")) {
        std::size_t p = 0;
        const std::string& t = *c;
        while (p < t.size()) {
            const std::size_t q = t.find(' ', p);
            const std::string name = t.substr(p, q == std::string::npos ? std::string::npos : q - p);
            if (!name.empty())
                if (auto v = f.find_var(name)) candidates.push_back(*v);
            if (q == std::string::npos) break;
            p = q + 1;
        }
    }
    for (const char* name : {"x", "y", "lon", "lat", "longitude", "latitude"})
        if (auto v = f.find_var(name)) candidates.push_back(*v);
    for (int v : candidates) {
        if (f.dim_names(v) != std::vector<std::string>{station_dim}) continue;
        const auto sn = f.att_text(v, "standard_name");
        const std::string name = f.var_name(v);
        if (s.x < 0 && (is_longitude(f, v) || (sn && *sn == "projection_x_coordinate") || name == "x")) s.x = v;
        if (s.y < 0 && (is_latitude(f, v) || (sn && *sn == "projection_y_coordinate") || name == "y")) s.y = v;
    }
    if (s.x < 0 || s.y < 0)
        fail(f.path(), "variable '" + f.var_name(s.level) + "'",
             "no station coordinates: give x and y (projection_x/y_coordinate) or longitude and latitude on dimension '" +
                 station_dim + "'");
    s.geographic = is_longitude(f, s.x);
    if (s.geographic != is_latitude(f, s.y))
        fail(f.path(), "station coordinates", "one is longitude or latitude and the other is not");
}

std::vector<double> read_times(const nc::File& f, const std::string& dim) {
    const auto tv = f.find_var(dim);
    if (!tv) fail(f.path(), "dimension '" + dim + "'", "has no time coordinate variable of the same name");
    const auto sn = f.att_text(*tv, "standard_name"), axis = f.att_text(*tv, "axis"), u = f.att_text(*tv, "units");
    if (!(sn && *sn == "time") && !(axis && *axis == "T") && !(u && units::time_to_seconds(*u)))
        fail(f.path(), "variable '" + dim + "'", "the first dimension of the level must be time (standard_name time, axis T, or time units)");
    std::vector<double> t = nc::read_finite(f, dim);
    const double factor = units::time_factor(f, *tv);
    for (double& v : t) v *= factor;
    if (t.size() < 2) fail(f.path(), "variable '" + dim + "'", "needs at least two times");
    std::vector<double> steps;
    for (std::size_t k = 1; k < t.size(); ++k) {
        if (!(t[k] > t[k - 1]))
            fail(f.path(), "variable '" + dim + "'",
                 "time is not increasing at index " + std::to_string(k) + " (" + number_text(t[k - 1]) + " s, then " +
                     number_text(t[k]) + " s)");
        steps.push_back(t[k] - t[k - 1]);
    }
    std::vector<double> sorted = steps;
    std::nth_element(sorted.begin(), sorted.begin() + std::ptrdiff_t(sorted.size() / 2), sorted.end());
    const double median = sorted[sorted.size() / 2];
    for (std::size_t k = 0; k < steps.size(); ++k)  // the gap rule of the boundary series (common/timeseries.hpp)
        if (steps[k] > 10.0 && steps[k] > 10.0 * median)
            fail(f.path(), "variable '" + dim + "'",
                 "a gap of " + number_text(steps[k]) + " s after " + number_text(t[k]) + " s (the median step is " +
                     number_text(median) + " s)");
    return t;
}

Source find_source(const nc::File& f, const SideLine& line, const std::string& option) {
    if (const std::string kind = cf::kind_of(f); !kind.empty() && kind != boundary_names::file_kind)
        fail(f.path(), "flotsam_file_kind",
             "is '" + kind + "', not boundary values: a run writes those with --boundary-output FILE --boundary-box ...");
    Source s;
    const auto level = find_standard(f, level_names);
    if (!level)
        fail(f.path(), "water level", "no variable with standard_name " + level_names[0] + " (or " + level_names[1] + ", " +
                                          level_names[2] + ", " + level_names[3] + ")");
    s.level = *level;
    const auto dims = f.dim_names(s.level);
    if (dims.size() != 2 && dims.size() != 3)
        fail(f.path(), "variable '" + f.var_name(s.level) + "'", "must be (time, station) or (time, y, x)");
    s.gridded = dims.size() == 3;
    auto u = find_standard(f, {boundary_names::x_velocity}), v = find_standard(f, {boundary_names::y_velocity});
    if (!u && !v) {
        u = find_standard(f, {"eastward_sea_water_velocity"});
        v = find_standard(f, {"northward_sea_water_velocity"});
    }
    if (bool(u) != bool(v)) fail(f.path(), "velocity", "one component without the other");
    if (u) {
        if (f.dim_names(*u) != dims || f.dim_names(*v) != dims)
            fail(f.path(), "velocity", "its dimensions differ from the level's");
        s.u = *u;
        s.v = *v;
    }
    if (auto d = find_standard(f, {boundary_names::depth}); d && f.dim_names(*d) == dims) s.depth = *d;
    // The record's size before any of it is read: times x points x values.
    const std::vector<std::size_t> shape = f.shape(s.level);
    const double points = double(s.gridded ? line.along.size() : shape[1]), values = 1.0 + (s.u >= 0 ? 2.0 : 0.0) + (s.depth >= 0 ? 1.0 : 0.0);
    check_allocation(option + " " + f.path(), number_text(double(shape[0])) + " times at " + number_text(points) + " points",
                     double(shape[0]) * points * values, 2.0 * sizeof(double), "values");
    s.time = read_times(f, dims[0]);
    if (s.gridded) {
        const auto x = f.find_var(dims[2]), y = f.find_var(dims[1]);
        if (!x || !y)
            fail(f.path(), "variable '" + f.var_name(s.level) + "'",
                 "dimensions (" + dims[1] + ", " + dims[2] + ") have no coordinate variables (y, x)");
        s.x = *x;
        s.y = *y;
        if (is_latitude(f, s.x) || is_longitude(f, s.y))
            fail(f.path(), "variable '" + f.var_name(s.level) + "'", "must be (time, y, x), not (time, x, y)");
        s.geographic = is_longitude(f, s.x);
    } else {
        find_station_coordinates(f, s, dims[1]);
    }
    return s;
}

// From the file's coordinates to the scene's, and back; identity when both are local
// metres or the same CRS.
struct Frames {
    std::string path;
    std::unique_ptr<OGRCoordinateTransformation> to_scene, to_file;
    bool identity() const { return !to_scene; }
    void scene(double& x, double& y) const {
        if (to_scene && !to_scene->Transform(1, &x, &y))
            fail(path, "coordinates", "(" + number_text(x) + ", " + number_text(y) + ") cannot be carried into the scene's CRS");
    }
    void file(double& x, double& y) const {
        if (to_file && !to_file->Transform(1, &x, &y))
            fail(path, "coordinates", "(" + number_text(x) + ", " + number_text(y) + ") cannot be carried into the file's CRS");
    }
};

Frames frames(const nc::File& f, const Source& s, const cf::GridMapping& scene_crs) {
    const cf::GridMapping file_crs = cf::read_crs(f, f.var_name(s.level));
    Frames fr;
    fr.path = f.path();
    if (file_crs.empty() && !s.geographic) {
        if (!scene_crs.empty())
            fail(f.path(), "coordinate reference system",
                 "none (no grid_mapping on '" + f.var_name(s.level) + "' and x, y are not longitude and latitude), while the scene is in " +
                     scene_crs.name() + ": add the CRS as a CF grid mapping, or give longitude and latitude");
        return fr;  // both local metres
    }
    gdal::init();
    OGRSpatialReference from;
    if (file_crs.empty()) {
        from.importFromEPSG(4326);
    } else {
        from = gdal::spatial_ref(file_crs, f.path());
    }
    from.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    if (scene_crs.empty())
        fail(f.path(), "coordinate reference system",
             "the file is in " + gdal::label(from) + " but the scene is in local metres without a CRS: import the scene with its CRS");
    OGRSpatialReference to = gdal::spatial_ref(scene_crs, "the scene");
    to.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    if (from.IsSame(&to)) return fr;
    fr.to_scene.reset(OGRCreateCoordinateTransformation(&from, &to));
    fr.to_file.reset(OGRCreateCoordinateTransformation(&to, &from));
    if (!fr.to_scene || !fr.to_file)
        fail(f.path(), "coordinate reference system", "no transformation from " + gdal::label(from) + " to " + gdal::label(to));
    return fr;
}

// The unit vectors, in the scene's frame, of the file's velocity axes at file point (x, y).
std::array<double, 4> velocity_axes(const Frames& fr, double x, double y, bool geographic) {
    if (fr.identity()) return {1.0, 0.0, 0.0, 1.0};
    const double step = geographic ? 1e-5 : 1.0;
    double x0 = x, y0 = y, x1 = x + step, y1 = y, x2 = x, y2 = y + step;
    fr.scene(x0, y0);
    fr.scene(x1, y1);
    fr.scene(x2, y2);
    const double a = std::hypot(x1 - x0, y1 - y0), b = std::hypot(x2 - x0, y2 - y0);
    return {(x1 - x0) / a, (y1 - y0) / a, (x2 - x0) / b, (y2 - y0) / b};
}

// What a variable's values may be once converted to m or m s-1 (docs/reliability.md): a
// depth not negative, a level within max_forcing_depth of the scene's lowest bed, a speed
// at most 1000 m/s; and its missing-value marker.
struct Limit {
    double fill = 0.0;
    double factor = 1.0, lo = -INFINITY, hi = INFINITY;
    std::string why;  // what the range is, for the message
};
using Limits = std::map<int, Limit>;

void check_value(const nc::File& f, int var, double value, const Limits& limits, std::size_t k, const std::string& where) {
    const Limit& l = limits.at(var);
    if (!std::isfinite(value) || value == l.fill || std::fabs(value) >= 1e30)
        fail(f.path(), "variable '" + f.var_name(var) + "'",
             "no value (" + number_text(value) + ") at time index " + std::to_string(k) + ", " + where);
    if (!(value * l.factor >= l.lo && value * l.factor <= l.hi))
        fail(f.path(), "variable '" + f.var_name(var) + "'",
             number_text(value * l.factor) + " at time index " + std::to_string(k) + ", " + where + " is outside [" +
                 number_text(l.lo) + ", " + number_text(l.hi) + "] (" + l.why + ")");
}

double fill_of(const nc::File& f, int var) {
    if (auto v = f.att_double(var, "_FillValue")) return *v;
    if (auto v = f.att_double(var, "missing_value")) return *v;
    return cf::fill_value;
}

Limits limits_of(const nc::File& f, const Source& s, const ForcingNeeds& needs) {
    Limits limits;
    const double deep = max_forcing_depth;
    Limit level{fill_of(f, s.level), units::length_factor(f, s.level), -INFINITY, INFINITY, ""};
    if (!std::isnan(needs.bed_min)) {
        level.lo = needs.bed_min - deep;
        level.hi = needs.bed_min + deep;
        level.why = "a level within " + number_text(deep) + " m of the scene's lowest bed, " + number_text(needs.bed_min) +
                    " m: deeper water than any ocean's";
    }
    limits[s.level] = level;
    if (s.depth >= 0)
        limits[s.depth] = {fill_of(f, s.depth), units::length_factor(f, s.depth), 0.0, deep, "a water depth: never negative"};
    if (s.u >= 0) {
        const double sf = units::speed_factor(f, s.u);
        if (units::speed_factor(f, s.v) != sf) fail(f.path(), "velocity", "its two components have different units");
        for (int v : {s.u, s.v}) limits[v] = {fill_of(f, v), sf, -1000.0, 1000.0, "a water speed in m/s"};
    }
    return limits;
}

// The times cover the run: from its start, and to its end within one of the file's own
// steps (a record written every 10 s may end up to 10 s before a run that is not a
// multiple of it). A file shifted in time leaves the side unforced otherwise.
void check_times(const nc::File& f, const Source& s, const ForcingNeeds& needs) {
    if (std::isnan(needs.t_end)) return;
    const double first = s.time.front(), last = s.time.back();
    std::vector<double> steps;
    for (std::size_t k = 1; k < s.time.size(); ++k) steps.push_back(s.time[k] - s.time[k - 1]);
    std::nth_element(steps.begin(), steps.begin() + std::ptrdiff_t(steps.size() / 2), steps.end());
    const double step = steps[steps.size() / 2], tol = 1e-9 * std::max(1.0, std::fabs(needs.t_end));
    if (first > needs.t_start + tol || last < needs.t_end - step - tol)
        fail(f.path(), "time",
             "covers " + number_text(first) + " to " + number_text(last) + " s, the run " + number_text(needs.t_start) + " to " +
                 number_text(needs.t_end) + " s: " +
                 (first >= needs.t_end || last <= needs.t_start ? "they do not overlap (is the file's time axis shifted?)"
                                                                : "the side would be held at the file's first or last values") +
                 "; the file's time counts from the run's start (t = 0)");
}

// The stations within reach of the side's edge line, as (position along it, station), in
// order along it, a corner written by two sides once; they must cover the side.
std::vector<std::pair<double, std::size_t>> stations_along(const nc::File& f, const std::vector<double>& sx,
                                                           const std::vector<double>& sy, const SideLine& line) {
    const std::size_t ns = sx.size();
    std::vector<double> nearest(ns, INFINITY);
    for (std::size_t p = 0; p < ns; ++p)
        for (std::size_t q = 0; q < ns; ++q)
            if (p != q) nearest[p] = std::min(nearest[p], std::hypot(sx[p] - sx[q], sy[p] - sy[q]));
    std::vector<double> sorted = nearest;
    std::nth_element(sorted.begin(), sorted.begin() + std::ptrdiff_t(ns / 2), sorted.end());
    const double spacing = ns > 1 ? sorted[ns / 2] : 0.0;
    const double reach = std::max(line.cell_normal, 0.5 * spacing) * (1.0 + 1e-9);
    const double lo = line.along.front() - 0.5 * line.cell_along - reach, hi = line.along.back() + 0.5 * line.cell_along + reach;
    std::vector<std::pair<double, std::size_t>> chosen;  // (along, station)
    for (std::size_t p = 0; p < ns; ++p) {
        const double normal = line.x_side ? sx[p] : sy[p], along = line.x_side ? sy[p] : sx[p];
        if (std::fabs(normal - line.edge) <= reach && along >= lo && along <= hi) chosen.push_back({along, p});
    }
    if (chosen.empty())
        fail(f.path(), "stations",
             "none within " + number_text(reach) + " m of the side's edge (" + (line.x_side ? "x = " : "y = ") +
                 number_text(line.edge) + " m in the scene's frame)");
    std::stable_sort(chosen.begin(), chosen.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    std::vector<std::pair<double, std::size_t>> unique;  // a corner written by two sides counts once
    for (const auto& c : chosen)
        if (unique.empty() || c.first - unique.back().first > 1e-9 * std::max(1.0, std::fabs(c.first))) unique.push_back(c);

    const double first = unique.front().first, last = unique.back().first, half = 0.5 * line.cell_along * (1.0 + 1e-9);
    if (first > line.along.front() + half || last < line.along.back() - half)
        fail(f.path(), "stations",
             "do not cover the side: those within reach of its edge span " + number_text(first) + " to " + number_text(last) +
                 " m along it, its cells " + number_text(line.along.front()) + " to " + number_text(line.along.back()) + " m");

    return unique;
}

// The station or grid coordinates, in metres (projected) or degrees, checked: values
// another program could write absurd are refused (longitudes within a turn either way,
// latitudes within the poles, projected coordinates within 1e8 m, as tracks are checked;
// a station at −1e30 m was left out of the side without a word).
std::array<std::vector<double>, 2> read_coordinates(const nc::File& f, const Source& s) {
    std::array<std::vector<double>, 2> xy;
    for (const int axis : {0, 1}) {
        const int var = axis == 0 ? s.x : s.y;
        std::vector<double>& values = xy[std::size_t(axis)];
        values = nc::read_finite(f, f.var_name(var));
        const double factor = s.geographic ? 1.0 : units::length_factor(f, var);
        const double bound = s.geographic ? (axis == 0 ? 360.0 : 90.0) : 1e8;
        for (double& v : values) {
            v *= factor;
            if (!(std::fabs(v) <= bound))
                fail(f.path(), "variable '" + f.var_name(var) + "'",
                     "value " + number_text(v) + (s.geographic ? " degrees" : " m") + " is outside [" + number_text(-bound) +
                         ", " + number_text(bound) + "]");
        }
    }
    return xy;
}

SideRecord place_stations(const nc::File& f, const Source& s, const Frames& fr, const SideLine& line, const Limits& limits) {
    const std::size_t nt = s.time.size(), ns = f.shape(s.level)[1];
    const auto [xs, ys] = read_coordinates(f, s);
    std::vector<double> sx = xs, sy = ys;
    for (std::size_t p = 0; p < ns; ++p) fr.scene(sx[p], sy[p]);
    const std::vector<std::pair<double, std::size_t>> unique = stations_along(f, sx, sy, line);

    SideRecord r;
    r.source = f.path();
    r.time = s.time;
    const std::size_t np = unique.size();
    for (const auto& c : unique) r.along.push_back(c.first);
    const std::vector<double> level = f.get_double(s.level);
    const double lf = limits.at(s.level).factor;
    r.level.resize(nt * np);
    std::vector<double> uf, vf, df;
    double sf = 1.0, dfac = 1.0;
    if (s.depth >= 0) {
        df = f.get_double(s.depth);
        dfac = limits.at(s.depth).factor;
        r.depth.resize(nt * np);
    }
    if (s.u >= 0) {
        uf = f.get_double(s.u);
        vf = f.get_double(s.v);
        sf = limits.at(s.u).factor;
        r.u.resize(nt * np);
        r.v.resize(nt * np);
    }
    for (std::size_t c = 0; c < np; ++c) {
        const std::size_t p = unique[c].second;
        const std::string where = "station " + std::to_string(p);
        const auto axes = s.u >= 0 ? velocity_axes(fr, xs[p], ys[p], s.geographic) : std::array<double, 4>{};
        for (std::size_t k = 0; k < nt; ++k) {
            const double value = level[k * ns + p];
            check_value(f, s.level, value, limits, k, where);
            r.level[k * np + c] = lf * value;
            if (s.depth >= 0) {
                check_value(f, s.depth, df[k * ns + p], limits, k, where);
                r.depth[k * np + c] = dfac * df[k * ns + p];
            }
            if (s.u >= 0) {
                const double a = uf[k * ns + p], b = vf[k * ns + p];
                check_value(f, s.u, a, limits, k, where);
                check_value(f, s.v, b, limits, k, where);
                r.u[k * np + c] = sf * (a * axes[0] + b * axes[2]);
                r.v[k * np + c] = sf * (a * axes[1] + b * axes[3]);
            }
        }
    }
    return r;
}

// Fractional index of value a on a monotone axis; throws when a lies more than half a
// spacing beyond its ends.
double axis_position(const std::vector<double>& axis, double a, const nc::File& f, const std::string& name) {
    const std::size_t n = axis.size();
    const bool rising = n < 2 || axis[1] > axis[0];
    const double first = axis.front(), last = axis.back();
    const double half = n > 1 ? 0.5 * std::fabs(axis[1] - axis[0]) : 0.0;
    const double lo = std::min(first, last) - half, hi = std::max(first, last) + half;
    if (a < lo || a > hi)
        fail(f.path(), "variable '" + name + "'",
             "does not cover the side: it spans " + number_text(lo) + " to " + number_text(hi) + ", the side needs " +
                 number_text(a));
    for (std::size_t i = 0; i + 1 < n; ++i) {
        const double a0 = axis[i], a1 = axis[i + 1];
        if ((rising && a >= a0 && a <= a1) || (!rising && a <= a0 && a >= a1)) return double(i) + (a - a0) / (a1 - a0);
    }
    return (rising ? a < first : a > first) ? 0.0 : double(n - 1);
}

SideRecord place_on_grid(const nc::File& f, const Source& s, const Frames& fr, const SideLine& line, const Limits& limits) {
    const auto shape = f.shape(s.level);
    const std::size_t nt = s.time.size(), ny = shape[1], nx = shape[2];
    const auto [ax, ay] = read_coordinates(f, s);
    const std::size_t np = line.along.size();
    std::vector<double> fi(np), fj(np);
    std::vector<std::array<double, 4>> axes(np);
    std::size_t i0 = nx, i1 = 0, j0 = ny, j1 = 0;
    for (std::size_t p = 0; p < np; ++p) {
        double x = line.x_side ? line.edge : line.along[p], y = line.x_side ? line.along[p] : line.edge;
        fr.file(x, y);
        fi[p] = axis_position(ax, x, f, f.var_name(s.x));
        fj[p] = axis_position(ay, y, f, f.var_name(s.y));
        if (s.u >= 0) axes[p] = velocity_axes(fr, x, y, s.geographic);
        i0 = std::min(i0, std::size_t(std::floor(fi[p])));
        i1 = std::max(i1, std::min(nx - 1, std::size_t(std::floor(fi[p])) + 1));
        j0 = std::min(j0, std::size_t(std::floor(fj[p])));
        j1 = std::max(j1, std::min(ny - 1, std::size_t(std::floor(fj[p])) + 1));
    }
    const std::size_t wx = i1 - i0 + 1, wy = j1 - j0 + 1;
    SideRecord r;
    r.source = f.path();
    r.time = s.time;
    r.along = line.along;
    r.level.resize(nt * np);
    if (s.u >= 0) {
        r.u.resize(nt * np);
        r.v.resize(nt * np);
    }
    const double lf = limits.at(s.level).factor;
    const double sf = s.u >= 0 ? limits.at(s.u).factor : 1.0;
    const double dfac = s.depth >= 0 ? limits.at(s.depth).factor : 1.0;
    if (s.depth >= 0) r.depth.resize(nt * np);
    std::vector<double> lw(wx * wy), uw, vw, dw;
    for (std::size_t k = 0; k < nt; ++k) {
        auto slab = [&](int var, std::vector<double>& out) {
            out.resize(wx * wy);
            f.get_slab(var, {k, j0, i0}, {1, wy, wx}, out.data());
            for (std::size_t q = 0; q < out.size(); ++q)
                check_value(f, var, out[q], limits, k, "cell (x index " + std::to_string(i0 + q % wx) + ", y index " +
                                                         std::to_string(j0 + q / wx) + ")");
        };
        slab(s.level, lw);
        if (s.u >= 0) {
            slab(s.u, uw);
            slab(s.v, vw);
        }
        if (s.depth >= 0) slab(s.depth, dw);
        for (std::size_t p = 0; p < np; ++p) {
            const std::size_t ia = std::min(std::size_t(std::floor(fi[p])), nx - 1), ja = std::min(std::size_t(std::floor(fj[p])), ny - 1);
            const std::size_t ib = std::min(ia + 1, nx - 1), jb = std::min(ja + 1, ny - 1);
            const double wxp = std::clamp(fi[p] - double(ia), 0.0, 1.0), wyp = std::clamp(fj[p] - double(ja), 0.0, 1.0);
            auto bilinear = [&](const std::vector<double>& w) {
                auto at = [&](std::size_t i, std::size_t j) { return w[(j - j0) * wx + (i - i0)]; };
                return (1 - wyp) * ((1 - wxp) * at(ia, ja) + wxp * at(ib, ja)) + wyp * ((1 - wxp) * at(ia, jb) + wxp * at(ib, jb));
            };
            r.level[k * np + p] = lf * bilinear(lw);
            if (s.depth >= 0) r.depth[k * np + p] = std::max(0.0, dfac * bilinear(dw));
            if (s.u >= 0) {
                const double a = bilinear(uw), b = bilinear(vw);
                r.u[k * np + p] = sf * (a * axes[p][0] + b * axes[p][2]);
                r.v[k * np + p] = sf * (a * axes[p][1] + b * axes[p][3]);
            }
        }
    }
    return r;
}

}  // namespace

SideRecord read_side_forcing(const std::string& path, const std::string& side, const Grid& grid, const cf::GridMapping& crs,
                             const ForcingNeeds& needs) {
    const nc::File f = nc::File::open_read(path);
    const SideLine line = side_line(side, grid, path);
    const Source s = find_source(f, line, needs.option);
    check_times(f, s, needs);
    const Frames fr = frames(f, s, crs);
    const Limits limits = limits_of(f, s, needs);
    return s.gridded ? place_on_grid(f, s, fr, line, limits) : place_stations(f, s, fr, line, limits);
}

}  // namespace flotsam::data
