#include "export/gis_export.hpp"

#include <gdal_alg.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <map>
#include <memory>
#include <optional>

#include "common/atomic_file.hpp"
#include "common/checks.hpp"
#include "common/error.hpp"
#include "common/netcdf.hpp"
#include "common/units.hpp"
#include "data/gdal_support.hpp"
#include "formats/scene.hpp"
#include "formats/stats_file.hpp"
#include "sweep/sweep_file.hpp"

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

// <stem>.part<ext>: a temporary name that keeps the extension (GDAL's vector drivers
// go by it), renamed when complete. Shapefile sidecars (.shx, .dbf, .prj, .cpg) follow.
std::string partial_name(const std::string& path) {
    std::filesystem::path p(path);
    return (p.parent_path() / (p.stem().string() + ".part" + p.extension().string())).string();
}

void remove_with_sidecars(const std::string& path) {
    std::filesystem::path p(path);
    std::error_code ec;
    std::filesystem::remove(p, ec);
    if (p.extension() == ".shp")
        for (const char* ext : {".shx", ".dbf", ".prj", ".cpg"})
            std::filesystem::remove(std::filesystem::path(p).replace_extension(ext), ec);
}

void rename_with_sidecars(const std::string& from, const std::string& to) {
    std::filesystem::path a(from), b(to);
    std::filesystem::rename(a, b);
    if (b.extension() == ".shp")
        for (const char* ext : {".shx", ".dbf", ".prj", ".cpg"}) {
            auto sa = std::filesystem::path(a).replace_extension(ext), sb = std::filesystem::path(b).replace_extension(ext);
            if (std::filesystem::exists(sa)) std::filesystem::rename(sa, sb);
        }
}

void add_field(OGRLayer& layer, const std::string& out_path, const std::string& name, OGRFieldType type) {
    OGRFieldDefn d(name.c_str(), type);
    if (layer.CreateField(&d) != OGRERR_NONE) fail(out_path, "field '" + name + "'", "cannot create: " + gdal::last_error());
}

// One layer of `geometry` in `crs` (read from `crs_file` for messages) written by
// `write(layer)`, which returns the features written, into a file of GDAL's
// `driver_name` under a temporary name: renamed (with shapefile sidecars) when complete,
// removed when `write` throws.
template <class Write>
std::size_t write_vector_layer(const std::string& out_path, const char* driver_name, const char* layer_name,
                               const cf::GridMapping& crs, const std::string& crs_file, OGRwkbGeometryType geometry, Write write) {
    ensure_parent_dir(out_path);
    const std::string temp = partial_name(out_path);
    remove_with_sidecars(temp);
    GDALDriver* driver = GetGDALDriverManager()->GetDriverByName(driver_name);
    if (!driver) fail(out_path, "GDAL", std::string("no ") + driver_name + " driver");
    std::size_t written = 0;
    try {
        gdal::Dataset ds(driver->Create(temp.c_str(), 0, 0, 0, GDT_Unknown, nullptr));
        if (!ds) fail(out_path, "GDAL", "cannot create: " + gdal::last_error());
        std::optional<OGRSpatialReference> srs;
        if (!crs.empty()) srs = gdal::spatial_ref(crs, crs_file);
        OGRLayer* layer = ds->CreateLayer(layer_name, srs ? &*srs : nullptr, geometry, nullptr);
        if (!layer) fail(out_path, std::string("layer '") + layer_name + "'", "cannot create: " + gdal::last_error());
        written = write(*layer);
    } catch (...) {
        remove_with_sidecars(temp);
        throw;
    }
    remove_with_sidecars(out_path);
    rename_with_sidecars(temp, out_path);
    return written;
}

}  // namespace

std::string file_safe(const std::string& label) {
    std::string s;
    for (char c : label) s += std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' ? c : (c == '+' ? '-' : '_');
    return s;
}

void write_cog(const std::string& path, const Grid& g, const cf::GridMapping& crs, const MapLayer& layer,
               const std::string& source) {
    gdal::init();
    if (layer.values.size() != g.size()) fail(path, layer.name, "map size does not match its grid");
    ensure_parent_dir(path);
    GDALDriver* mem = GetGDALDriverManager()->GetDriverByName("MEM");
    GDALDriver* cog = GetGDALDriverManager()->GetDriverByName("COG");
    if (!mem || !cog) fail(path, "GDAL", "the MEM or COG driver is missing (GDAL 3.1 or later is needed)");
    gdal::Dataset d(mem->Create("", g.nx, g.ny, 1, GDT_Float32, nullptr));
    if (!d) fail(path, "GDAL", "cannot create an in-memory raster: " + gdal::last_error());
    double gt[6];
    gdal::geotransform(g, gt);
    d->SetGeoTransform(gt);
    if (!crs.empty()) {
        const OGRSpatialReference s = gdal::spatial_ref(crs, path);
        d->SetSpatialRef(&s);
    }
    // North-up: GeoTIFF row 0 is flotsam's last (northern) row.
    std::vector<float> rows(layer.values.size());
    for (int j = 0; j < g.ny; ++j)
        std::copy_n(layer.values.begin() + std::ptrdiff_t(j) * g.nx, g.nx, rows.begin() + std::ptrdiff_t(g.ny - 1 - j) * g.nx);
    GDALRasterBand* band = d->GetRasterBand(1);
    if (band->RasterIO(GF_Write, 0, 0, g.nx, g.ny, rows.data(), g.nx, g.ny, GDT_Float32, 0, 0, nullptr) != CE_None)
        fail(path, layer.name, "cannot fill the raster: " + gdal::last_error());
    band->SetNoDataValue(std::nan(""));
    band->SetDescription(layer.name.c_str());
    band->SetUnitType(layer.units.c_str());
    d->SetMetadataItem("long_name", layer.long_name.c_str());
    d->SetMetadataItem("units", layer.units.c_str());
    d->SetMetadataItem("source", source.c_str());
    d->SetMetadataItem("crs", crs.empty() ? "none: local metres" : crs.name().c_str());

    AtomicOutput out(path);
    const char* options[] = {"COMPRESS=DEFLATE", "PREDICTOR=YES", "BLOCKSIZE=256", "OVERVIEWS=AUTO", "RESAMPLING=AVERAGE", nullptr};
    gdal::Dataset written(cog->CreateCopy(out.temp_path().c_str(), d.get(), FALSE, const_cast<char**>(options), nullptr, nullptr));
    if (!written) fail(path, layer.name, "GDAL could not write the Cloud-Optimised GeoTIFF: " + gdal::last_error());
    written.reset();  // flush and close before the rename
    // GDAL may leave an .aux.xml beside the temporary file; it carries nothing COG lacks.
    std::error_code ec;
    std::filesystem::remove(out.temp_path() + ".aux.xml", ec);
    out.commit();
}

namespace {

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

}  // namespace

std::vector<MapLayer> stats_maps(const std::string& stats_path, Grid& grid, cf::GridMapping& crs, SceneOf* scene) {
    namespace schema = stats_file;
    const nc::File f = nc::File::open_read(stats_path);
    cf::require_kind(f, {schema::kind}, "--stats");
    for (const char* v :
         {schema::pass_probability.name, schema::max_debris_speed.name, schema::group_body.name, schema::group_variant.name})
        if (!f.has_var(v)) fail(stats_path, std::string("variable '") + v + "'", "missing: not a file written by `flotsam stats`");
    grid = grid_of(f);
    crs = cf::read_crs(f, schema::pass_probability.name);
    if (scene) {
        const double coarsen = f.att_double(NC_GLOBAL, schema::attribute::map_coarsen).value_or(1.0);
        *scene = SceneOf{stats_path, grid.dx / std::max(coarsen, 1.0),
                         f.att_text(NC_GLOBAL, schema::attribute::scene_buildings_sha256).value_or(""), crs};
    }
    const auto bodies = f.get_strings(f.var(schema::group_body.name)), variants = f.get_strings(f.var(schema::group_variant.name));
    const std::string probability = schema::pass_probability.name, speed = schema::max_debris_speed.name;
    std::vector<MapLayer> maps;
    for (std::size_t k = 0; k < bodies.size(); ++k) {
        const std::string group = bodies[k] + " " + variants[k];
        const std::string stem = file_safe(bodies[k] + "_" + variants[k]);
        maps.push_back({probability + "_" + stem, "fraction of the trajectories of " + group + " whose centre passes the cell", "1",
                        read_map(f, probability, grid, k)});
        maps.push_back(
            {speed + "_" + stem, "largest speed of " + group + " in the cell [m/s]", "m s-1", read_map(f, speed, grid, k)});
    }
    maps.push_back({schema::pass_probability_all.name, "fraction of all trajectories whose centre passes the cell", "1",
                    read_map(f, schema::pass_probability_all.name, grid)});
    maps.push_back({schema::max_debris_speed_all.name, "largest body speed in the cell over all trajectories [m/s]", "m s-1",
                    read_map(f, schema::max_debris_speed_all.name, grid)});
    for (const MapLayer& m : maps) {
        if (m.name.rfind(probability, 0) == 0)
            check_map(stats_path, m, 0.0, 1.0, "a fraction of trajectories");
        else if (std::any_of(m.values.begin(), m.values.end(), [](float v) { return !std::isnan(v); }))
            check_map(stats_path, m, 0.0, 1000.0, "a speed in m/s");  // no trajectory passes a cell: all missing is fine
    }
    return maps;
}

std::vector<MapLayer> flow_maps(const std::vector<std::string>& flow_paths, Grid& grid, cf::GridMapping& crs, SceneOf* scene) {
    if (flow_paths.empty()) fail("--flow", "", "no flow files");
    std::vector<MapLayer> maps = {{"max_depth", "largest water depth over the run", "m", {}},
                                  {"max_speed", "largest depth-averaged speed over the run", "m s-1", {}},
                                  {"arrival_time", "time when the depth first exceeds the arrival depth", "s", {}}};
    std::vector<float> bed;
    std::string fingerprint;
    for (std::size_t k = 0; k < flow_paths.size(); ++k) {
        const nc::File f = nc::File::open_read(flow_paths[k]);
        cf::require_kind(f, {"flow"}, "--flow");
        for (const char* v : {"max_depth", "max_speed", "arrival_time", "time", "z"})
            if (!f.has_var(v))
                fail(flow_paths[k], std::string("variable '") + v + "'", "missing: not a flow written by `flotsam hydro`");
        const Grid g = grid_of(f);
        const cf::GridMapping this_crs = cf::read_crs(f, "h");
        const std::vector<float> z = read_map(f, "z", g);
        const std::string this_fingerprint = f.att_text(NC_GLOBAL, "scene_buildings_sha256").value_or("");
        if (k == 0) {
            grid = g;
            crs = this_crs;
            bed = z;
            fingerprint = this_fingerprint;
            if (const auto depth = f.att_double(f.var("arrival_time"), "arrival_depth"))
                maps[2].long_name += " (" + std::to_string(*depth) + " m)";
        } else {
            // An envelope is over flows of one scene, on one window.
            if (g.nx != grid.nx || g.ny != grid.ny || g.x0 != grid.x0 || g.y0 != grid.y0 || g.dx != grid.dx)
                fail(flow_paths[k], "x, y",
                     "a different grid from " + flow_paths[0] + " (an ensemble's flows share one output window)");
            cf::check_same_crs(flow_paths[k], this_crs, flow_paths[0], crs);
            for (std::size_t c = 0; c < z.size(); ++c)
                if (!(z[c] == bed[c] || (std::isnan(z[c]) && std::isnan(bed[c]))))
                    fail(flow_paths[k], "variable 'z'",
                         "the bed differs from that of " + flow_paths[0] + " at flat index " + std::to_string(c) + " (" +
                             number_text(z[c]) + " and " + number_text(bed[c]) +
                             " m): the flows come from different scenes, and an envelope is over one scene's flows");
            if (!fingerprint.empty() && !this_fingerprint.empty() && this_fingerprint != fingerprint)
                fail(flow_paths[k], "",
                     "was computed on another scene than " + flow_paths[0] +
                         " (their scenes' building masks differ: scene_buildings_sha256 " + this_fingerprint + " and " +
                         fingerprint + "); an envelope is over one scene's flows");
        }
        const std::vector<double> time = nc::read_finite(f, "time");
        MapLayer depth{"max_depth", "", "m", read_map(f, "max_depth", g)},
            speed{"max_speed", "", "m s-1", read_map(f, "max_speed", g)},
            arrival{"arrival_time", "", "s", read_map(f, "arrival_time", g)};
        // The maps a flow stores: never missing depth or speed, arrival within the run.
        for (const MapLayer* m : {&depth, &speed})
            for (std::size_t c = 0; c < m->values.size(); ++c)
                if (std::isnan(m->values[c]))
                    fail(flow_paths[k], "variable '" + m->name + "'",
                         "missing (NaN or a fill value) at flat index " + std::to_string(c) +
                             ": a flow stores a value in every cell (0 where always dry)");
        check_map(flow_paths[k], depth, 0.0, 11000.0, "a water depth in m");
        check_map(flow_paths[k], speed, 0.0, 1000.0, "a speed in m/s");
        if (std::any_of(arrival.values.begin(), arrival.values.end(), [](float v) { return !std::isnan(v); }))
            check_map(flow_paths[k], arrival, time.front() - 1e-6, time.back() + 1e-6,
                      "an arrival time within the run's " + number_text(time.front()) + " to " + number_text(time.back()) + " s");
        if (scene && k == 0) *scene = SceneOf{flow_paths[0], g.dx, fingerprint, crs};
        const std::vector<float>& depth_values = depth.values;
        const std::vector<float>& speed_values = speed.values;
        const std::vector<float>& arrival_values = arrival.values;
        if (k == 0) {
            maps[0].values = depth_values;
            maps[1].values = speed_values;
            maps[2].values = arrival_values;
            continue;
        }
        for (std::size_t c = 0; c < depth_values.size(); ++c) {
            maps[0].values[c] = std::fmax(maps[0].values[c], depth_values[c]);
            maps[1].values[c] = std::fmax(maps[1].values[c], speed_values[c]);
            maps[2].values[c] = std::fmin(maps[2].values[c], arrival_values[c]);
        }
    }
    if (flow_paths.size() > 1)
        for (auto& m : maps)
            m.long_name = (m.name == "arrival_time" ? "earliest " : "envelope (largest) of the ") + m.long_name + " over " +
                          std::to_string(flow_paths.size()) + " flows";
    return maps;
}

std::size_t write_tracks(const std::string& trajectory_path, const std::string& out_path, SceneOf* scene, bool check_only) {
    gdal::init();
    check_output_file("--out-dir", out_path);
    const nc::File f = nc::File::open_read(trajectory_path);
    cf::require_kind(f, {"trajectories", "sweep"}, "--trajectories");
    for (const char* v : {"x", "y", "time", "trajectory_id"})
        if (!f.has_var(v))
            fail(trajectory_path, std::string("variable '") + v + "'", "missing: not a flotsam trajectory or sweep file");
    // A sweep file goes through its reader, which checks its tables against each other
    // (member ids, flow indices, the body and variant tables, finite tracks, status flags).
    if (cf::kind_of(f) == "sweep") (void)sweep::read_sweep_file(trajectory_path);
    if (f.value_dims(f.var("trajectory_id")) != std::vector<std::string>{"trajectory"})
        fail(trajectory_path, "variable 'trajectory_id'", "must be one-dimensional on dimension 'trajectory'");
    const std::string ext = std::filesystem::path(out_path).extension().string();
    const char* driver_name = ext == ".gpkg"                          ? "GPKG"
                              : (ext == ".geojson" || ext == ".json") ? "GeoJSON"
                              : ext == ".shp"                         ? "ESRI Shapefile"
                                                                      : nullptr;
    if (!driver_name) fail(out_path, "extension", "'" + ext + "': use .gpkg (GeoPackage), .geojson or .shp");
    const std::size_t ntraj = f.dim_length("trajectory"), nt = f.dim_length("time");
    // Every track variable on (trajectory, time), every per-trajectory one on trajectory:
    // a transposed or short table is a named error, never lines drawn through wrong values.
    auto track_var = [&](const char* name) {
        const int id = f.var(name);
        if (f.dim_names(id) != std::vector<std::string>{"trajectory", "time"} || f.shape(id) != std::vector<std::size_t>{ntraj, nt})
            fail(trajectory_path, std::string("variable '") + name + "'",
                 "must have dimensions (trajectory, time) = (" + std::to_string(ntraj) + ", " + std::to_string(nt) + ")");
        return id;
    };
    const std::vector<double> time = nc::read_finite(f, "time");
    if (f.dim_names(f.var("time")) != std::vector<std::string>{"time"})
        fail(trajectory_path, "variable 'time'", "must be one-dimensional on dimension 'time'");
    for (std::size_t k = 1; k < time.size(); ++k)
        if (!(time[k] > time[k - 1]))
            fail(trajectory_path, "variable 'time'", "must increase (at index " + std::to_string(k) + ")");
    const std::vector<double> x = f.get_double(track_var("x")), y = f.get_double(track_var("y"));
    const bool has_speed = f.has_var("u") && f.has_var("v");
    const std::vector<double> u = has_speed ? f.get_double(track_var("u")) : std::vector<double>{},
                              v = has_speed ? f.get_double(track_var("v")) : std::vector<double>{};
    // Positions are numbers: flotsam writes every sample of every track.
    for (const auto* series : {&x, &y, &u, &v})
        for (std::size_t k = 0; k < series->size(); ++k)
            if (!std::isfinite((*series)[k]) || std::fabs((*series)[k]) >= 1e12)
                fail(trajectory_path,
                     std::string("variable '") +
                         (series == &x   ? "x"
                          : series == &y ? "y"
                          : series == &u ? "u"
                                         : "v") +
                         "'",
                     "trajectory " + std::to_string(k / std::max<std::size_t>(nt, 1)) + ", time index " +
                         std::to_string(k % std::max<std::size_t>(nt, 1)) + ": " + number_text((*series)[k]) +
                         " is not a position or speed (NaN, infinite or a fill value)");
    const cf::GridMapping crs = cf::read_crs(f, "yaw");

    // The per-trajectory variables, in the file's order, become attributes.
    struct Column {
        std::string name;
        nc_type type;
        std::vector<std::string> text;
        std::vector<double> number;
    };
    std::vector<Column> columns;
    int nvars = 0;
    nc_inq_nvars(f.id(), &nvars);
    for (int id = 0; id < nvars; ++id) {
        const auto dims = f.value_dims(id);  // a string column's: without its string length
        if (dims.empty() || dims[0] != "trajectory" || (dims.size() == 2 && dims[1] == "time")) continue;
        if (dims.size() != 1 || f.value_shape(id)[0] != ntraj)
            fail(trajectory_path, "variable '" + f.var_name(id) + "'", "must be one-dimensional on dimension 'trajectory'");
        nc_type type{};
        nc_inq_vartype(f.id(), id, &type);
        if (type == NC_CHAR) type = NC_STRING;  // strings either way: a character array, or NC_STRING in older files
        Column c{f.var_name(id), type, {}, {}};
        if (type == NC_STRING)
            c.text = f.get_strings(id);
        else
            c.number = f.get_double(id);
        columns.push_back(std::move(c));
    }
    if (scene) *scene = SceneOf{trajectory_path, 0.0, f.att_text(NC_GLOBAL, "scene_buildings_sha256").value_or(""), crs};
    if (check_only) return ntraj;

    return write_vector_layer(out_path, driver_name, "tracks", crs, trajectory_path, wkbLineString, [&](OGRLayer& layer) {
        std::size_t written = 0;
        for (const auto& c : columns)
            add_field(layer, out_path, c.name,
                      c.type == NC_STRING                                             ? OFTString
                      : (c.type == NC_INT || c.type == NC_BYTE || c.type == NC_SHORT) ? OFTInteger
                                                                                      : OFTReal);
        for (const char* name : {"t_start", "t_end", "path_length", "max_speed"}) add_field(layer, out_path, name, OFTReal);
        for (std::size_t b = 0; b < ntraj; ++b) {
            OGRLineString line;
            double length = 0.0, vmax = 0.0, t0 = std::nan(""), t1 = std::nan("");
            double px = 0.0, py = 0.0;
            for (std::size_t k = 0; k < nt; ++k) {
                const double xb = x[b * nt + k], yb = y[b * nt + k];
                if (!std::isfinite(xb) || !std::isfinite(yb) || std::abs(xb) >= 0.5 * cf::fill_value) continue;
                if (line.getNumPoints() > 0) length += std::hypot(xb - px, yb - py);
                line.addPoint(xb, yb);
                px = xb;
                py = yb;
                if (std::isnan(t0)) t0 = time[k];
                t1 = time[k];
                if (has_speed) vmax = std::max(vmax, std::hypot(u[b * nt + k], v[b * nt + k]));
            }
            if (line.getNumPoints() == 0) continue;
            if (line.getNumPoints() == 1) line.addPoint(px, py);  // one sample: a line needs two points
            OGRFeature feature(layer.GetLayerDefn());
            for (std::size_t c = 0; c < columns.size(); ++c) {
                const auto& col = columns[c];
                if (col.type == NC_STRING)
                    feature.SetField(int(c), col.text[b].c_str());
                else if (col.type == NC_INT || col.type == NC_BYTE || col.type == NC_SHORT)
                    feature.SetField(int(c), int(col.number[b]));
                else
                    feature.SetField(int(c), col.number[b]);
            }
            feature.SetField("t_start", t0);
            feature.SetField("t_end", t1);
            feature.SetField("path_length", length);
            feature.SetField("max_speed", vmax);
            feature.SetGeometry(&line);
            if (layer.CreateFeature(&feature) != OGRERR_NONE)
                fail(out_path, "trajectory " + std::to_string(b), "cannot write: " + gdal::last_error());
            ++written;
        }
        return written;
    });
}

std::size_t write_building_footprints(const std::string& scene_path, const std::string& stats_path, const std::string& out_path) {
    gdal::init();
    const Scene scene = read_scene(scene_path);
    const std::vector<std::int32_t> ids = scene_building_ids(scene);
    if (ids.empty()) fail(scene_path, "variable 'building'", "the scene has no buildings to export");
    const nc::File st = nc::File::open_read(stats_path);
    cf::require_kind(st, {stats_file::kind});
    const std::string fingerprint = st.att_text(NC_GLOBAL, stats_file::attribute::scene_buildings_sha256).value_or("");
    if (!fingerprint.empty() && fingerprint != scene_buildings_sha256(scene))
        fail(stats_path, "scene_buildings_sha256",
             "comes from another scene than " + scene_path + " (grid or building mask differ)");
    if (!st.has_var(stats_file::building_id.name))
        fail(stats_path, "variable 'building_id'",
             "missing: statistics written before impacts were recorded (run flotsam stats again)");
    const std::vector<int> stat_ids = st.get_int(st.var(stats_file::building_id.name));
    const stats_file::BuildingVariables& b = stats_file::building_all;
    const stats_file::Variable* columns[] = {&b.hit_probability, &b.first_hit_time, &b.impact_count, &b.speed_median, &b.speed_p90,
                                             &b.speed_max,       &b.force_median,   &b.force_p90,    &b.force_max};
    const char* field_names[] = {"hit_probability", "first_hit_time_s", "impacts",     "speed_median_m_s", "speed_p90_m_s",
                                 "speed_max_m_s",   "force_median_N",   "force_p90_N", "force_max_N"};
    std::vector<std::vector<double>> values;
    for (const auto* c : columns) {
        values.push_back(st.get_double(st.var(c->name)));
        if (values.back().size() != stat_ids.size())
            fail(stats_path, std::string("variable '") + c->name + "'", "is not on dimension 'building'");
    }

    // The ids as a north-up Int32 raster, polygonised (4-connected pieces of one value),
    // then the pieces of each id joined.
    const Grid& g = scene.grid;
    GDALDriver* mem = GetGDALDriverManager()->GetDriverByName("MEM");
    if (!mem) fail(out_path, "GDAL", "the MEM driver is missing");
    gdal::Dataset raster(mem->Create("", g.nx, g.ny, 1, GDT_Int32, nullptr));
    double gt[6];
    gdal::geotransform(g, gt);
    raster->SetGeoTransform(gt);
    std::vector<std::int32_t> rows(ids.size());
    for (int j = 0; j < g.ny; ++j)
        std::copy_n(ids.begin() + std::ptrdiff_t(j) * g.nx, g.nx, rows.begin() + std::ptrdiff_t(g.ny - 1 - j) * g.nx);
    GDALRasterBand* band = raster->GetRasterBand(1);
    if (band->RasterIO(GF_Write, 0, 0, g.nx, g.ny, rows.data(), g.nx, g.ny, GDT_Int32, 0, 0, nullptr) != CE_None)
        fail(out_path, "buildings", "cannot fill the raster: " + gdal::last_error());
    band->SetNoDataValue(0.0);
    GDALDriver* memory = GetGDALDriverManager()->GetDriverByName("Memory");  // vector, in memory
    if (!memory) memory = mem;
    gdal::Dataset pieces(memory->Create("", 0, 0, 0, GDT_Unknown, nullptr));
    OGRLayer* piece_layer = pieces ? pieces->CreateLayer("pieces", nullptr, wkbPolygon, nullptr) : nullptr;
    if (!piece_layer) fail(out_path, "GDAL", "cannot create an in-memory vector layer: " + gdal::last_error());
    OGRFieldDefn id_field("id", OFTInteger);
    piece_layer->CreateField(&id_field);
    if (GDALPolygonize(GDALRasterBand::ToHandle(band), GDALRasterBand::ToHandle(band->GetMaskBand()),
                       OGRLayer::ToHandle(piece_layer), 0, nullptr, nullptr, nullptr) != CE_None)
        fail(out_path, "buildings", "GDAL could not polygonise the building ids: " + gdal::last_error());
    std::map<int, OGRMultiPolygon> by_id;
    piece_layer->ResetReading();
    for (OGRFeature* raw; (raw = piece_layer->GetNextFeature()) != nullptr;) {
        std::unique_ptr<OGRFeature, void (*)(OGRFeature*)> f(raw, OGRFeature::DestroyFeature);
        if (const OGRGeometry* geom = f->GetGeometryRef()) by_id[f->GetFieldAsInteger(0)].addGeometry(geom);
    }
    std::map<int, int> cells;
    for (std::int32_t id : ids)
        if (id > 0) ++cells[id];

    return write_vector_layer(out_path, "GPKG", "buildings", scene.crs, scene_path, wkbMultiPolygon, [&](OGRLayer& layer) {
        std::size_t written = 0;
        add_field(layer, out_path, "building_id", OFTInteger);
        add_field(layer, out_path, "cells", OFTInteger);
        add_field(layer, out_path, "area_m2", OFTReal);
        for (std::size_t c = 0; c < 9; ++c) add_field(layer, out_path, field_names[c], c == 2 ? OFTInteger : OFTReal);
        for (auto& [id, parts] : by_id) {
            std::unique_ptr<OGRGeometry> joined(parts.UnionCascaded());
            if (!joined) fail(out_path, "building " + std::to_string(id), "GDAL could not join its cells: " + gdal::last_error());
            std::unique_ptr<OGRGeometry> multi(OGRGeometryFactory::forceToMultiPolygon(joined.release()));
            OGRFeature feature(layer.GetLayerDefn());
            feature.SetField("building_id", id);
            feature.SetField("cells", cells[id]);
            feature.SetField("area_m2", double(cells[id]) * g.dx * g.dy);
            const auto k = std::find(stat_ids.begin(), stat_ids.end(), id);
            for (std::size_t c = 0; c < 9; ++c) {
                const double v = k == stat_ids.end() ? std::nan("") : values[c][std::size_t(k - stat_ids.begin())];
                if (c == 0 || c == 2)
                    feature.SetField(field_names[c], std::isnan(v) ? 0.0 : v);  // never hit: 0 and no impacts
                else if (std::isfinite(v) && std::fabs(v) < 0.5 * cf::fill_value)
                    feature.SetField(field_names[c], v);
                else
                    feature.SetFieldNull(feature.GetFieldIndex(field_names[c]));
            }
            feature.SetGeometry(multi.get());
            if (layer.CreateFeature(&feature) != OGRERR_NONE)
                fail(out_path, "building " + std::to_string(id), "cannot write: " + gdal::last_error());
            ++written;
        }
        return written;
    });
}

}  // namespace flotsam::gis
