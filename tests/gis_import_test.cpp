// GIS in: a GeoTIFF DEM with its CRS, datum and nodata; footprints burnt into
// the building mask and z; Manning n from a land-use raster and polygons; the CRS
// carried into the scene as a CF grid mapping that GDAL reads back; and the errors a user
// meets, each naming the file and what is wrong.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "common/error.hpp"
#include "common/netcdf.hpp"
#include "data/dem_import.hpp"
#include "data/gdal_support.hpp"
#include "tests/test_support.hpp"

using namespace flotsam;
using test::error_of;
using test::write_file;

namespace {

// UTM zone 53N, near Kainan: the upper-left corner of the test rasters.
constexpr double east0 = 518000.0, north0 = 3780000.0;

// A north-up GeoTIFF of nx x ny cells of `cell` metres whose row 0 is the north row;
// z(i, j_from_north) from `f`; EPSG code 0: no CRS.
std::string write_geotiff(const std::string& path, int nx, int ny, double cell, int epsg, const std::function<double(int, int)>& f,
                          std::optional<double> nodata = std::nullopt, double rotation = 0.0) {
    gdal::init();
    GDALDriver* drv = GetGDALDriverManager()->GetDriverByName("GTiff");
    gdal::Dataset d(drv->Create(path.c_str(), nx, ny, 1, GDT_Float32, nullptr));
    double gt[6] = {east0, cell, rotation, north0, 0.0, -cell};
    d->SetGeoTransform(gt);
    if (epsg) {
        OGRSpatialReference s;
        s.importFromEPSG(epsg);
        d->SetSpatialRef(&s);
    }
    std::vector<float> v(std::size_t(nx) * std::size_t(ny));
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) v[std::size_t(j) * nx + i] = float(f(i, j));
    if (nodata) d->GetRasterBand(1)->SetNoDataValue(*nodata);
    EXPECT_EQ(d->GetRasterBand(1)->RasterIO(GF_Write, 0, 0, nx, ny, v.data(), nx, ny, GDT_Float32, 0, 0, nullptr), CE_None);
    return path;
}

// A beach: 40 x 20 cells of 5 m, sea bed -4 m in the west rising 0.25 m per cell east.
double beach(int i, int) { return -4.0 + 0.25 * i; }

std::string square_feature(double x0, double y0, double side, const std::string& props) {
    char buf[512];
    std::snprintf(
        buf, sizeof buf,
        R"({"type":"Feature","properties":{%s},"geometry":{"type":"Polygon","coordinates":[[[%.3f,%.3f],[%.3f,%.3f],[%.3f,%.3f],[%.3f,%.3f],[%.3f,%.3f]]]}})",
        props.c_str(), x0, y0, x0 + side, y0, x0 + side, y0 + side, x0, y0 + side, x0, y0);
    return buf;
}

std::string geojson(const std::string& crs_urn, const std::vector<std::string>& features) {
    std::string s = R"({"type":"FeatureCollection",)";
    if (!crs_urn.empty()) s += R"("crs":{"type":"name","properties":{"name":")" + crs_urn + R"("}},)";
    s += R"("features":[)";
    for (std::size_t k = 0; k < features.size(); ++k) s += (k ? "," : "") + features[k];
    return s + "]}";
}

ImportDef import_def(const std::string& dem, double res = 5.0) {
    ImportDef d;
    d.dem_path = dem;
    d.resolution = res;
    return d;
}

double z_at(const Scene& s, double x, double y) { return s.z[s.grid.index(s.grid.cell_i(x), s.grid.cell_j(y))]; }

}  // namespace

TEST(GisImport, GeoTiffWithEpsgKeepsGridValuesAndCrs) {
    const std::string dir = test::scratch_dir("gis_geotiff");
    const std::string tif = write_geotiff(dir + "/dem.tif", 40, 20, 5.0, 32653, beach);
    ImportDef def = import_def(tif);
    def.gis.still_water_level = 0.5;  // the DEM's datum lies 0.5 m below still water
    const Scene s = import_scene(def);
    EXPECT_EQ(s.grid.nx, 40);
    EXPECT_EQ(s.grid.ny, 20);
    EXPECT_DOUBLE_EQ(s.grid.x_min_edge(), east0);
    EXPECT_DOUBLE_EQ(s.grid.y_max_edge(), north0);
    EXPECT_DOUBLE_EQ(s.grid.y_min_edge(), north0 - 100.0);
    // Cell (i = 10, any row): DEM -4 + 2.5 = -1.5, minus the 0.5 m datum offset.
    EXPECT_NEAR(z_at(s, east0 + 52.5, north0 - 50.0), -2.0, 1e-6);
    EXPECT_EQ(s.crs.name(), "EPSG:32653");
    ASSERT_NE(s.crs.find("grid_mapping_name"), nullptr);
    EXPECT_EQ(s.crs.find("grid_mapping_name")->text, "transverse_mercator");
    EXPECT_DOUBLE_EQ(s.crs.find("longitude_of_central_meridian")->numbers.at(0), 135.0);
    EXPECT_DOUBLE_EQ(s.crs.find("false_easting")->numbers.at(0), 500000.0);
    EXPECT_DOUBLE_EQ(s.crs.find("scale_factor_at_central_meridian")->numbers.at(0), 0.9996);

    // Written and read back: the grid mapping survives, and GDAL places the scene's z
    // exactly where the GeoTIFF was, in EPSG:32653.
    write_scene(dir + "/scene.nc", s, "test");
    const Scene back = read_scene(dir + "/scene.nc");
    EXPECT_EQ(back.crs.name(), "EPSG:32653");
    EXPECT_EQ(back.crs.wkt(), s.crs.wkt());
    {
        const nc::File f = nc::File::open_read(dir + "/scene.nc");
        EXPECT_EQ(f.att_text(f.var("z"), "grid_mapping").value_or(""), "crs");
    }
    gdal::Dataset g = gdal::open_raster("NETCDF:\"" + dir + "/scene.nc\":z");
    double gt[6];
    ASSERT_EQ(g->GetGeoTransform(gt), CE_None);
    EXPECT_NEAR(gt[0], east0, 1e-6);
    EXPECT_NEAR(gt[3], north0, 1e-6);
    EXPECT_NEAR(gt[1], 5.0, 1e-9);
    EXPECT_NEAR(gt[5], -5.0, 1e-9);
    ASSERT_NE(g->GetSpatialRef(), nullptr);
    OGRSpatialReference utm;
    utm.importFromEPSG(32653);
    EXPECT_TRUE(g->GetSpatialRef()->IsSame(&utm));
}

TEST(GisImport, GeographicDemNeedsTargetCrsAndIsReprojected) {
    const std::string dir = test::scratch_dir("gis_geographic");
    // 0.0005 degree cells (about 46 m east-west, 55 m north-south) around 34.15 N 135.2 E.
    gdal::init();
    GDALDriver* drv = GetGDALDriverManager()->GetDriverByName("GTiff");
    const std::string tif = dir + "/dem_wgs84.tif";
    {
        gdal::Dataset d(drv->Create(tif.c_str(), 30, 20, 1, GDT_Float32, nullptr));
        double gt[6] = {135.19, 0.0005, 0.0, 34.16, 0.0, -0.0005};
        d->SetGeoTransform(gt);
        OGRSpatialReference s;
        s.importFromEPSG(4326);
        d->SetSpatialRef(&s);
        std::vector<float> v(600, 3.0f);
        EXPECT_EQ(d->GetRasterBand(1)->RasterIO(GF_Write, 0, 0, 30, 20, v.data(), 30, 20, GDT_Float32, 0, 0, nullptr), CE_None);
    }
    const std::string e = error_of([&] { import_scene(import_def(tif, 20.0)); });
    EXPECT_NE(e.find(tif), std::string::npos) << e;
    EXPECT_NE(e.find("geographic coordinates"), std::string::npos) << e;
    EXPECT_NE(e.find("--target-crs"), std::string::npos) << e;

    ImportDef def = import_def(tif, 20.0);
    def.gis.target_crs = "EPSG:32653";
    // The corners of the warped grid lie outside the rotated source: crop to its inside.
    def.gis.extent = std::array<double, 4>{517600.0, 518800.0, 3778900.0, 3779800.0};
    const Scene s = import_scene(def);
    EXPECT_EQ(s.crs.name(), "EPSG:32653");
    EXPECT_DOUBLE_EQ(s.grid.dx, 20.0);
    EXPECT_NEAR(z_at(s, 518000.0, 3779300.0), 3.0, 1e-6);
    // -tap: cell edges on multiples of the resolution.
    EXPECT_NEAR(std::fmod(s.grid.x_min_edge(), 20.0), 0.0, 1e-6);
}

TEST(GisImport, BadRastersAreNamed) {
    const std::string dir = test::scratch_dir("gis_bad");
    const std::string no_crs = write_geotiff(dir + "/no_crs.tif", 10, 10, 5.0, 0, beach);
    std::string e = error_of([&] { import_scene(import_def(no_crs)); });
    EXPECT_NE(e.find(no_crs), std::string::npos) << e;
    EXPECT_NE(e.find("coordinate reference system"), std::string::npos) << e;
    EXPECT_NE(e.find("--crs"), std::string::npos) << e;
    // --crs assigns one; --crs local takes it as local metres.
    ImportDef assigned = import_def(no_crs);
    assigned.gis.assign_crs = "EPSG:32653";
    EXPECT_EQ(import_scene(assigned).crs.name(), "EPSG:32653");
    assigned.gis.assign_crs = "local";
    EXPECT_TRUE(import_scene(assigned).crs.empty());

    const std::string rotated = write_geotiff(dir + "/rotated.tif", 10, 10, 5.0, 32653, beach, std::nullopt, 0.5);
    e = error_of([&] { import_scene(import_def(rotated)); });
    EXPECT_NE(e.find(rotated), std::string::npos) << e;
    EXPECT_NE(e.find("rotated"), std::string::npos) << e;

    // Nodata in the two westernmost columns.
    const std::string holes = write_geotiff(
        dir + "/holes.tif", 10, 10, 5.0, 32653, [](int i, int j) { return i < 2 ? -9999.0 : beach(i, j); }, -9999.0);
    e = error_of([&] { import_scene(import_def(holes)); });
    EXPECT_NE(e.find(holes), std::string::npos) << e;
    EXPECT_NE(e.find("20 nodata cells inside the domain"), std::string::npos) << e;
    EXPECT_NE(e.find("x = 518002.5"), std::string::npos) << e;  // the first one's centre
    ImportDef cropped = import_def(holes);
    cropped.gis.extent = std::array<double, 4>{east0 + 10.0, east0 + 50.0, north0 - 50.0, north0};
    const Scene c = import_scene(cropped);
    EXPECT_EQ(c.grid.nx, 8);
    EXPECT_NEAR(c.grid.x_min_edge(), east0 + 10.0, 1e-9);
    ImportDef filled = import_def(holes);
    filled.gis.nodata_fill = -4.0;
    EXPECT_NEAR(z_at(import_scene(filled), east0 + 2.5, north0 - 2.5), -4.0, 1e-12);

    // Feet are not metres.
    const std::string feet = write_geotiff(dir + "/feet.tif", 10, 10, 5.0, 2230, beach);  // NAD83 / California zone 6 (ftUS)
    e = error_of([&] { import_scene(import_def(feet)); });
    EXPECT_NE(e.find("not metres"), std::string::npos) << e;

    // An irregular NetCDF grid: GDAL finds no geotransform.
    {
        nc::File f = nc::File::create(dir + "/irregular.nc");
        const int dx = f.def_dim("east", 4), dy = f.def_dim("north", 3);
        const int vx = f.def_var("east", NC_DOUBLE, {dx}), vy = f.def_var("north", NC_DOUBLE, {dy});
        const int vz = f.def_var("elevation", NC_FLOAT, {dy, dx});
        f.enddef();
        f.put(vx, std::vector<double>{0, 1, 2, 3.5});
        f.put(vy, std::vector<double>{0, 1, 2});
        f.put(vz, std::vector<float>(12, 1.0f));
    }
    ImportDef irregular = import_def(dir + "/irregular.nc");
    irregular.gis.assign_crs = "EPSG:32653";
    e = error_of([&] { import_scene(irregular); });
    EXPECT_NE(e.find("irregular.nc"), std::string::npos) << e;
    EXPECT_NE(e.find("not uniformly spaced"), std::string::npos) << e;
}

TEST(GisImport, FootprintsBurnBuildingsAndHeightsReprojectingOtherCrs) {
    const std::string dir = test::scratch_dir("gis_footprints");
    const std::string tif = write_geotiff(dir + "/flat.tif", 20, 20, 5.0, 32653, [](int, int) { return 2.0; });
    // Two squares in UTM: a 20 m one with height 12, a 10 m one without a height.
    const std::string utm =
        write_file(dir, "buildings.geojson",
                   geojson("urn:ogc:def:crs:EPSG::32653", {square_feature(east0 + 10, north0 - 40, 20, R"("height": 12.0)"),
                                                           square_feature(east0 + 60, north0 - 40, 10, R"("height": null)")}));
    ImportDef def = import_def(tif);
    def.gis.buildings = utm;
    def.gis.building_height_field = "height";
    def.gis.building_height = 6.0;
    const Scene s = import_scene(def);
    std::size_t cells = 0;
    for (auto b : s.building) cells += std::size_t(b);
    EXPECT_EQ(cells, 16u + 4u);                                // 4 x 4 and 2 x 2 cells of 5 m
    EXPECT_DOUBLE_EQ(z_at(s, east0 + 20, north0 - 30), 14.0);  // ground 2 + 12
    EXPECT_DOUBLE_EQ(z_at(s, east0 + 65, north0 - 35), 8.0);   // ground 2 + the default 6
    EXPECT_DOUBLE_EQ(z_at(s, east0 + 50, north0 - 30), 2.0);   // open ground
    EXPECT_EQ(s.building[s.grid.index(s.grid.cell_i(east0 + 50), s.grid.cell_j(north0 - 30))], 0);

    // The same first square in WGS84 (lon/lat): reprojected, and said so.
    OGRSpatialReference from, to;
    from.importFromEPSG(32653);
    to.importFromEPSG(4326);
    from.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    to.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    std::unique_ptr<OGRCoordinateTransformation> t(OGRCreateCoordinateTransformation(&from, &to));
    std::string ring;
    for (auto [x, y] : std::vector<std::pair<double, double>>{{10, -40}, {30, -40}, {30, -20}, {10, -20}, {10, -40}}) {
        double e = east0 + x, n = north0 + y;
        ASSERT_TRUE(t->Transform(1, &e, &n));
        char buf[64];
        std::snprintf(buf, sizeof buf, "%s[%.10f,%.10f]", ring.empty() ? "" : ",", e, n);
        ring += buf;
    }
    const std::string wgs = write_file(
        dir, "buildings_wgs84.geojson",
        geojson("", {R"({"type":"Feature","properties":{},"geometry":{"type":"Polygon","coordinates":[[)" + ring + "]]}}"}));
    ImportDef re = import_def(tif);
    re.gis.buildings = wgs;
    const Scene r = import_scene(re);
    cells = 0;
    for (auto b : r.building) cells += std::size_t(b);
    EXPECT_EQ(cells, 16u);
    EXPECT_NE(r.comment.find("reprojected from EPSG:4326 to the scene's EPSG:32653"), std::string::npos) << r.comment;
    EXPECT_DOUBLE_EQ(z_at(r, east0 + 20, north0 - 30), 2.0);  // no height given: z as the DEM

    // Footprints with no CRS (a shapefile without .prj) for a scene that has one: refused.
    const std::string bare = dir + "/bare.shp";
    {
        gdal::Dataset v(
            GetGDALDriverManager()->GetDriverByName("ESRI Shapefile")->Create(bare.c_str(), 0, 0, 0, GDT_Unknown, nullptr));
        OGRLayer* layer = v->CreateLayer("bare", nullptr, wkbPolygon, nullptr);
        OGRFeature f(layer->GetLayerDefn());
        OGRPolygon poly;
        OGRLinearRing ringg;
        for (auto [x, y] : std::vector<std::pair<double, double>>{{0, -20}, {10, -20}, {10, -10}, {0, -10}, {0, -20}})
            ringg.addPoint(east0 + x, north0 + y);
        poly.addRing(&ringg);
        f.SetGeometry(&poly);
        ASSERT_EQ(layer->CreateFeature(&f), OGRERR_NONE);
    }
    ImportDef nocrs = import_def(tif);
    nocrs.gis.buildings = bare;
    std::string e = error_of([&] { import_scene(nocrs); });
    EXPECT_NE(e.find("bare.shp"), std::string::npos) << e;
    EXPECT_NE(e.find("coordinate reference system"), std::string::npos) << e;
    EXPECT_NE(e.find("EPSG:32653"), std::string::npos) << e;
    // A missing height field is named with the fields there are.
    ImportDef badfield = import_def(tif);
    badfield.gis.buildings = utm;
    badfield.gis.building_height_field = "levels";
    e = error_of([&] { import_scene(badfield); });
    EXPECT_NE(e.find("field 'levels'"), std::string::npos) << e;
    EXPECT_NE(e.find("height"), std::string::npos) << e;
}

TEST(GisImport, ManningFromLandUseClassesAndPolygons) {
    const std::string dir = test::scratch_dir("gis_manning");
    const std::string tif = write_geotiff(dir + "/flat.tif", 20, 20, 5.0, 32653, [](int, int) { return 1.0; });
    // Land use at 10 m: class 1 (water) in the west half, 2 (urban) in the east.
    const std::string lu = write_geotiff(dir + "/landuse.tif", 10, 10, 10.0, 32653, [](int i, int) { return i < 5 ? 1.0 : 2.0; });
    const std::string table = write_file(dir, "classes.csv", "class,n\n1,0.025\n2,0.08  # dense buildings\n");
    ImportDef def = import_def(tif);
    def.gis.manning_raster = lu;
    def.gis.manning_classes = table;
    Scene s = import_scene(def);
    ASSERT_EQ(s.manning_n.size(), s.grid.size());
    EXPECT_DOUBLE_EQ(s.manning_n[s.grid.index(2, 10)], 0.025);
    EXPECT_DOUBLE_EQ(s.manning_n[s.grid.index(15, 10)], 0.08);
    // A polygon of n = 0.035 over the north-west 20 m wins over the raster.
    def.gis.manning_polygons = write_file(
        dir, "park.geojson", geojson("urn:ogc:def:crs:EPSG::32653", {square_feature(east0, north0 - 20, 20, R"("n": 0.035)")}));
    s = import_scene(def);
    EXPECT_DOUBLE_EQ(s.manning_n[s.grid.index(1, 18)], 0.035);
    EXPECT_DOUBLE_EQ(s.manning_n[s.grid.index(1, 2)], 0.025);
    // A class the table lacks is named.
    def.gis.manning_polygons.clear();
    def.gis.manning_classes = write_file(dir, "short.csv", "1,0.025\n");
    const std::string e = error_of([&] { import_scene(def); });
    EXPECT_NE(e.find("short.csv"), std::string::npos) << e;
    EXPECT_NE(e.find("class 2"), std::string::npos) << e;
}

TEST(GisImport, FeaturesHydroTableBecomesSceneRecommendations) {
    const std::string dir = test::scratch_dir("gis_hydro_defaults");
    const std::string tif = write_geotiff(dir + "/dem.tif", 10, 10, 5.0, 32653, beach);
    ImportDef def = import_def(tif);
    def.features_path = write_file(dir, "f.toml", "[hydro]\nmax-dt = 0.79\narrival-depth = 6.25\nnest-x = -300\n");
    const Scene s = import_scene(def);
    EXPECT_EQ(s.hydro_defaults, "max-dt = 0.79\narrival-depth = 6.25\nnest-x = -300\n");
    def.features_path = write_file(dir, "bad.toml", "[hydro]\ncfl = 0.3\n");
    const std::string e = error_of([&] { import_scene(def); });
    EXPECT_NE(e.find("bad.toml"), std::string::npos) << e;
    EXPECT_NE(e.find("cfl"), std::string::npos) << e;
}
