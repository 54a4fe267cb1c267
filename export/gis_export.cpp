#include "export/gis_export.hpp"

#include <gdal_alg.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
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

// Colours (light to strong): depths in blues (sea paler than land), speeds and
// probabilities in warm colours, arrival from early (dark red) to late (blue).
const std::vector<std::string> sea_depth_colours = {"#eff3ff", "#c6dbef", "#9ecae1", "#6baed6", "#3182bd"};
const std::vector<std::string> land_depth_colours = {"#c7e9f8", "#6cc3ef", "#1f8fd6", "#1750a8", "#2a0f78"};
const std::vector<std::string> flow_speed_colours = {"#fcfdbf", "#feb078", "#f1605d", "#b5367a", "#641a80"};
const std::vector<std::string> arrival_colours = {"#67001f", "#d6604d", "#fddbc7", "#d1e5f0", "#4393c3"};
const std::vector<std::string> probability_colours = {"#ffffb2", "#fed976", "#feb24c", "#fd8d3c", "#f03b20", "#bd0026"};
const std::vector<std::string> debris_speed_colours = {"#0d0887", "#7e03a8", "#cc4778", "#f89540", "#f0f921"};

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
// One layer to write: its name, geometry, styles (the first the default) and writer, which
// returns the features written.
struct VectorLayerDef {
    std::string name;
    OGRwkbGeometryType geometry = wkbUnknown;
    std::vector<qgis::NamedStyle> styles;
    std::function<std::size_t(OGRLayer&)> write;
};

// Layers in `crs` (read from `crs_file` for messages), each written by its `write`, into a
// file of GDAL's `driver_name` under a temporary name: renamed (with shapefile sidecars)
// when complete, removed when a writer throws. A GeoPackage keeps the styles in its
// layer_styles table; another format gets the default style as <stem>.qml beside it
// (QGIS loads it with the file). The GeoPackage's dates are fixed: the same inputs give
// the same bytes. Returns the features written.
std::size_t write_vector_layers(const std::string& out_path, const char* driver_name, const cf::GridMapping& crs,
                                const std::string& crs_file, const std::vector<VectorLayerDef>& defs) {
    ensure_parent_dir(out_path);
    const std::string temp = partial_name(out_path);
    remove_with_sidecars(temp);
    GDALDriver* driver = GetGDALDriverManager()->GetDriverByName(driver_name);
    if (!driver) fail(out_path, "GDAL", std::string("no ") + driver_name + " driver");
    const bool geopackage = std::string(driver_name) == "GPKG";
    std::size_t written = 0;
    CPLSetThreadLocalConfigOption("OGR_CURRENT_DATE", "2000-01-01T00:00:00.000Z");
    try {
        gdal::Dataset ds(driver->Create(temp.c_str(), 0, 0, 0, GDT_Unknown, nullptr));
        if (!ds) fail(out_path, "GDAL", "cannot create: " + gdal::last_error());
        std::optional<OGRSpatialReference> srs;
        if (!crs.empty()) srs = gdal::spatial_ref(crs, crs_file);
        for (const VectorLayerDef& def : defs) {
            OGRLayer* layer = ds->CreateLayer(def.name.c_str(), srs ? &*srs : nullptr, def.geometry, nullptr);
            if (!layer) fail(out_path, "layer '" + def.name + "'", "cannot create: " + gdal::last_error());
            written += def.write(*layer);
            if (geopackage && !def.styles.empty()) qgis::store_styles(*ds, out_path, def.name, def.styles);
        }
    } catch (...) {
        CPLSetThreadLocalConfigOption("OGR_CURRENT_DATE", nullptr);
        remove_with_sidecars(temp);
        throw;
    }
    CPLSetThreadLocalConfigOption("OGR_CURRENT_DATE", nullptr);
    remove_with_sidecars(out_path);
    rename_with_sidecars(temp, out_path);
    if (!geopackage && defs.size() == 1 && !defs[0].styles.empty())
        qgis::write_qml(std::filesystem::path(out_path).replace_extension(".qml").string(), defs[0].styles[0].qml);
    return written;
}

// The pieces (4-connected cells of one value) of every positive id of a grid of ids
// (row-major, southern row first; 0: none), as polygons in the grid's coordinates.
std::map<int, OGRMultiPolygon> polygons_of(const Grid& g, const std::vector<std::int32_t>& ids, const std::string& out_path) {
    GDALDriver* mem = GetGDALDriverManager()->GetDriverByName("MEM");
    if (!mem) fail(out_path, "GDAL", "the MEM driver is missing");
    gdal::Dataset raster(mem->Create("", g.nx, g.ny, 1, GDT_Int32, nullptr));
    double gt[6];
    gdal::geotransform(g, gt);
    raster->SetGeoTransform(gt);
    std::vector<std::int32_t> rows(ids.size());
    for (int j = 0; j < g.ny; ++j)  // north-up
        std::copy_n(ids.begin() + std::ptrdiff_t(j) * g.nx, g.nx, rows.begin() + std::ptrdiff_t(g.ny - 1 - j) * g.nx);
    GDALRasterBand* band = raster->GetRasterBand(1);
    if (band->RasterIO(GF_Write, 0, 0, g.nx, g.ny, rows.data(), g.nx, g.ny, GDT_Int32, 0, 0, nullptr) != CE_None)
        fail(out_path, "polygons", "cannot fill the raster: " + gdal::last_error());
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
        fail(out_path, "polygons", "GDAL could not polygonise the cells: " + gdal::last_error());
    std::map<int, OGRMultiPolygon> by_id;
    piece_layer->ResetReading();
    for (OGRFeature* raw; (raw = piece_layer->GetNextFeature()) != nullptr;) {
        std::unique_ptr<OGRFeature, void (*)(OGRFeature*)> f(raw, OGRFeature::DestroyFeature);
        if (const OGRGeometry* geom = f->GetGeometryRef()) by_id[f->GetFieldAsInteger(0)].addGeometry(geom);
    }
    return by_id;
}

// ---- the styles the vector layers are written with ----

// Distinct colours for categories (matplotlib's "tab10"), repeated beyond ten.
const std::vector<std::string> category_colours = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd",
                                                   "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"};

qgis::Symbol fill(const std::string& colour, const std::string& outline, double width_mm, double opacity = 1.0) {
    return {qgis::Symbol::Kind::fill, colour, outline, width_mm, 2.0, opacity, false};
}

std::string tracks_qml(const std::vector<std::string>& sources) {
    qgis::VectorStyle s;
    s.field = "source";
    for (std::size_t k = 0; k < sources.size(); ++k)
        s.categories.push_back({sources[k],
                                sources[k],
                                {qgis::Symbol::Kind::line, category_colours[k % category_colours.size()], "", 0.15, 2.0, 0.3}});
    s.other = {qgis::Symbol::Kind::line, "#404040", "", 0.15, 2.0, 0.3};
    if (sources.empty()) s.symbol = s.other;
    return qgis::vector_qml(s);
}

std::string buildings_qml() {
    qgis::VectorStyle s;
    s.field = "hit_probability";
    s.classes.push_back({0.0, 0.0, "not hit", fill("#dcdcdc", "#a0a0a0", 0.1)});
    const qgis::RasterStyle p = qgis::probability_classes(probability_colours);
    double lower = 0.0;
    for (const qgis::ColourStop& c : p.stops) {
        s.classes.push_back({lower, c.value, "hit by " + c.label + " of the tracks", fill(c.colour, "#5a5a5a", 0.15)});
        lower = c.value;
    }
    // The force on the buildings that matter (hit by at least 5 % of the tracks): labels on
    // every hit building would cover the map.
    s.labels.expression =
        "CASE WHEN \"hit_probability\" >= 0.05 AND \"force_p90_N\" IS NOT NULL "
        "THEN 'p90 ' || format_number(\"force_p90_N\" / 1000, 0) || ' kN' END";
    s.labels.size_pt = 7;
    return qgis::vector_qml(s);
}

std::string buildings_force_qml() {
    qgis::VectorStyle s;
    s.field = "coalesce(\"force_p90_N\", -1)";
    s.classes = {{-1.0, -1.0, "not hit", fill("#dcdcdc", "#a0a0a0", 0.1)},
                 {0.0, 1e4, "p90 force ≤ 10 kN", fill("#fee5d9", "#5a5a5a", 0.15)},
                 {1e4, 1e5, "10 – 100 kN", fill("#fcae91", "#5a5a5a", 0.15)},
                 {1e5, 1e6, "100 kN – 1 MN", fill("#fb6a4a", "#5a5a5a", 0.15)},
                 {1e6, 1e15, "> 1 MN", fill("#cb181d", "#5a5a5a", 0.15)}};
    return qgis::vector_qml(s);
}

// Debris sources in purple, labelled by `label` (a QGIS expression).
std::string sources_qml(bool points, const std::string& label) {
    qgis::VectorStyle s;
    s.symbol =
        points ? qgis::Symbol{qgis::Symbol::Kind::marker, "#7a0177", "#ffffff", 0.3, 2.6, 1.0, false} : fill("", "#7a0177", 0.7);
    s.labels.expression = label;
    s.labels.size_pt = 8;
    s.labels.colour = "#4a0048";
    s.labels.polygon_inside = !points;
    return qgis::vector_qml(s);
}
const char* source_label = "\"layer\" || coalesce(' (' || \"type\" || ')', '')";

// The scene's named features: gauges black, sections and regions (of the statistics) teal.
std::string feature_qml(qgis::Symbol::Kind kind) {
    qgis::VectorStyle s;
    s.symbol = kind == qgis::Symbol::Kind::marker ? qgis::Symbol{kind, "#202020", "#ffffff", 0.3, 2.0, 1.0, false}
               : kind == qgis::Symbol::Kind::line ? qgis::Symbol{kind, "#00747a", "", 0.6, 2.0, 1.0, false}
                                                  : fill("", "#00747a", 0.5);
    s.labels.expression = "\"name\"";
    s.labels.size_pt = 7;
    s.labels.colour = kind == qgis::Symbol::Kind::marker ? "#202020" : "#00474b";
    s.labels.polygon_inside = kind == qgis::Symbol::Kind::fill;
    return qgis::vector_qml(s);
}

std::string hazard_regions_qml() {
    qgis::VectorStyle s;
    s.field = "flow";
    s.categories = {
        {"inflow", "within ±22.5° of the inflow", {qgis::Symbol::Kind::fill, "#d7301f", "#d7301f", 0.5, 2.0, 0.8, true}},
        {"return flow", "within ±22.5° of the return flow", {qgis::Symbol::Kind::fill, "#f08c00", "#f08c00", 0.5, 2.0, 0.8, true}}};
    s.other = fill("", "#808080", 0.4);
    s.labels.expression = "\"source\"";
    s.labels.size_pt = 7;
    s.labels.colour = "#8a1c0f";
    return qgis::vector_qml(s);
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
    // Exact statistics in the file (STATISTICS_*), so a GIS shows the range without a scan;
    // a map without any value has none.
    double lo = 0, hi = 0, mean = 0, sd = 0;
    if (band->ComputeStatistics(FALSE, &lo, &hi, &mean, &sd, nullptr, nullptr) != CE_None) (void)gdal::last_error();

    // Overviews halving the map until its larger side fits one 256-pixel tile, and at
    // least one (a small map too opens with a pyramid).
    int overviews = 1;
    while ((std::max(g.nx, g.ny) >> overviews) > 256) ++overviews;
    const std::string overview_count = "OVERVIEW_COUNT=" + std::to_string(overviews);
    AtomicOutput out(path);
    const char* options[] = {"COMPRESS=DEFLATE",
                             "PREDICTOR=YES",
                             "BLOCKSIZE=256",
                             "OVERVIEWS=AUTO",
                             "RESAMPLING=AVERAGE",
                             overview_count.c_str(),
                             "OVERVIEW_COMPRESS=DEFLATE",
                             "OVERVIEW_PREDICTOR=YES",
                             nullptr};
    gdal::Dataset written(cog->CreateCopy(out.temp_path().c_str(), d.get(), FALSE, const_cast<char**>(options), nullptr, nullptr));
    if (!written) fail(path, layer.name, "GDAL could not write the Cloud-Optimised GeoTIFF: " + gdal::last_error());
    written.reset();  // flush and close before the rename
    // GDAL may leave an .aux.xml beside the temporary file; it carries nothing COG lacks.
    std::error_code ec;
    std::filesystem::remove(out.temp_path() + ".aux.xml", ec);
    out.commit();
    if (!qgis::empty(layer.style))
        qgis::write_qml(std::filesystem::path(path).replace_extension(".qml").string(), qgis::raster_qml(layer.style));
}

void crop_maps(std::vector<MapLayer>& maps, Grid& g, const Grid& window) {
    const double tol = 1e-6 * g.dx;
    auto first_inside = [&](double origin, double step, int n, double edge) {
        int k = 0;
        while (k < n && origin + k * step < edge - tol) ++k;
        return k;
    };
    auto last_inside = [&](double origin, double step, int n, double edge) {
        int k = n - 1;
        while (k >= 0 && origin + k * step > edge + tol) --k;
        return k;
    };
    int i0 = first_inside(g.x0, g.dx, g.nx, window.x0 - 0.5 * window.dx);
    int i1 = last_inside(g.x0, g.dx, g.nx, window.x0 + (window.nx - 0.5) * window.dx);
    int j0 = first_inside(g.y0, g.dy, g.ny, window.y0 - 0.5 * window.dy);
    int j1 = last_inside(g.y0, g.dy, g.ny, window.y0 + (window.ny - 0.5) * window.dy);
    if (i0 > i1 || j0 > j1) return;  // no overlap: keep the maps whole
    // Nothing with a value is cut away.
    for (const MapLayer& m : maps)
        for (int j = 0; j < g.ny; ++j)
            for (int i = 0; i < g.nx; ++i)
                if (!std::isnan(m.values[g.index(i, j)])) {
                    i0 = std::min(i0, i);
                    i1 = std::max(i1, i);
                    j0 = std::min(j0, j);
                    j1 = std::max(j1, j);
                }
    if (i0 == 0 && j0 == 0 && i1 == g.nx - 1 && j1 == g.ny - 1) return;
    Grid c = g;
    c.nx = i1 - i0 + 1;
    c.ny = j1 - j0 + 1;
    c.x0 = g.x0 + i0 * g.dx;
    c.y0 = g.y0 + j0 * g.dy;
    for (MapLayer& m : maps) {
        std::vector<float> v(c.size());
        for (int j = 0; j < c.ny; ++j)
            for (int i = 0; i < c.nx; ++i) v[c.index(i, j)] = m.values[g.index(i + i0, j + j0)];
        m.values = std::move(v);
    }
    g = c;
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
                        read_map(f, probability, grid, k), "pass probability, " + group});
        maps.push_back({speed + "_" + stem, "largest speed of " + group + " in the cell [m/s]", "m s-1",
                        read_map(f, speed, grid, k), "largest debris speed, " + group});
    }
    maps.push_back({schema::pass_probability_all.name, "fraction of all trajectories whose centre passes the cell", "1",
                    read_map(f, schema::pass_probability_all.name, grid), "pass probability, all tracks"});
    maps.push_back({schema::max_debris_speed_all.name, "largest body speed in the cell over all trajectories [m/s]", "m s-1",
                    read_map(f, schema::max_debris_speed_all.name, grid), "largest debris speed, all tracks"});
    for (const MapLayer& m : maps) {
        if (m.name.rfind(probability, 0) == 0)
            check_map(stats_path, m, 0.0, 1.0, "a fraction of trajectories");
        else if (std::any_of(m.values.begin(), m.values.end(), [](float v) { return !std::isnan(v); }))
            check_map(stats_path, m, 0.0, 1000.0, "a speed in m/s");  // no trajectory passes a cell: all missing is fine
    }
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
        m.style = m.name.rfind(probability, 0) == 0 ? qgis::probability_classes(probability_colours, 0.8)
                                                    : qgis::ramp(qgis::round_ceiling(speed_top), debris_speed_colours, "m s-1");
    return maps;
}

std::vector<MapLayer> flow_maps(const std::vector<std::string>& flow_paths, Grid& grid, cf::GridMapping& crs, SceneOf* scene) {
    if (flow_paths.empty()) fail("--flow", "", "no flow files");
    std::vector<MapLayer> maps = {{"max_depth", "largest water depth over the run", "m", {}},
                                  {"max_speed", "largest depth-averaged speed over the run", "m s-1", {}},
                                  {"arrival_time", "time when the depth first exceeds the arrival depth", "s", {}}};
    std::vector<float> bed;
    std::string fingerprint;
    double flood_depth = 0.0, end_time = 0.0;
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
        end_time = std::max(end_time, time.back());
        // Flooded: deeper than the flow's flood_depth (its `flooded` flag), else than its dry tolerance.
        const double this_flood = f.has_var("flooded") ? f.att_double(f.var("flooded"), "flood_depth").value_or(0.0)
                                                       : f.att_double(NC_GLOBAL, "dry_depth_m").value_or(0.0);
        flood_depth = k == 0 ? this_flood : std::min(flood_depth, this_flood);
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
    // Never flooded: no depth, no speed. Onshore (bed above still water): the inundation depth.
    MapLayer onshore{"inundation_depth",
                     "largest water depth over the run where the bed (buildings included) stands above still water", "m",
                     std::vector<float>(bed.size(), no_value)};
    for (std::size_t c = 0; c < bed.size(); ++c) {
        if (!(maps[0].values[c] > flood_depth)) maps[0].values[c] = maps[1].values[c] = no_value;
        if (bed[c] > 0) onshore.values[c] = maps[0].values[c];
    }
    maps.insert(maps.begin() + 1, onshore);
    if (flow_paths.size() > 1)
        for (auto& m : maps)
            m.long_name = (m.name == "arrival_time" ? "earliest " : "envelope (largest) of the ") + m.long_name + " over " +
                          std::to_string(flow_paths.size()) + " flows";
    const std::string over = flow_paths.size() > 1 ? " (" + std::to_string(flow_paths.size()) + " flows)" : "";
    auto largest = [](const std::vector<float>& v) {
        float top = 0;
        for (float x : v)
            if (x > top) top = x;
        return double(top);
    };
    maps[0].title = "largest water depth" + over;
    maps[0].style = qgis::ramp(qgis::round_ceiling(largest(maps[0].values)), sea_depth_colours, "m", 0.85);
    maps[1].title = "inundation depth onshore" + over;
    maps[1].style = qgis::ramp(qgis::round_ceiling(largest(maps[1].values)), land_depth_colours, "m");
    maps[2].title = "largest flow speed" + over;
    maps[2].style = qgis::ramp(qgis::round_ceiling(largest(maps[2].values)), flow_speed_colours, "m s-1");
    maps[3].title = (flow_paths.size() > 1 ? "earliest arrival" : "arrival time") + over;
    maps[3].style = qgis::ramp(end_time, arrival_colours, "s");
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

    // `source`: where each track's body came from, the GIS feature (a yard's bodies share
    // it) or else the body itself; the tracks are coloured by it.
    auto column_of = [&](const std::string& name) -> Column* {
        for (Column& c : columns)
            if (c.name == name && c.type == NC_STRING) return &c;
        return nullptr;
    };
    if (Column* source = column_of("source")) {  // a debris file: empty where the body has no feature
        const Column* id = column_of("trajectory_id");
        for (std::size_t b = 0; b < ntraj; ++b)
            if (source->text[b].empty() && id) source->text[b] = id->text[b];
    } else if (const Column* body = column_of("body"); body && f.has_var("body_name")) {  // a sweep file: its body table
        const auto names = f.get_strings(f.var("body_name"));
        const auto sources = f.has_var("body_source") ? f.get_strings(f.var("body_source")) : std::vector<std::string>{};
        Column c{"source", NC_STRING, {}, {}};
        for (std::size_t b = 0; b < ntraj; ++b) {
            const auto k = std::size_t(std::find(names.begin(), names.end(), body->text[b]) - names.begin());
            c.text.push_back(k < sources.size() && !sources[k].empty() ? sources[k] : body->text[b]);
        }
        columns.push_back(std::move(c));
    }
    std::vector<std::string> source_names;
    if (const Column* source = column_of("source"))
        for (const std::string& name : source->text)
            if (std::find(source_names.begin(), source_names.end(), name) == source_names.end()) source_names.push_back(name);

    const std::vector<qgis::NamedStyle> styles = {
        {"tracks by source", "thin translucent lines, one colour per debris source", tracks_qml(source_names), true}};
    return write_vector_layers(out_path, driver_name, crs, trajectory_path,
                               {{"tracks", wkbLineString, styles, [&](OGRLayer& layer) {
                                     std::size_t written = 0;
                                     for (const auto& c : columns)
                                         add_field(layer, out_path, c.name,
                                                   c.type == NC_STRING                                             ? OFTString
                                                   : (c.type == NC_INT || c.type == NC_BYTE || c.type == NC_SHORT) ? OFTInteger
                                                                                                                   : OFTReal);
                                     for (const char* name : {"t_start", "t_end", "path_length", "max_speed"})
                                         add_field(layer, out_path, name, OFTReal);
                                     for (std::size_t b = 0; b < ntraj; ++b) {
                                         OGRLineString line;
                                         double length = 0.0, vmax = 0.0, t0 = std::nan(""), t1 = std::nan("");
                                         double px = 0.0, py = 0.0;
                                         for (std::size_t k = 0; k < nt; ++k) {
                                             const double xb = x[b * nt + k], yb = y[b * nt + k];
                                             if (!std::isfinite(xb) || !std::isfinite(yb) || std::abs(xb) >= 0.5 * cf::fill_value)
                                                 continue;
                                             if (line.getNumPoints() > 0) length += std::hypot(xb - px, yb - py);
                                             line.addPoint(xb, yb);
                                             px = xb;
                                             py = yb;
                                             if (std::isnan(t0)) t0 = time[k];
                                             t1 = time[k];
                                             if (has_speed) vmax = std::max(vmax, std::hypot(u[b * nt + k], v[b * nt + k]));
                                         }
                                         if (line.getNumPoints() == 0) continue;
                                         if (line.getNumPoints() == 1)
                                             line.addPoint(px, py);  // one sample: a line needs two points
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
                                             fail(out_path, "trajectory " + std::to_string(b),
                                                  "cannot write: " + gdal::last_error());
                                         ++written;
                                     }
                                     return written;
                                 }}});
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

    const Grid& g = scene.grid;
    std::map<int, OGRMultiPolygon> by_id = polygons_of(g, ids, out_path);
    std::map<int, int> cells;
    for (std::int32_t id : ids)
        if (id > 0) ++cells[id];

    const std::vector<qgis::NamedStyle> styles = {
        {"hit probability", "footprints by the share of tracks that hit them; label: the 90th-percentile impact force",
         buildings_qml(), true},
        {"p90 force", "footprints by the 90th-percentile impact force", buildings_force_qml(), false}};
    return write_vector_layers(
        out_path, "GPKG", scene.crs, scene_path,
        {{"buildings", wkbMultiPolygon, styles, [&](OGRLayer& layer) {
              std::size_t written = 0;
              add_field(layer, out_path, "building_id", OFTInteger);
              add_field(layer, out_path, "cells", OFTInteger);
              add_field(layer, out_path, "area_m2", OFTReal);
              for (std::size_t c = 0; c < 9; ++c) add_field(layer, out_path, field_names[c], c == 2 ? OFTInteger : OFTReal);
              for (auto& [id, parts] : by_id) {
                  std::unique_ptr<OGRGeometry> joined(parts.UnionCascaded());
                  if (!joined)
                      fail(out_path, "building " + std::to_string(id), "GDAL could not join its cells: " + gdal::last_error());
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
          }}});
}

}  // namespace flotsam::gis

namespace flotsam::gis {

std::size_t write_sources(const std::string& sources_path, const cf::GridMapping& crs, const std::string& out_path,
                          bool check_only) {
    gdal::init();
    gdal::Dataset in = gdal::open_vector(sources_path);
    std::optional<OGRSpatialReference> target;
    if (!crs.empty()) {
        target = gdal::spatial_ref(crs, out_path);
        target->SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    }
    // Every feature, carried into the scene's CRS, as an area or a point.
    struct Source {
        std::string layer, type;
        GIntBig feature = 0;
        int count = 0;
        bool has_count = false;
        std::unique_ptr<OGRGeometry> geometry;
    };
    std::vector<Source> areas, points;
    for (int l = 0; l < in->GetLayerCount(); ++l) {
        OGRLayer* layer = in->GetLayer(l);
        const OGRSpatialReference* from = layer->GetSpatialRef();
        if (bool(from) != bool(target))
            fail(sources_path, std::string("layer '") + layer->GetName() + "'",
                 from ? "has a CRS and the scene has none (local metres)" : "has no CRS and the scene has one");
        std::unique_ptr<OGRCoordinateTransformation> to_scene;
        if (from && !from->IsSame(&*target)) {
            OGRSpatialReference source_crs(*from);
            source_crs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
            to_scene.reset(OGRCreateCoordinateTransformation(&source_crs, &*target));
            if (!to_scene)
                fail(sources_path, std::string("layer '") + layer->GetName() + "'", "cannot be carried into the scene's CRS");
        }
        const int type_field = layer->GetLayerDefn()->GetFieldIndex("type");
        const int count_field = layer->GetLayerDefn()->GetFieldIndex("count");
        layer->ResetReading();
        for (OGRFeature* raw; (raw = layer->GetNextFeature()) != nullptr;) {
            std::unique_ptr<OGRFeature, void (*)(OGRFeature*)> f(raw, OGRFeature::DestroyFeature);
            const OGRGeometry* geometry = f->GetGeometryRef();
            if (!geometry) continue;
            Source s{layer->GetName(),
                     type_field >= 0 ? f->GetFieldAsString(type_field) : "",
                     f->GetFID(),
                     count_field >= 0 ? f->GetFieldAsInteger(count_field) : 0,
                     count_field >= 0 && f->IsFieldSetAndNotNull(count_field),
                     std::unique_ptr<OGRGeometry>(geometry->clone())};
            if (to_scene && s.geometry->transform(to_scene.get()) != OGRERR_NONE)
                fail(sources_path, s.layer + " feature " + std::to_string(s.feature), "cannot be carried into the scene's CRS");
            const auto flat = wkbFlatten(s.geometry->getGeometryType());
            if (flat == wkbPolygon || flat == wkbMultiPolygon) {
                s.geometry.reset(OGRGeometryFactory::forceToMultiPolygon(s.geometry.release()));
                areas.push_back(std::move(s));
            } else if (flat == wkbPoint) {
                points.push_back(std::move(s));
            } else {
                fail(sources_path, s.layer + " feature " + std::to_string(s.feature), "is neither a point nor a polygon");
            }
        }
    }
    if (areas.empty() && points.empty()) fail(sources_path, "", "holds no point or polygon feature: no debris source to export");
    if (check_only) return areas.size() + points.size();
    auto writer = [&out_path](std::vector<Source>& sources) {
        return [&out_path, list = &sources](OGRLayer& layer) {
            add_field(layer, out_path, "layer", OFTString);
            add_field(layer, out_path, "feature", OFTInteger64);
            add_field(layer, out_path, "type", OFTString);
            add_field(layer, out_path, "count", OFTInteger);
            for (Source& s : *list) {
                OGRFeature feature(layer.GetLayerDefn());
                feature.SetField("layer", s.layer.c_str());
                feature.SetField("feature", s.feature);
                if (!s.type.empty()) feature.SetField("type", s.type.c_str());
                if (s.has_count) feature.SetField("count", s.count);
                feature.SetGeometry(s.geometry.get());
                if (layer.CreateFeature(&feature) != OGRERR_NONE)
                    fail(out_path, s.layer + " feature " + std::to_string(s.feature), "cannot write: " + gdal::last_error());
            }
            return list->size();
        };
    };
    std::vector<VectorLayerDef> defs;
    if (!areas.empty())
        defs.push_back({"source_areas",
                        wkbMultiPolygon,
                        {{"outlined", "the yards, outlined and labelled", sources_qml(false, source_label), true}},
                        writer(areas)});
    if (!points.empty())
        defs.push_back({"source_points",
                        wkbPoint,
                        {{"points", "single bodies, labelled", sources_qml(true, source_label), true}},
                        writer(points)});
    return write_vector_layers(out_path, "GPKG", crs, sources_path, defs);
}

std::size_t write_hazard_regions(const std::string& regions_path, const std::string& out_path, bool check_only,
                                 cf::GridMapping* crs_out) {
    gdal::init();
    const nc::File f = nc::File::open_read(regions_path);
    for (const char* v : {"x", "y", "source", "region_inflow", "region_outflow"})
        if (!f.has_var(v))
            fail(regions_path, std::string("variable '") + v + "'",
                 "missing: not hazard regions written by pipelines/hazard_region.py");
    const Grid g = grid_of(f);
    const cf::GridMapping crs = cf::read_crs(f, "region_inflow");
    if (crs_out) *crs_out = crs;
    const std::vector<std::string> sources = f.get_strings(f.var("source"));
    struct Region {
        std::string source, flow;
        int cells;
        OGRMultiPolygon shape;
    };
    std::vector<Region> regions;
    for (const auto& [name, flow] : {std::pair{"region_inflow", "inflow"}, std::pair{"region_outflow", "return flow"}}) {
        const int v = f.var(name);
        if (f.shape(v) != std::vector<std::size_t>{sources.size(), std::size_t(g.ny), std::size_t(g.nx)})
            fail(regions_path, std::string("variable '") + name + "'", "must be on (source, y, x)");
        if (check_only) continue;
        const std::vector<int> mask = f.get_int(v);
        for (std::size_t k = 0; k < sources.size(); ++k) {
            std::vector<std::int32_t> ids(g.size());
            int cells = 0;
            for (std::size_t c = 0; c < g.size(); ++c) cells += ids[c] = mask[k * g.size() + c] != 0;
            if (cells == 0) continue;
            std::map<int, OGRMultiPolygon> pieces = polygons_of(g, ids, out_path);
            std::unique_ptr<OGRGeometry> joined(pieces[1].UnionCascaded());
            if (!joined) fail(out_path, sources[k] + " " + flow, "GDAL could not join its cells: " + gdal::last_error());
            std::unique_ptr<OGRGeometry> multi(OGRGeometryFactory::forceToMultiPolygon(joined.release()));
            regions.push_back({sources[k], flow, cells, *multi->toMultiPolygon()});
        }
    }
    if (check_only) return sources.size();
    return write_vector_layers(
        out_path, "GPKG", crs, regions_path,
        {{"hazard_regions",
          wkbMultiPolygon,
          {{"by flow", "the design standard's regions, hatched by flow direction", hazard_regions_qml(), true}},
          [&](OGRLayer& layer) {
              add_field(layer, out_path, "source", OFTString);
              add_field(layer, out_path, "flow", OFTString);
              add_field(layer, out_path, "cells", OFTInteger);
              add_field(layer, out_path, "area_m2", OFTReal);
              for (Region& r : regions) {
                  OGRFeature feature(layer.GetLayerDefn());
                  feature.SetField("source", r.source.c_str());
                  feature.SetField("flow", r.flow.c_str());
                  feature.SetField("cells", r.cells);
                  feature.SetField("area_m2", r.cells * g.dx * g.dy);
                  feature.SetGeometry(&r.shape);
                  if (layer.CreateFeature(&feature) != OGRERR_NONE) fail(out_path, r.source, "cannot write: " + gdal::last_error());
              }
              return regions.size();
          }}});
}

std::size_t write_scene_features(const std::string& scene_path, const std::string& out_path) {
    gdal::init();
    const Scene scene = read_scene(scene_path);
    auto name_field = [&](OGRLayer& layer) { add_field(layer, out_path, "name", OFTString); };
    auto add = [&](OGRLayer& layer, const std::string& name, const OGRGeometry& g, double heading = std::nan("")) {
        OGRFeature feature(layer.GetLayerDefn());
        feature.SetField("name", name.c_str());
        if (!std::isnan(heading)) feature.SetField("heading_deg", heading);
        feature.SetGeometry(&g);
        if (layer.CreateFeature(&feature) != OGRERR_NONE) fail(out_path, name, "cannot write: " + gdal::last_error());
    };
    std::vector<VectorLayerDef> defs;
    for (const char* kind : {"start", "gauge"}) {
        std::vector<ScenePoint> points;
        for (const ScenePoint& p : scene.points)
            if (p.kind == kind) points.push_back(p);
        if (points.empty()) continue;
        const bool start = std::string(kind) == "start";
        defs.push_back({start ? "starts" : "gauges",
                        wkbPoint,
                        {{"labelled", start ? "the scene's debris starts" : "the scene's gauges",
                          start ? sources_qml(true, "\"name\"") : feature_qml(qgis::Symbol::Kind::marker), true}},
                        [&, points, start](OGRLayer& layer) {
                            name_field(layer);
                            if (start) add_field(layer, out_path, "heading_deg", OFTReal);
                            for (const ScenePoint& p : points)
                                add(layer, p.name, OGRPoint(p.x, p.y), start ? p.heading_deg : std::nan(""));
                            return points.size();
                        }});
    }
    if (!scene.sections.empty())
        defs.push_back({"sections",
                        wkbLineString,
                        {{"labelled", "the passage sections", feature_qml(qgis::Symbol::Kind::line), true}},
                        [&](OGRLayer& layer) {
                            name_field(layer);
                            for (const Section& c : scene.sections) {
                                OGRLineString line;
                                line.addPoint(c.x, c.y_min);
                                line.addPoint(c.x, c.y_max);
                                add(layer, c.name, line);
                            }
                            return scene.sections.size();
                        }});
    if (!scene.regions.empty())
        defs.push_back({"regions",
                        wkbPolygon,
                        {{"labelled", "the arrival-count regions", feature_qml(qgis::Symbol::Kind::fill), true}},
                        [&](OGRLayer& layer) {
                            name_field(layer);
                            for (const Region& r : scene.regions) {
                                OGRLinearRing ring;
                                for (const auto& v : r.polygon) ring.addPoint(v[0], v[1]);
                                ring.closeRings();
                                OGRPolygon polygon;
                                polygon.addRing(&ring);
                                add(layer, r.name, polygon);
                            }
                            return scene.regions.size();
                        }});
    if (defs.empty()) return 0;
    return write_vector_layers(out_path, "GPKG", scene.crs, scene_path, defs);
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
    style.scalar = qgis::ramp(depth_top, land_depth_colours, "m", 0.8);
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
