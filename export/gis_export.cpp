#include "export/gis_export.hpp"

#include <gdal_alg.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <optional>

#include "common/atomic_file.hpp"
#include "common/checks.hpp"
#include "common/error.hpp"
#include "data/gdal_support.hpp"
#include "export/vector_output.hpp"

namespace flotsam::gis {

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
    if (layer.CreateField(&d) != OGRERR_NONE) fail_writing(out_path, "field '" + name + "'", "create it");
}

void fail_writing(const std::string& path, const std::string& what, const std::string& doing) {
    fail(path, what, "GDAL could not " + doing + ": " + gdal::last_error() + disk_full_hint(path));
}

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
        (void)gdal::last_error();  // cleared: a failure while closing shows as pending
        gdal::Dataset ds(driver->Create(temp.c_str(), 0, 0, 0, GDT_Unknown, nullptr));
        if (!ds) fail_writing(out_path, "GDAL", "create it");
        std::optional<OGRSpatialReference> srs;
        if (!crs.empty()) srs = gdal::spatial_ref(crs, crs_file);
        for (const VectorLayerDef& def : defs) {
            OGRLayer* layer = ds->CreateLayer(def.name.c_str(), srs ? &*srs : nullptr, def.geometry, nullptr);
            if (!layer) fail_writing(out_path, "layer '" + def.name + "'", "create it");
            written += def.write(*layer);
            if (geopackage && !def.styles.empty()) qgis::store_styles(*ds, out_path, def.name, def.styles);
        }
        ds.reset();  // flush and close: a full disk may show only here
        if (gdal::error_pending()) fail_writing(out_path, "layers", "finish writing them");
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
    (void)gdal::last_error();  // cleared: a failure while closing shows as pending
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
    if (!written) fail_writing(path, layer.name, "write the Cloud-Optimised GeoTIFF");
    written.reset();  // flush and close before the rename
    if (gdal::error_pending()) fail_writing(path, layer.name, "finish the Cloud-Optimised GeoTIFF");
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

}  // namespace flotsam::gis
