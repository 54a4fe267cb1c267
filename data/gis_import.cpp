#include "data/gis_import.hpp"

#include <gdal_alg.h>
#include <gdal_utils.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>

#include "common/checks.hpp"
#include "common/error.hpp"
#include "data/dem_import.hpp"
#include "data/gdal_support.hpp"
#include "data/vector_layer.hpp"

namespace flotsam {

namespace {

std::string exact_text(double v) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return buf;
}

void flip_rows(std::vector<double>& z, int nx, int ny) {
    for (int j = 0; j < ny / 2; ++j)
        std::swap_ranges(z.begin() + std::ptrdiff_t(j) * nx, z.begin() + std::ptrdiff_t(j + 1) * nx,
                         z.begin() + std::ptrdiff_t(ny - 1 - j) * nx);
}

// gdalwarp through GDAL's library API, into memory.
gdal::Dataset warp(GDALDataset& src, const std::vector<std::string>& args, const std::string& path, const std::string& what) {
    CPLStringList argv;
    for (const auto& a : args) argv.AddString(a.c_str());
    GDALWarpAppOptions* options = GDALWarpAppOptionsNew(argv.List(), nullptr);
    if (!options) fail(path, what, "bad warp options: " + gdal::last_error());
    GDALDatasetH in = GDALDataset::ToHandle(&src);
    int usage_error = 0;
    GDALDatasetH out = GDALWarp("", nullptr, 1, &in, options, &usage_error);
    GDALWarpAppOptionsFree(options);
    if (!out) fail(path, what, "GDAL could not warp it: " + gdal::last_error());
    return gdal::Dataset(GDALDataset::FromHandle(out));
}

bool metres(const std::string& unit) {
    std::string u = unit;
    std::transform(u.begin(), u.end(), u.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return u.empty() || u == "m" || u == "metre" || u == "meter" || u == "metres" || u == "meters";
}

// Band 1 on a north-up grid as a DEM (rows south first); nodata and NaN become NaN.
Dem dem_from_dataset(GDALDataset& ds, const std::string& path) {
    if (ds.GetRasterCount() < 1) {
        char** sub = ds.GetMetadata("SUBDATASETS");
        std::string hint;
        if (sub && sub[0]) {
            const std::string first = sub[0];
            hint = ": it holds several variables; name one as GDAL does, e.g. " + first.substr(first.find('=') + 1);
        }
        fail(path, "", "no raster band" + hint);
    }
    double gt[6];
    if (ds.GetGeoTransform(gt) != CE_None)
        fail(path, "georeferencing",
             "no geotransform: the grid's coordinates are missing or not uniformly spaced (a regular north-up grid is needed)");
    if (gt[2] != 0.0 || gt[4] != 0.0)
        fail(path, "geotransform",
             "a rotated or sheared grid (row/column terms " + number_text(gt[2]) + ", " + number_text(gt[4]) +
                 "): warp it north-up first, e.g. gdalwarp -t_srs EPSG:n in.tif north_up.tif");
    if (!(gt[1] > 0.0) || gt[5] == 0.0) fail(path, "geotransform", "pixel size must be positive along x and non-zero along y");
    GDALRasterBand* band = ds.GetRasterBand(1);
    const std::string unit = band->GetUnitType() ? band->GetUnitType() : "";
    if (!metres(unit)) fail(path, "band 1 units", "'" + unit + "': elevations must be in metres");
    Dem d;
    d.path = path;
    d.grid.nx = ds.GetRasterXSize();
    d.grid.ny = ds.GetRasterYSize();
    d.grid.dx = gt[1];
    d.grid.dy = std::abs(gt[5]);
    d.grid.x0 = gt[0] + 0.5 * gt[1];
    d.grid.y0 = gt[5] < 0.0 ? gt[3] + d.grid.ny * gt[5] + 0.5 * d.grid.dy : gt[3] + 0.5 * d.grid.dy;
    d.z.resize(d.grid.size());
    if (band->RasterIO(GF_Read, 0, 0, d.grid.nx, d.grid.ny, d.z.data(), d.grid.nx, d.grid.ny, GDT_Float64, 0, 0, nullptr) !=
        CE_None)
        fail(path, "band 1", "cannot read: " + gdal::last_error());
    int has_nodata = 0, has_scale = 0, has_offset = 0;
    const double nodata = band->GetNoDataValue(&has_nodata);
    const double scale = band->GetScale(&has_scale), offset = band->GetOffset(&has_offset);
    for (double& v : d.z) {
        if ((has_nodata && v == nodata) || !std::isfinite(v))
            v = std::nan("");
        else if (has_scale || has_offset)
            v = v * (has_scale ? scale : 1.0) + (has_offset ? offset : 0.0);
    }
    if (gt[5] < 0.0) flip_rows(d.z, d.grid.nx, d.grid.ny);
    const char* title = ds.GetMetadataItem("NC_GLOBAL#title");
    d.title = title ? title : "";
    return d;
}

void check_projected_metres(const OGRSpatialReference& crs, const std::string& file, const std::string& what) {
    if (crs.IsGeographic())
        fail(file, what + " " + gdal::label(crs),
             "geographic coordinates (degrees): give --target-crs EPSG:n, a projected CRS in metres (e.g. the local UTM "
             "zone), to reproject to");
    if (!crs.IsProjected()) fail(file, what + " " + gdal::label(crs), "not a projected CRS (x and y must be map metres)");
    const char* unit = nullptr;
    const double to_metre = crs.GetLinearUnits(&unit);
    if (to_metre != 1.0)
        fail(file, what + " " + gdal::label(crs),
             std::string("linear unit is '") + (unit ? unit : "?") + "' (" + number_text(to_metre) +
                 " m), not metres: give --target-crs to reproject");
}

// An in-memory raster on the scene grid (north-up), one band of `type`, filled with `init`.
gdal::Dataset scene_raster(const Scene& s, GDALDataType type, double init) {
    GDALDriver* mem = GetGDALDriverManager()->GetDriverByName("MEM");
    GDALDataset* d = mem->Create("", s.grid.nx, s.grid.ny, 1, type, nullptr);
    if (!d) fail("scene", "raster", "GDAL could not create an in-memory raster: " + gdal::last_error());
    double gt[6];
    gdal::geotransform(s.grid, gt);
    d->SetGeoTransform(gt);
    if (auto crs = scene_spatial_ref(s)) d->SetSpatialRef(&*crs);
    d->GetRasterBand(1)->Fill(init);
    return gdal::Dataset(d);
}

std::vector<double> read_scene_raster(GDALDataset& d, const Scene& s) {
    std::vector<double> v(s.grid.size());
    if (d.GetRasterBand(1)->RasterIO(GF_Read, 0, 0, s.grid.nx, s.grid.ny, v.data(), s.grid.nx, s.grid.ny, GDT_Float64, 0, 0,
                                     nullptr) != CE_None)
        fail("scene", "raster", "cannot read back: " + gdal::last_error());
    flip_rows(v, s.grid.nx, s.grid.ny);
    return v;
}

// The polygons of a vector layer in the scene's CRS, with one number per polygon from
// `field` (NaN where the field is null; all NaN when `field` is empty).
struct Polygons {
    std::vector<std::unique_ptr<OGRGeometry>> geometry;
    std::vector<double> value;
    std::string note;  // reprojection, if any
};

Polygons read_polygons(const std::string& path, const std::string& layer_name, const std::string& field, const Scene& s,
                       const std::string& option) {
    const VectorLayer v = open_vector_layer(path, layer_name, s);
    int field_index = -1;
    if (!field.empty()) {
        field_index = v.field_index(field);
        if (field_index < 0) fail(v.where, "field '" + field + "'", "not in the layer (fields: " + v.field_names() + ")");
    }
    Polygons out;
    out.note = v.note;
    for (OGRFeature* raw; (raw = v.layer->GetNextFeature()) != nullptr;) {
        std::unique_ptr<OGRFeature, void (*)(OGRFeature*)> feature(raw, OGRFeature::DestroyFeature);
        const OGRGeometry* g = feature->GetGeometryRef();
        if (!g) continue;
        const auto type = wkbFlatten(g->getGeometryType());
        if (type != wkbPolygon && type != wkbMultiPolygon)
            fail(v.where, "feature " + std::to_string(feature->GetFID()),
                 std::string("is a ") + OGRGeometryTypeToName(g->getGeometryType()) + ", not a polygon (" + option +
                     " needs polygons)");
        double value = std::nan("");
        if (field_index >= 0 && feature->IsFieldSetAndNotNull(field_index)) value = feature->GetFieldAsDouble(field_index);
        out.geometry.push_back(v.geometry_in_scene(*feature));
        out.value.push_back(value);
    }
    if (out.geometry.empty()) fail(v.where, "features", "no polygons in the layer");
    return out;
}

// Burns polygon k (1-based) into an Int32 raster on the scene grid; 0 outside. A cell
// belongs to a polygon when its centre lies inside (GDAL's default rule).
std::vector<int> rasterise_ids(const Polygons& p, const Scene& s, const std::string& path) {
    gdal::Dataset r = scene_raster(s, GDT_Int32, 0.0);
    std::vector<OGRGeometryH> geoms;
    std::vector<double> burn;
    for (std::size_t k = 0; k < p.geometry.size(); ++k) {
        geoms.push_back(OGRGeometry::ToHandle(p.geometry[k].get()));
        burn.push_back(double(k + 1));
    }
    int band = 1;
    if (GDALRasterizeGeometries(GDALDataset::ToHandle(r.get()), 1, &band, int(geoms.size()), geoms.data(), nullptr, nullptr,
                                burn.data(), nullptr, nullptr, nullptr) != CE_None)
        fail(path, "polygons", "GDAL could not rasterise them: " + gdal::last_error());
    const auto v = read_scene_raster(*r, s);
    return std::vector<int>(v.begin(), v.end());
}

}  // namespace

cf::GridMapping sidecar_or_assigned_crs(const std::string& dem_path, const GisImportDef& gis) {
    if (gis.assign_crs == "local") return {};
    std::optional<OGRSpatialReference> crs;
    if (!gis.assign_crs.empty()) {
        crs = gdal::crs_from_text(gis.assign_crs, "--crs");
    } else {
        std::filesystem::path prj(dem_path);
        prj.replace_extension(".prj");
        if (std::filesystem::exists(prj)) crs = gdal::crs_from_text(prj.string(), prj.string());
    }
    if (!crs) return {};
    check_projected_metres(*crs, dem_path, "CRS");
    return gdal::grid_mapping(*crs);
}

Dem read_gis_dem(const std::string& path, const GisImportDef& gis, double resolution) {
    gdal::Dataset ds = gdal::open_raster(path);
    const OGRSpatialReference* in_file = ds->GetSpatialRef();
    std::optional<OGRSpatialReference> source;
    if (gis.assign_crs == "local") {
        // Local metres: no CRS.
    } else if (!gis.assign_crs.empty()) {
        source = gdal::crs_from_text(gis.assign_crs, "--crs");
        if (in_file && !in_file->IsSame(&*source))
            std::fprintf(stderr, "scene import: %s: its CRS %s is replaced by --crs %s\n", path.c_str(),
                         gdal::label(*in_file).c_str(), gdal::label(*source).c_str());
    } else if (in_file) {
        source = *in_file;
        source->SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    } else {
        fail(path, "coordinate reference system",
             "none in the file: give --crs EPSG:n (the CRS it is in), or --crs local for a grid in local metres");
    }
    std::optional<OGRSpatialReference> final_crs = source;
    gdal::Dataset warped;
    GDALDataset* use = ds.get();
    if (!gis.target_crs.empty()) {
        OGRSpatialReference target = gdal::crs_from_text(gis.target_crs, "--target-crs");
        check_projected_metres(target, "--target-crs", "CRS");
        if (!source) fail(path, "--target-crs", "the DEM has no CRS to reproject from (give its CRS with --crs)");
        if (!source->IsSame(&target)) {
            double gt[6];
            const bool coarser = ds->GetGeoTransform(gt) == CE_None && source->IsProjected() &&
                                 resolution > std::abs(gt[1]) * source->GetLinearUnits();
            char* wkt_in = nullptr;
            char* wkt_out = nullptr;
            source->exportToWkt(&wkt_in);
            target.exportToWkt(&wkt_out);
            const std::vector<std::string> args = {"-of",
                                                   "MEM",
                                                   "-s_srs",
                                                   wkt_in,
                                                   "-t_srs",
                                                   wkt_out,
                                                   "-tr",
                                                   exact_text(resolution),
                                                   exact_text(resolution),
                                                   "-tap",
                                                   "-r",
                                                   coarser ? "average" : "bilinear",
                                                   "-ot",
                                                   "Float64",
                                                   "-dstnodata",
                                                   "nan",
                                                   "-wo",
                                                   "SAMPLE_GRID=YES"};
            CPLFree(wkt_in);
            CPLFree(wkt_out);
            warped = warp(*ds, args, path, "reprojection to " + gdal::label(target));
            use = warped.get();
            std::fprintf(stderr, "scene import: %s reprojected from %s to %s at %s m\n", path.c_str(), gdal::label(*source).c_str(),
                         gdal::label(target).c_str(), number_text(resolution).c_str());
        }
        final_crs = target;
    } else if (source) {
        check_projected_metres(*source, path, "CRS");
    }
    Dem d = dem_from_dataset(*use, path);
    if (final_crs) d.crs = gdal::grid_mapping(*final_crs);
    apply_extent_and_datum(d, gis);
    // Nodata inside the domain.
    std::size_t missing = 0, first = 0;
    for (std::size_t k = 0; k < d.z.size(); ++k)
        if (std::isnan(d.z[k])) {
            if (missing++ == 0) first = k;
            if (gis.nodata_fill) d.z[k] = *gis.nodata_fill;
        }
    if (missing > 0 && !gis.nodata_fill) {
        const int i = int(first % std::size_t(d.grid.nx)), j = int(first / std::size_t(d.grid.nx));
        fail(path, "band 1",
             std::to_string(missing) + " nodata cells inside the domain (the first at x = " + coordinate_text(d.grid.x(i)) +
                 ", y = " + coordinate_text(d.grid.y(j)) +
                 "): crop them away with --extent x_min,x_max,y_min,y_max or fill them with --nodata-fill ELEVATION");
    }
    return d;
}

void apply_extent_and_datum(Dem& d, const GisImportDef& gis) {
    if (gis.extent) {
        const auto& e = *gis.extent;
        if (!(e[1] > e[0] && e[3] > e[2])) fail("--extent", "", "needs x_min < x_max and y_min < y_max");
        int i0 = d.grid.nx, i1 = -1, j0 = d.grid.ny, j1 = -1;
        for (int i = 0; i < d.grid.nx; ++i)
            if (d.grid.x(i) >= e[0] && d.grid.x(i) <= e[1]) i0 = std::min(i0, i), i1 = std::max(i1, i);
        for (int j = 0; j < d.grid.ny; ++j)
            if (d.grid.y(j) >= e[2] && d.grid.y(j) <= e[3]) j0 = std::min(j0, j), j1 = std::max(j1, j);
        if (i1 < i0 || j1 < j0)
            fail("--extent", "",
                 "holds no cell centre of " + d.path + " (its cells span x " + coordinate_text(d.grid.x_min_edge()) + " .. " +
                     coordinate_text(d.grid.x_max_edge()) + ", y " + coordinate_text(d.grid.y_min_edge()) + " .. " +
                     coordinate_text(d.grid.y_max_edge()) + ")");
        d.source_grid = d.grid;
        Grid g = d.grid;
        g.nx = i1 - i0 + 1;
        g.ny = j1 - j0 + 1;
        g.x0 = d.grid.x(i0);
        g.y0 = d.grid.y(j0);
        std::vector<double> z(g.size());
        for (int j = 0; j < g.ny; ++j)
            for (int i = 0; i < g.nx; ++i) z[g.index(i, j)] = d.z[d.grid.index(i + i0, j + j0)];
        d.grid = g;
        d.z = std::move(z);
    }
    if (gis.still_water_level != 0.0)
        for (double& v : d.z) v -= gis.still_water_level;
}

std::string burn_building_footprints(Scene& s, const GisImportDef& gis) {
    if (gis.buildings.empty()) return "";
    if (gis.building_height && !(*gis.building_height >= 0.0)) fail("--building-height", "", "must be >= 0 m");
    const Polygons p = read_polygons(gis.buildings, gis.buildings_layer, gis.building_height_field, s, "--buildings");
    const std::vector<int> id = rasterise_ids(p, s, gis.buildings);
    // Heights: per footprint, the lowest z among its cells is its ground.
    std::vector<double> ground(p.geometry.size(), std::numeric_limits<double>::infinity());
    std::vector<std::size_t> cells(p.geometry.size(), 0);
    for (std::size_t k = 0; k < id.size(); ++k)
        if (id[k] > 0) {
            ground[std::size_t(id[k] - 1)] = std::min(ground[std::size_t(id[k] - 1)], s.z[k]);
            ++cells[std::size_t(id[k] - 1)];
        }
    std::size_t raised = 0, empty = 0;
    for (std::size_t f = 0; f < p.geometry.size(); ++f) {
        empty += cells[f] == 0;
        const double h = std::isnan(p.value[f]) ? gis.building_height.value_or(std::nan("")) : p.value[f];
        if (!std::isnan(h) && !(h >= 0.0))
            fail(gis.buildings, "field '" + gis.building_height_field + "'",
                 "footprint " + std::to_string(f) + " has a negative height");
    }
    s.building.assign(s.grid.size(), 0);
    s.building_id.assign(s.grid.size(), 0);  // each cell's footprint: its place in the layer, from 1
    std::size_t burnt = 0;
    for (std::size_t k = 0; k < id.size(); ++k) {
        if (id[k] <= 0) continue;
        const std::size_t f = std::size_t(id[k] - 1);
        s.building[k] = 1;
        s.building_id[k] = id[k];
        ++burnt;
        const double h = std::isnan(p.value[f]) ? gis.building_height.value_or(std::nan("")) : p.value[f];
        if (!std::isnan(h) && ground[f] + h > s.z[k]) {
            s.z[k] = ground[f] + h;
            ++raised;
        }
    }
    std::string note = "buildings: " + std::to_string(p.geometry.size()) + " footprints from " + gis.buildings + " -> " +
                       std::to_string(burnt) + " building cells (" + std::to_string(raised) + " raised to ground + height)";
    if (empty > 0) note += "; " + std::to_string(empty) + " footprints cover no cell centre (smaller than the grid)";
    if (!p.note.empty()) note += "; " + p.note;
    return note;
}

namespace {

std::map<long, double> read_class_table(const std::string& path) {
    std::ifstream in(path);
    if (!in) fail(path, "", "cannot open");
    std::map<long, double> table;
    std::string line;
    for (int lineno = 1; std::getline(in, line); ++lineno) {
        if (const auto hash = line.find('#'); hash != std::string::npos) line.resize(hash);
        if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
        std::replace(line.begin(), line.end(), ',', ' ');
        std::istringstream ss(line);
        double code = 0, n = 0;
        std::string rest;
        if (!(ss >> code >> n) || (ss >> rest)) {
            if (table.empty() && lineno == 1) continue;  // a header line
            fail(path, "line " + std::to_string(lineno), "expected: class,n (a land-use code and its Manning n)");
        }
        if (code != std::floor(code)) fail(path, "line " + std::to_string(lineno), "the class must be a whole number");
        if (!(n >= 0.0 && n < 1.0)) fail(path, "line " + std::to_string(lineno), "Manning n must be in [0, 1) s m^-1/3");
        table[long(code)] = n;
    }
    if (table.empty()) fail(path, "", "no class,n rows");
    return table;
}

}  // namespace

std::vector<double> manning_from_gis(const Scene& s, const GisImportDef& gis, std::vector<double> n, std::string& note) {
    if (gis.manning_raster.empty() && gis.manning_polygons.empty()) return n;
    if (!gis.manning_classes.empty() && gis.manning_raster.empty())
        fail("--manning-classes", gis.manning_classes, "needs --manning-raster (the land-use codes it maps)");
    if (n.empty()) n.assign(s.grid.size(), std::nan(""));
    if (!gis.manning_raster.empty()) {
        gdal::Dataset src = gdal::open_raster(gis.manning_raster);
        const OGRSpatialReference* rcrs = src->GetSpatialRef();
        const auto scrs = scene_spatial_ref(s);
        if (scrs && !rcrs)
            fail(gis.manning_raster, "coordinate reference system", "none, while the scene is in " + gdal::label(*scrs));
        if (!scrs && rcrs)
            fail(gis.manning_raster, "coordinate reference system " + gdal::label(*rcrs), "the scene is in local metres (no CRS)");
        const bool classes = !gis.manning_classes.empty();
        std::vector<std::string> args = {"-of",
                                         "MEM",
                                         "-ot",
                                         "Float64",
                                         "-r",
                                         classes ? "mode" : "average",
                                         "-te",
                                         exact_text(s.grid.x_min_edge()),
                                         exact_text(s.grid.y_min_edge()),
                                         exact_text(s.grid.x_max_edge()),
                                         exact_text(s.grid.y_max_edge()),
                                         "-ts",
                                         std::to_string(s.grid.nx),
                                         std::to_string(s.grid.ny),
                                         "-dstnodata",
                                         "nan"};
        if (!scrs) {  // both local: same frame, no transformation
            args.insert(args.end(), {"-to", "SRC_METHOD=GEOTRANSFORM", "-to", "DST_METHOD=GEOTRANSFORM"});
        }
        gdal::Dataset on_grid = warp(*src, args, gis.manning_raster, "resampling onto the scene grid");
        const std::vector<double> v = read_scene_raster(*on_grid, s);
        std::map<long, double> table;
        if (classes) table = read_class_table(gis.manning_classes);
        std::size_t used = 0;
        for (std::size_t k = 0; k < v.size(); ++k) {
            if (std::isnan(v[k])) continue;
            double value = v[k];
            if (classes) {
                const auto it = table.find(std::lround(v[k]));
                if (it == table.end())
                    fail(gis.manning_classes, "class " + std::to_string(std::lround(v[k])),
                         "found in " + gis.manning_raster + " but not in the table");
                value = it->second;
            } else if (!(value >= 0.0 && value < 1.0)) {
                fail(gis.manning_raster, "band 1",
                     "value " + number_text(value) +
                         " is not a Manning n in [0, 1) s m^-1/3 (give "
                         "--manning-classes if these are land-use codes)");
            }
            n[k] = value;
            ++used;
        }
        note += "Manning n: " + std::to_string(used) + " cells from " + gis.manning_raster +
                (classes ? " (classes mapped by " + gis.manning_classes + ")" : std::string());
    }
    if (!gis.manning_polygons.empty()) {
        const Polygons p = read_polygons(gis.manning_polygons, "", gis.manning_field, s, "--manning-polygons");
        for (std::size_t f = 0; f < p.value.size(); ++f)
            if (!(p.value[f] >= 0.0 && p.value[f] < 1.0))
                fail(gis.manning_polygons, "field '" + gis.manning_field + "'",
                     "polygon " + std::to_string(f) + ": n = " + number_text(p.value[f]) + " is not in [0, 1) s m^-1/3");
        const std::vector<int> id = rasterise_ids(p, s, gis.manning_polygons);
        std::size_t used = 0;
        for (std::size_t k = 0; k < id.size(); ++k)
            if (id[k] > 0) {
                n[k] = p.value[std::size_t(id[k] - 1)];
                ++used;
            }
        note += std::string(note.empty() ? "" : "; ") + "Manning n: " + std::to_string(used) + " cells from the polygons of " +
                gis.manning_polygons + (p.note.empty() ? "" : " (" + p.note + ")");
    }
    std::size_t missing = 0;
    for (double v : n) missing += std::isnan(v);
    if (missing > 0)
        fail(gis.manning_raster.empty() ? gis.manning_polygons : gis.manning_raster, "Manning n",
             std::to_string(missing) + " scene cells get no n from it: add a [[manning]] rule in --features for the rest");
    return n;
}

}  // namespace flotsam
