// The maps of statistics and flow files, and a flow as a mesh layer (export/gis_export.hpp).
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <optional>

#include "common/checks.hpp"
#include "common/error.hpp"
#include "common/netcdf.hpp"
#include "common/units.hpp"
#include "export/gis_export.hpp"
#include "export/styles.hpp"
#include "formats/stats_file.hpp"

namespace flotsam::gis {

namespace {

constexpr float no_value = std::numeric_limits<float>::quiet_NaN();

// A value that CF files store as missing (fill value or NaN) becomes NaN.
float as_map_value(double v, std::optional<double> fill) {
    if (!std::isfinite(v) || (fill && v == *fill) || std::abs(v) >= 0.5 * cf::fill_value) return no_value;
    return float(v);
}

Grid grid_of(const nc::File& f) { return grid_from_coordinates(nc::read_finite(f, "x"), nc::read_finite(f, "y"), f.path()); }

// The factor from a variable's units to flotsam's (m, s, m s-1; "1" for fractions), or a
// named error for units it cannot convert.
double si_factor(const nc::File& f, int v) {
    const auto u = f.att_text(v, "units");
    if (!u || u->empty() || *u == "1") return 1.0;
    if (const auto l = units::length_to_metres(*u)) return *l;
    if (const auto t = units::time_to_seconds(*u)) return *t;
    if (const auto s = units::speed_to_metres_per_second(*u)) return *s;
    fail(f.path(), "variable '" + f.var_name(v) + "' attribute 'units'",
         "'" + *u + "' is no length, time or speed flotsam can convert (m, cm, ft, km; s, min, h; m s-1, km h-1, ...)");
}

// The slab `index` of a variable over (..., y, x), as map values.
std::vector<float> read_map(const nc::File& f, const std::string& name, const Grid& g, std::size_t index = 0) {
    const int v = f.var(name);
    const auto shape = f.shape(v);
    if (shape.size() < 2 || shape[shape.size() - 2] != std::size_t(g.ny) || shape.back() != std::size_t(g.nx))
        fail(f.path(), "variable '" + name + "'", "is not a map over (y, x)");
    std::vector<std::size_t> start(shape.size(), 0), count = shape;
    if (shape.size() == 3) {
        start[0] = index;
        count[0] = 1;
    }
    std::vector<double> raw(g.size());
    f.get_slab(v, start, count, raw.data());
    const auto fill = f.att_double(v, "_FillValue");
    const double factor = si_factor(f, v);
    std::vector<float> out(raw.size());
    for (std::size_t k = 0; k < raw.size(); ++k) out[k] = as_map_value(raw[k], fill) * float(factor);
    return out;
}

// Every value of a map within [lo, hi] where it has one (NaN: no value), and at least one
// value: a map of nothing, or of negative depths, is no map.
void check_map(const std::string& path, const MapLayer& m, double lo, double hi, const std::string& what) {
    std::size_t valued = 0;
    for (std::size_t k = 0; k < m.values.size(); ++k) {
        const float v = m.values[k];
        if (std::isnan(v)) continue;
        ++valued;
        if (!(v >= lo && v <= hi))
            fail(path, "variable '" + m.name + "'",
                 number_text(v) + " at flat index " + std::to_string(k) + " is outside [" + number_text(lo) + ", " +
                     number_text(hi) + "] (" + what + ")");
    }
    if (valued == 0) fail(path, "variable '" + m.name + "'", "holds no value in any cell (all missing): nothing to map");
}

// The extent of a grid's cells, for SceneOf.
std::vector<double> extent_of(const Grid& g) { return {g.x_min_edge(), g.x_max_edge(), g.y_min_edge(), g.y_max_edge()}; }

// Slab `index` of a (group, y, x) statistic, or the (y, x) one, as map values.
std::vector<float> map_of(const std::vector<double>& values, const Grid& g, std::size_t index = 0) {
    std::vector<float> out(g.size());
    for (std::size_t k = 0; k < out.size(); ++k) out[k] = float(values[index * g.size() + k]);
    return out;
}

}  // namespace

std::vector<MapLayer> stats_maps(const std::string& stats_path, Grid& grid, cf::GridMapping& crs, SceneOf* scene) {
    namespace schema = stats_file;
    const nc::File f = schema::open_checked(stats_path, "--stats");
    grid = schema::map_grid(f);
    crs = cf::read_crs(f, schema::pass_probability.name);
    if (scene) {
        const double coarsen = f.att_double(NC_GLOBAL, schema::attribute::map_coarsen).value_or(1.0);
        *scene = SceneOf{stats_path, grid.dx / std::max(coarsen, 1.0),
                         f.att_text(NC_GLOBAL, schema::attribute::scene_buildings_sha256).value_or(""), crs, extent_of(grid)};
    }
    const auto bodies = f.get_strings(f.var(schema::group_body.name)), variants = f.get_strings(f.var(schema::group_variant.name));
    const std::vector<double> probability = schema::read_values(f, schema::pass_probability),
                              speed = schema::read_values(f, schema::max_debris_speed);
    if (bodies.size() != variants.size() || probability.size() != bodies.size() * grid.size())
        fail(stats_path, std::string("variable '") + schema::pass_probability.name + "'",
             "is not a map over (group, y, x) of the file's groups and grid");
    const std::string p_name = schema::pass_probability.name, v_name = schema::max_debris_speed.name;
    std::vector<MapLayer> maps;
    for (std::size_t k = 0; k < bodies.size(); ++k) {
        const std::string group = bodies[k] + " " + variants[k];
        const std::string stem = file_safe(bodies[k] + "_" + variants[k]);
        maps.push_back({p_name + "_" + stem, "fraction of the trajectories of " + group + " whose centre passes the cell", "1",
                        map_of(probability, grid, k), "pass probability, " + group});
        maps.push_back({v_name + "_" + stem, "largest speed of " + group + " in the cell [m/s]", "m s-1", map_of(speed, grid, k),
                        "largest debris speed, " + group});
    }
    maps.push_back({schema::pass_probability_all.name, "fraction of all trajectories whose centre passes the cell", "1",
                    map_of(schema::read_values(f, schema::pass_probability_all), grid), "pass probability, all tracks"});
    maps.push_back({schema::max_debris_speed_all.name, "largest body speed in the cell over all trajectories [m/s]", "m s-1",
                    map_of(schema::read_values(f, schema::max_debris_speed_all), grid), "largest debris speed, all tracks"});
    // Values were checked as the file was opened; a probability map of nothing is no map.
    for (const MapLayer& m : maps)
        if (m.units == "1") check_map(stats_path, m, 0.0, 1.0, "a fraction of trajectories");
    // A cell no body passes holds nothing: no value, in the probability and the speed maps
    // (each speed map follows the probability map before it).
    float speed_top = 0;
    for (std::size_t k = 0; k + 1 < maps.size(); k += 2) {
        std::vector<float>& p = maps[k].values;
        std::vector<float>& v = maps[k + 1].values;
        for (std::size_t c = 0; c < p.size(); ++c)
            if (!(p[c] > 0)) p[c] = v[c] = no_value;
        for (float x : v)
            if (x > speed_top) speed_top = x;
    }
    for (MapLayer& m : maps)
        m.style = m.name.rfind(p_name, 0) == 0 ? qgis::probability_classes(styles::probability_colours, 0.8)
                                               : qgis::ramp(qgis::round_ceiling(speed_top), styles::debris_speed_colours, "m s-1");
    return maps;
}

namespace {

// One flow's stored maps and what it says of its scene, checked: never missing depth or
// speed, arrival within the run.
struct OneFlow {
    Grid grid;
    cf::GridMapping crs;
    std::vector<float> bed;
    std::string fingerprint;
    double flood_depth = 0.0, end_time = 0.0, arrival_depth = std::nan("");
    MapLayer depth, speed, arrival;
};

OneFlow read_flow(const std::string& path) {
    const nc::File f = nc::File::open_read(path);
    cf::require_kind(f, {"flow"}, "--flow");
    for (const char* v : {"max_depth", "max_speed", "arrival_time", "time", "z"})
        if (!f.has_var(v)) fail(path, std::string("variable '") + v + "'", "missing: not a flow written by `flotsam hydro`");
    OneFlow o;
    o.grid = grid_of(f);
    o.crs = cf::read_crs(f, "h");
    o.bed = read_map(f, "z", o.grid);
    o.fingerprint = f.att_text(NC_GLOBAL, "scene_buildings_sha256").value_or("");
    o.arrival_depth = f.att_double(f.var("arrival_time"), "arrival_depth").value_or(std::nan(""));
    const std::vector<double> time = nc::read_finite(f, "time");
    o.end_time = time.back();
    // Flooded: deeper than the flow's flood_depth (its `flooded` flag), else than its dry tolerance.
    o.flood_depth = f.has_var("flooded") ? f.att_double(f.var("flooded"), "flood_depth").value_or(0.0)
                                         : f.att_double(NC_GLOBAL, "dry_depth_m").value_or(0.0);
    o.depth = {"max_depth", "", "m", read_map(f, "max_depth", o.grid)};
    o.speed = {"max_speed", "", "m s-1", read_map(f, "max_speed", o.grid)};
    o.arrival = {"arrival_time", "", "s", read_map(f, "arrival_time", o.grid)};
    for (const MapLayer* m : {&o.depth, &o.speed})
        for (std::size_t c = 0; c < m->values.size(); ++c)
            if (std::isnan(m->values[c]))
                fail(path, "variable '" + m->name + "'",
                     "missing (NaN or a fill value) at flat index " + std::to_string(c) +
                         ": a flow stores a value in every cell (0 where always dry)");
    check_map(path, o.depth, 0.0, 11000.0, "a water depth in m");
    check_map(path, o.speed, 0.0, 1000.0, "a speed in m/s");
    if (std::any_of(o.arrival.values.begin(), o.arrival.values.end(), [](float v) { return !std::isnan(v); }))
        check_map(path, o.arrival, time.front() - 1e-6, time.back() + 1e-6,
                  "an arrival time within the run's " + number_text(time.front()) + " to " + number_text(time.back()) + " s");
    return o;
}

// An envelope is over flows of one scene, on one window.
void check_same_flow_scene(const OneFlow& o, const std::string& path, const OneFlow& first, const std::string& first_path) {
    const Grid &g = o.grid, &grid = first.grid;
    if (g.nx != grid.nx || g.ny != grid.ny || g.x0 != grid.x0 || g.y0 != grid.y0 || g.dx != grid.dx)
        fail(path, "x, y", "a different grid from " + first_path + " (an ensemble's flows share one output window)");
    cf::check_same_crs(path, o.crs, first_path, first.crs);
    for (std::size_t c = 0; c < o.bed.size(); ++c)
        if (!(o.bed[c] == first.bed[c] || (std::isnan(o.bed[c]) && std::isnan(first.bed[c]))))
            fail(path, "variable 'z'",
                 "the bed differs from that of " + first_path + " at flat index " + std::to_string(c) + " (" + number_text(o.bed[c]) +
                     " and " + number_text(first.bed[c]) +
                     " m): the flows come from different scenes, and an envelope is over one scene's flows");
    if (!first.fingerprint.empty() && !o.fingerprint.empty() && o.fingerprint != first.fingerprint)
        fail(path, "",
             "was computed on another scene than " + first_path + " (their scenes' building masks differ: scene_buildings_sha256 " +
                 o.fingerprint + " and " + first.fingerprint + "); an envelope is over one scene's flows");
}

// Titles and colour ramps of the flow maps (depth, onshore depth, speed, arrival).
void style_flow_maps(std::vector<MapLayer>& maps, std::size_t flows, double end_time) {
    const std::string over = flows > 1 ? " (" + std::to_string(flows) + " flows)" : "";
    auto largest = [](const std::vector<float>& v) {
        float top = 0;
        for (float x : v)
            if (x > top) top = x;
        return double(top);
    };
    maps[0].title = "largest water depth" + over;
    maps[0].style = qgis::ramp(qgis::round_ceiling(largest(maps[0].values)), styles::sea_depth_colours, "m", 0.85);
    maps[1].title = "inundation depth onshore" + over;
    maps[1].style = qgis::ramp(qgis::round_ceiling(largest(maps[1].values)), styles::land_depth_colours, "m");
    maps[2].title = "largest flow speed" + over;
    maps[2].style = qgis::ramp(qgis::round_ceiling(largest(maps[2].values)), styles::flow_speed_colours, "m s-1");
    maps[3].title = (flows > 1 ? "earliest arrival" : "arrival time") + over;
    maps[3].style = qgis::ramp(end_time, styles::arrival_colours, "s");
}

}  // namespace

std::vector<MapLayer> flow_maps(const std::vector<std::string>& flow_paths, Grid& grid, cf::GridMapping& crs, SceneOf* scene) {
    if (flow_paths.empty()) fail("--flow", "", "no flow files");
    std::vector<MapLayer> maps = {{"max_depth", "largest water depth over the run", "m", {}},
                                  {"max_speed", "largest depth-averaged speed over the run", "m s-1", {}},
                                  {"arrival_time", "time when the depth first exceeds the arrival depth", "s", {}}};
    OneFlow first;
    double flood_depth = 0.0, end_time = 0.0;
    for (std::size_t k = 0; k < flow_paths.size(); ++k) {
        OneFlow o = read_flow(flow_paths[k]);
        end_time = std::max(end_time, o.end_time);
        flood_depth = k == 0 ? o.flood_depth : std::min(flood_depth, o.flood_depth);
        if (k > 0) {
            check_same_flow_scene(o, flow_paths[k], first, flow_paths[0]);
            for (std::size_t c = 0; c < o.depth.values.size(); ++c) {
                maps[0].values[c] = std::fmax(maps[0].values[c], o.depth.values[c]);
                maps[1].values[c] = std::fmax(maps[1].values[c], o.speed.values[c]);
                maps[2].values[c] = std::fmin(maps[2].values[c], o.arrival.values[c]);
            }
            continue;
        }
        if (!std::isnan(o.arrival_depth)) maps[2].long_name += " (" + std::to_string(o.arrival_depth) + " m)";
        if (scene) *scene = SceneOf{flow_paths[0], o.grid.dx, o.fingerprint, o.crs, extent_of(o.grid)};
        maps[0].values = o.depth.values;
        maps[1].values = o.speed.values;
        maps[2].values = o.arrival.values;
        first = std::move(o);
    }
    grid = first.grid;
    crs = first.crs;
    const std::vector<float>& bed = first.bed;
    // Never flooded: no depth, no speed. Onshore (bed above still water): the inundation depth.
    MapLayer onshore{"inundation_depth", "largest water depth over the run where the bed (buildings included) stands above still water",
                     "m", std::vector<float>(bed.size(), no_value)};
    for (std::size_t c = 0; c < bed.size(); ++c) {
        if (!(maps[0].values[c] > flood_depth)) maps[0].values[c] = maps[1].values[c] = no_value;
        if (bed[c] > 0) onshore.values[c] = maps[0].values[c];
    }
    maps.insert(maps.begin() + 1, onshore);
    if (flow_paths.size() > 1)
        for (auto& m : maps)
            m.long_name = (m.name == "arrival_time" ? "earliest " : "envelope (largest) of the ") + m.long_name + " over " +
                          std::to_string(flow_paths.size()) + " flows";
    style_flow_maps(maps, flow_paths.size(), end_time);
    return maps;
}

qgis::ProjectLayer flow_mesh_layer(const std::string& flow_path, double depth_top) {
    const nc::File f = nc::File::open_read(flow_path);
    cf::require_kind(f, {"flow"}, "--flow");
    // QGIS (MDAL, through GDAL's netCDF driver) makes one dataset group of each gridded
    // variable with the grid mapping, named by its long name, u and v joined into one
    // named without "x-/y-component of", and orders the groups by name.
    auto group_name = [&](int v) {
        std::string n = f.att_text(v, "long_name").value_or(f.var_name(v));
        for (const char* part : {"x-component of ", "y-component of "})
            if (const auto at = n.find(part); at != std::string::npos) n.erase(at, std::string(part).size());
        return n;
    };
    std::vector<std::string> names;
    int nvars = 0;
    nc_inq_nvars(f.id(), &nvars);
    for (int v = 0; v < nvars; ++v) {
        const auto dims = f.dim_names(v);
        if (dims.size() < 2 || dims[dims.size() - 2] != "y" || dims.back() != "x" || !f.att_text(v, "grid_mapping")) continue;
        if (std::find(names.begin(), names.end(), group_name(v)) == names.end()) names.push_back(group_name(v));
    }
    std::sort(names.begin(), names.end());
    auto index_of = [&](const char* var) {
        if (!f.has_var(var)) return -1;
        const auto k = std::find(names.begin(), names.end(), group_name(f.var(var)));
        return k == names.end() ? -1 : int(k - names.begin());
    };
    qgis::MeshStyle style;
    style.scalar_group = index_of("h");
    style.vector_group = index_of("u");
    // Depths over the onshore range (deeper water takes the last colour); dry cells clear,
    // from clear at 0 to the first colour at a thousandth of the range.
    style.scalar = qgis::ramp(depth_top, styles::land_depth_colours, "m", 0.8);
    qgis::ColourStop dry = style.scalar.stops.front();
    dry.alpha = 0;
    dry.label = "dry";
    style.scalar.stops.front().value = 1e-3 * depth_top;
    style.scalar.stops.front().label = qgis::value_label(1e-3 * depth_top, "m");
    style.scalar.stops.insert(style.scalar.stops.begin(), dry);
    style.arrow_min_speed = 1e-3 * std::sqrt(9.81 * depth_top);  // a thousandth of the wave speed at the top depth
    const std::vector<double> time = nc::read_finite(f, "time");
    qgis::ProjectLayer layer;
    layer.kind = qgis::ProjectLayer::Kind::mesh;
    layer.path = flow_path;
    layer.name = "flow " + std::filesystem::path(flow_path).stem().string() + ": depth and velocity in time";
    layer.qml = qgis::mesh_qml(style);
    layer.time_start = time.front();
    layer.time_end = time.back();
    return layer;
}

}  // namespace flotsam::gis
