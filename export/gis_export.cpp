#include "export/gis_export.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>

#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "common/netcdf.hpp"
#include "data/gdal_support.hpp"

namespace flotsam::gis {

namespace {

constexpr float no_value = std::numeric_limits<float>::quiet_NaN();

// A value that CF files store as missing (fill value or NaN) becomes NaN.
float as_map_value(double v, std::optional<double> fill) {
    if (!std::isfinite(v) || (fill && v == *fill) || std::abs(v) >= 0.5 * cf::fill_value) return no_value;
    return float(v);
}

Grid grid_of(const nc::File& f) { return grid_from_coordinates(nc::read_finite(f, "x"), nc::read_finite(f, "y"), f.path()); }

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
    std::vector<float> out(raw.size());
    for (std::size_t k = 0; k < raw.size(); ++k) out[k] = as_map_value(raw[k], fill);
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

std::vector<MapLayer> stats_maps(const std::string& stats_path, Grid& grid, cf::GridMapping& crs) {
    const nc::File f = nc::File::open_read(stats_path);
    for (const char* v : {"pass_probability", "max_debris_speed", "group_body", "group_variant"})
        if (!f.has_var(v)) fail(stats_path, std::string("variable '") + v + "'", "missing: not a file written by `flotsam stats`");
    grid = grid_of(f);
    crs = cf::read_crs(f, "pass_probability");
    const auto bodies = f.get_strings(f.var("group_body")), variants = f.get_strings(f.var("group_variant"));
    std::vector<MapLayer> maps;
    for (std::size_t k = 0; k < bodies.size(); ++k) {
        const std::string group = bodies[k] + " " + variants[k];
        const std::string stem = file_safe(bodies[k] + "_" + variants[k]);
        maps.push_back({"pass_probability_" + stem, "fraction of the trajectories of " + group + " whose centre passes the cell",
                        "1", read_map(f, "pass_probability", grid, k)});
        maps.push_back({"max_debris_speed_" + stem, "largest speed of " + group + " in the cell [m/s]", "m s-1",
                        read_map(f, "max_debris_speed", grid, k)});
    }
    maps.push_back({"pass_probability_all", "fraction of all trajectories whose centre passes the cell", "1",
                    read_map(f, "pass_probability_all", grid)});
    maps.push_back({"max_debris_speed_all", "largest body speed in the cell over all trajectories [m/s]", "m s-1",
                    read_map(f, "max_debris_speed_all", grid)});
    return maps;
}

std::vector<MapLayer> flow_maps(const std::vector<std::string>& flow_paths, Grid& grid, cf::GridMapping& crs) {
    if (flow_paths.empty()) fail("--flow", "", "no flow files");
    std::vector<MapLayer> maps = {{"max_depth", "largest water depth over the run", "m", {}},
                                  {"max_speed", "largest depth-averaged speed over the run", "m s-1", {}},
                                  {"arrival_time", "time when the depth first exceeds the arrival depth", "s", {}}};
    for (std::size_t k = 0; k < flow_paths.size(); ++k) {
        const nc::File f = nc::File::open_read(flow_paths[k]);
        const Grid g = grid_of(f);
        if (k == 0) {
            grid = g;
            crs = cf::read_crs(f, "h");
            if (const auto depth = f.att_double(f.var("arrival_time"), "arrival_depth"))
                maps[2].long_name += " (" + std::to_string(*depth) + " m)";
        } else if (g.nx != grid.nx || g.ny != grid.ny || g.x0 != grid.x0 || g.y0 != grid.y0 || g.dx != grid.dx) {
            fail(flow_paths[k], "x, y",
                 "a different grid from " + flow_paths[0] + " (an ensemble's flows share one output window)");
        }
        const std::vector<float> depth = read_map(f, "max_depth", g), speed = read_map(f, "max_speed", g),
                                 arrival = read_map(f, "arrival_time", g);
        if (k == 0) {
            maps[0].values = depth;
            maps[1].values = speed;
            maps[2].values = arrival;
            continue;
        }
        for (std::size_t c = 0; c < depth.size(); ++c) {
            maps[0].values[c] = std::fmax(maps[0].values[c], depth[c]);
            maps[1].values[c] = std::fmax(maps[1].values[c], speed[c]);
            maps[2].values[c] = std::fmin(maps[2].values[c], arrival[c]);
        }
    }
    if (flow_paths.size() > 1)
        for (auto& m : maps)
            m.long_name = (m.name == "arrival_time" ? "earliest " : "envelope (largest) of the ") + m.long_name + " over " +
                          std::to_string(flow_paths.size()) + " flows";
    return maps;
}

std::size_t write_tracks(const std::string& trajectory_path, const std::string& out_path) {
    gdal::init();
    const nc::File f = nc::File::open_read(trajectory_path);
    for (const char* v : {"x", "y", "time", "trajectory_id"})
        if (!f.has_var(v))
            fail(trajectory_path, std::string("variable '") + v + "'", "missing: not a flotsam trajectory or sweep file");
    const std::string ext = std::filesystem::path(out_path).extension().string();
    const char* driver_name = ext == ".gpkg"                          ? "GPKG"
                              : (ext == ".geojson" || ext == ".json") ? "GeoJSON"
                              : ext == ".shp"                         ? "ESRI Shapefile"
                                                                      : nullptr;
    if (!driver_name) fail(out_path, "extension", "'" + ext + "': use .gpkg (GeoPackage), .geojson or .shp");
    const std::size_t ntraj = f.dim_length("trajectory"), nt = f.dim_length("time");
    const std::vector<double> time = f.get_double(f.var("time"));
    const std::vector<double> x = f.get_double(f.var("x")), y = f.get_double(f.var("y"));
    const bool has_speed = f.has_var("u") && f.has_var("v");
    const std::vector<double> u = has_speed ? f.get_double(f.var("u")) : std::vector<double>{},
                              v = has_speed ? f.get_double(f.var("v")) : std::vector<double>{};
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
        const auto dims = f.dim_names(id);
        if (dims.size() != 1 || dims[0] != "trajectory") continue;
        nc_type type{};
        nc_inq_vartype(f.id(), id, &type);
        Column c{f.var_name(id), type, {}, {}};
        if (type == NC_STRING)
            c.text = f.get_strings(id);
        else
            c.number = f.get_double(id);
        columns.push_back(std::move(c));
    }

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
        if (!crs.empty()) srs = gdal::spatial_ref(crs, trajectory_path);
        OGRLayer* layer = ds->CreateLayer("tracks", srs ? &*srs : nullptr, wkbLineString, nullptr);
        if (!layer) fail(out_path, "layer 'tracks'", "cannot create: " + gdal::last_error());
        auto add_field = [&](const std::string& name, OGRFieldType t) {
            OGRFieldDefn d(name.c_str(), t);
            if (layer->CreateField(&d) != OGRERR_NONE)
                fail(out_path, "field '" + name + "'", "cannot create: " + gdal::last_error());
        };
        for (const auto& c : columns)
            add_field(c.name, c.type == NC_STRING                                             ? OFTString
                              : (c.type == NC_INT || c.type == NC_BYTE || c.type == NC_SHORT) ? OFTInteger
                                                                                              : OFTReal);
        add_field("t_start", OFTReal);
        add_field("t_end", OFTReal);
        add_field("path_length", OFTReal);
        add_field("max_speed", OFTReal);
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
            OGRFeature feature(layer->GetLayerDefn());
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
            if (layer->CreateFeature(&feature) != OGRERR_NONE)
                fail(out_path, "trajectory " + std::to_string(b), "cannot write: " + gdal::last_error());
            ++written;
        }
    } catch (...) {
        remove_with_sidecars(temp);
        throw;
    }
    remove_with_sidecars(out_path);
    rename_with_sidecars(temp, out_path);
    return written;
}

}  // namespace flotsam::gis
