// GIS out: the Cloud-Optimised GeoTIFFs read back through GDAL with the right
// origin, pixel size, north-up orientation, CRS and values, and gdalinfo reports a COG;
// and the whole chain from a GeoTIFF through hydro, debris (a catalogue body) and export
// carries the CRS into every file, the maps and the track lines.
#include "export/gis_export.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>

#include "common/netcdf.hpp"
#include "data/gdal_support.hpp"
#include "tests/test_support.hpp"

using namespace flotsam;

namespace {

constexpr double east0 = 518000.0, north0 = 3780000.0;

std::string shell(const std::string& cmd) {
    std::string out;
    FILE* p = ::popen((cmd + " 2>&1").c_str(), "r");
    if (!p) return out;
    char buf[4096];
    std::size_t n;
    while ((n = std::fread(buf, 1, sizeof buf, p)) > 0) out.append(buf, n);
    ::pclose(p);
    return out;
}

cf::GridMapping utm53() {
    gdal::init();
    OGRSpatialReference s;
    s.importFromEPSG(32653);
    return gdal::grid_mapping(s);
}

}  // namespace

TEST(GisExport, CogReadsBackWithGeoreferencingAndValues) {
    const std::string dir = test::scratch_dir("gis_cog");
    // 6 x 4 cells of 2.5 m, lower-left edge at (east0, north0 - 10); value = 10 j + i with
    // j = 0 the southern row, and one cell without a value.
    Grid g{.nx = 6, .ny = 4, .x0 = east0 + 1.25, .y0 = north0 - 10.0 + 1.25, .dx = 2.5, .dy = 2.5};
    gis::MapLayer m{"pass_probability_test", "test map", "1", std::vector<float>(g.size())};
    for (int j = 0; j < g.ny; ++j)
        for (int i = 0; i < g.nx; ++i) m.values[g.index(i, j)] = float(10 * j + i);
    m.values[g.index(5, 0)] = std::nanf("");
    m.style = gis::qgis::probability_classes({"#ffffb2", "#fed976", "#feb24c", "#fd8d3c", "#f03b20", "#bd0026"});
    const std::string path = dir + "/map.tif";
    gis::write_cog(path, g, utm53(), m, "test");

    gdal::Dataset d = gdal::open_raster(path);
    EXPECT_STREQ(d->GetDriver()->GetDescription(), "GTiff");
    ASSERT_NE(d->GetMetadataItem("LAYOUT", "IMAGE_STRUCTURE"), nullptr);
    EXPECT_STREQ(d->GetMetadataItem("LAYOUT", "IMAGE_STRUCTURE"), "COG");
    double gt[6];
    ASSERT_EQ(d->GetGeoTransform(gt), CE_None);
    EXPECT_DOUBLE_EQ(gt[0], east0);   // west edge
    EXPECT_DOUBLE_EQ(gt[3], north0);  // north edge: north-up
    EXPECT_DOUBLE_EQ(gt[1], 2.5);     // pixel width
    EXPECT_DOUBLE_EQ(gt[5], -2.5);    // rows go south
    EXPECT_EQ(gt[2], 0.0);
    EXPECT_EQ(gt[4], 0.0);
    OGRSpatialReference utm;
    utm.importFromEPSG(32653);
    ASSERT_NE(d->GetSpatialRef(), nullptr);
    EXPECT_TRUE(d->GetSpatialRef()->IsSame(&utm));
    EXPECT_STREQ(d->GetSpatialRef()->GetAuthorityCode(nullptr), "32653");
    std::vector<float> v(g.size());
    ASSERT_EQ(d->GetRasterBand(1)->RasterIO(GF_Read, 0, 0, 6, 4, v.data(), 6, 4, GDT_Float32, 0, 0, nullptr), CE_None);
    EXPECT_EQ(v[0], 30.0f);         // row 0 = the northern row (j = 3), west column
    EXPECT_EQ(v[3 * 6 + 2], 2.0f);  // last row = the southern row (j = 0)
    EXPECT_TRUE(std::isnan(v[3 * 6 + 5]));
    int has = 0;
    EXPECT_TRUE(std::isnan(d->GetRasterBand(1)->GetNoDataValue(&has)));
    EXPECT_TRUE(has);
    EXPECT_STREQ(d->GetRasterBand(1)->GetDescription(), "pass_probability_test");
    // The point at the centre of cell (i = 2, j = 1) maps to pixel (2, 2).
    const double px = (east0 + 2.5 * 2 + 1.25 - gt[0]) / gt[1], py = (north0 - 10.0 + 2.5 + 1.25 - gt[3]) / gt[5];
    EXPECT_EQ(int(px), 2);
    EXPECT_EQ(int(py), 2);
    EXPECT_EQ(v[2 * 6 + 2], 12.0f);

    // gdalinfo, as a user would check it.
    const std::string info = shell("gdalinfo " + path);
    EXPECT_NE(info.find("LAYOUT=COG"), std::string::npos) << info;
    EXPECT_NE(info.find("Origin = (518000.000000000000000,3780000.000000000000000)"), std::string::npos) << info;
    EXPECT_NE(info.find("Pixel Size = (2.500000000000000,-2.500000000000000)"), std::string::npos) << info;
    EXPECT_NE(info.find("WGS 84 / UTM zone 53N"), std::string::npos) << info;
    EXPECT_NE(info.find("ID[\"EPSG\",32653]"), std::string::npos) << info;
    EXPECT_NE(info.find("COMPRESSION=DEFLATE"), std::string::npos) << info;
    // Even a small map has an overview, and its statistics are in the file.
    EXPECT_EQ(d->GetRasterBand(1)->GetOverviewCount(), 1);
    EXPECT_NE(info.find("Overviews: 3x2"), std::string::npos) << info;
    EXPECT_NE(info.find("STATISTICS_MAXIMUM=35"), std::string::npos) << info;
    EXPECT_NE(info.find("STATISTICS_MINIMUM=0"), std::string::npos) << info;
    EXPECT_NE(info.find("STATISTICS_VALID_PERCENT=95.83"), std::string::npos) << info;  // 23 of 24 cells
    // Its style beside it: QGIS's pseudocolour classes with their labels.
    std::ifstream qml(dir + "/map.qml");
    const std::string style((std::istreambuf_iterator<char>(qml)), std::istreambuf_iterator<char>());
    EXPECT_NE(style.find("type=\"singlebandpseudocolor\""), std::string::npos) << style;
    EXPECT_NE(style.find("colorRampType=\"DISCRETE\""), std::string::npos) << style;
    EXPECT_NE(style.find("value=\"0.01\" color=\"#ffffb2\" alpha=\"255\" label=\"≤ 1 %\""), std::string::npos) << style;
    EXPECT_NE(style.find("value=\"inf\" color=\"#bd0026\""), std::string::npos) << style;
}

TEST(GisExport, StyleRangesAreRoundAndLabelled) {
    EXPECT_DOUBLE_EQ(gis::qgis::round_ceiling(14.2), 20.0);
    EXPECT_DOUBLE_EQ(gis::qgis::round_ceiling(58.0), 100.0);
    EXPECT_DOUBLE_EQ(gis::qgis::round_ceiling(0.037), 0.05);
    EXPECT_DOUBLE_EQ(gis::qgis::round_ceiling(2.0), 2.0);
    EXPECT_DOUBLE_EQ(gis::qgis::round_ceiling(0.0), 1.0);
    const gis::qgis::RasterStyle r = gis::qgis::ramp(20.0, {"#000000", "#111111", "#222222", "#333333", "#444444"}, "m");
    ASSERT_EQ(r.stops.size(), 5u);
    EXPECT_DOUBLE_EQ(r.stops[1].value, 5.0);
    EXPECT_EQ(r.stops[1].label, "5 m");
    EXPECT_EQ(gis::qgis::value_label(0.25, "1"), "25 %");
    EXPECT_EQ(gis::qgis::value_label(1.5, "m s-1"), "1.5 m/s");
}

TEST(GisExport, CropKeepsTheWindowAndEveryValue) {
    // A 10 x 4 map of 2 m cells; the window covers columns 4..7, rows 1..2; one value
    // outside it at column 1, row 0.
    Grid g{.nx = 10, .ny = 4, .x0 = 1.0, .y0 = 1.0, .dx = 2.0, .dy = 2.0};
    Grid window{.nx = 4, .ny = 2, .x0 = 9.0, .y0 = 3.0, .dx = 2.0, .dy = 2.0};
    std::vector<gis::MapLayer> maps(1);
    maps[0].values.assign(g.size(), std::nanf(""));
    maps[0].values[g.index(1, 0)] = 7.0f;
    maps[0].values[g.index(5, 2)] = 3.0f;
    gis::crop_maps(maps, g, window);
    EXPECT_EQ(g.nx, 7);  // columns 1..7
    EXPECT_EQ(g.ny, 3);  // rows 0..2
    EXPECT_DOUBLE_EQ(g.x0, 3.0);
    EXPECT_DOUBLE_EQ(g.y0, 1.0);
    EXPECT_EQ(maps[0].values[g.index(0, 0)], 7.0f);
    EXPECT_EQ(maps[0].values[g.index(4, 2)], 3.0f);
    // Without a value outside, exactly the window.
    Grid g2{.nx = 10, .ny = 4, .x0 = 1.0, .y0 = 1.0, .dx = 2.0, .dy = 2.0};
    std::vector<gis::MapLayer> maps2(1);
    maps2[0].values.assign(g2.size(), std::nanf(""));
    gis::crop_maps(maps2, g2, window);
    EXPECT_EQ(g2.nx, 4);
    EXPECT_EQ(g2.ny, 2);
    EXPECT_DOUBLE_EQ(g2.x0, 9.0);
    EXPECT_DOUBLE_EQ(g2.y0, 3.0);
}

TEST(GisExport, ProjectIsAZipQgisReadsWithRelativePaths) {
    const std::string dir = test::scratch_dir("gis_project");
    gis::qgis::Project p;
    p.title = "t";
    p.crs = utm53();
    p.x_min = east0;
    p.y_min = north0 - 100;
    p.x_max = east0 + 200;
    p.y_max = north0;
    p.groups = {"debris", "maps"};
    p.layers.push_back({gis::qgis::ProjectLayer::Kind::vector, dir + "/gis/tracks.gpkg", "tracks", "tracks & <lines>", "debris",
                        true, "<qgis version=\"3.22.16\" labelsEnabled=\"1\"><renderer-v2 type=\"singleSymbol\"/></qgis>"});
    p.layers.push_back({gis::qgis::ProjectLayer::Kind::raster, dir + "/gis/depth.tif", "", "depth [m]", "maps", false,
                        gis::qgis::raster_qml(gis::qgis::ramp(1.0, {"#000000", "#ffffff"}, "m"))});
    p.layers.push_back({gis::qgis::ProjectLayer::Kind::mesh, dir + "/flows/flow.nc", "", "flow", "maps", false,
                        "<qgis version=\"3.22.16\"></qgis>", 0.0, 6640.0});
    p.time_step = 15.8;
    gis::qgis::write_project(dir + "/gis/project.qgz", p);
    // GDAL reads the archive (a zip of one deflated file), as QGIS does.
    const std::string inside = "/vsizip/{" + dir + "/gis/project.qgz}/project.qgs";  // braces: not a .zip name
    VSIStatBufL st;
    ASSERT_EQ(VSIStatL(inside.c_str(), &st), 0);
    std::string xml(std::size_t(st.st_size), '\0');
    VSILFILE* f = VSIFOpenL(inside.c_str(), "rb");
    ASSERT_NE(f, nullptr);
    ASSERT_EQ(VSIFReadL(xml.data(), 1, xml.size(), f), xml.size());
    VSIFCloseL(f);
    EXPECT_EQ(xml, gis::qgis::project_xml(p, dir + "/gis"));
    EXPECT_NE(xml.find("<datasource>./tracks.gpkg|layername=tracks</datasource>"), std::string::npos) << xml;
    EXPECT_NE(xml.find("<datasource>../flows/flow.nc</datasource>"), std::string::npos) << xml;
    EXPECT_NE(xml.find("<Absolute type=\"bool\">false</Absolute>"), std::string::npos) << xml;
    EXPECT_NE(xml.find("<authid>EPSG:32653</authid>"), std::string::npos) << xml;
    EXPECT_NE(xml.find("name=\"tracks &amp; &lt;lines&gt;\""), std::string::npos) << xml;
    EXPECT_NE(xml.find("<layer-tree-group name=\"debris\""), std::string::npos) << xml;
    EXPECT_NE(xml.find("labelsEnabled=\"1\""), std::string::npos) << xml;
    EXPECT_LT(xml.find("name=\"debris\""), xml.find("name=\"maps\""));  // the order given: debris drawn above maps
    // The mesh on the temporal controller: the run's 0 to 6640 s (01:50:40) from the epoch that stands for its start.
    EXPECT_NE(xml.find("start-time-extent=\"2000-01-01T00:00:00Z\" end-time-extent=\"2000-01-01T01:50:40Z\""), std::string::npos)
        << xml;
    EXPECT_NE(xml.find("timeStepUnit=\"s\" timeStep=\"15.800000000000001\""), std::string::npos) << xml;
    // The same project gives the same bytes.
    std::ifstream a(dir + "/gis/project.qgz", std::ios::binary);
    const std::string first((std::istreambuf_iterator<char>(a)), std::istreambuf_iterator<char>());
    gis::qgis::write_project(dir + "/gis/project.qgz", p);
    std::ifstream b(dir + "/gis/project.qgz", std::ios::binary);
    EXPECT_EQ(first, std::string((std::istreambuf_iterator<char>(b)), std::istreambuf_iterator<char>()));
}

TEST(GisExport, GeoTiffSceneThroughHydroDebrisAndExportKeepsTheCrs) {
    const std::string dir = test::scratch_dir("gis_chain");
    // A 300 m x 100 m beach at 5 m in UTM 53N: bed -5 m in the west rising 0.2 m per cell east.
    gdal::init();
    {
        gdal::Dataset d(
            GetGDALDriverManager()->GetDriverByName("GTiff")->Create((dir + "/dem.tif").c_str(), 60, 20, 1, GDT_Float32, nullptr));
        double gt[6] = {east0, 5.0, 0.0, north0, 0.0, -5.0};
        d->SetGeoTransform(gt);
        OGRSpatialReference s;
        s.importFromEPSG(32653);
        d->SetSpatialRef(&s);
        std::vector<float> v(1200);
        for (int j = 0; j < 20; ++j)
            for (int i = 0; i < 60; ++i) v[j * 60 + i] = float(-5.0 + 0.2 * i);
        ASSERT_EQ(d->GetRasterBand(1)->RasterIO(GF_Write, 0, 0, 60, 20, v.data(), 60, 20, GDT_Float32, 0, 0, nullptr), CE_None);
    }
    test::write_file(dir, "features.toml",
                     "[[point]]\nname = \"CAR\"\nkind = \"start\"\nx = 518150.0\ny = 3779950.0\n[[manning]]\nn = 0.025\n"
                     "[hydro]\nmax-dt = 0.5\narrival-depth = 0.17\n");
    test::write_file(dir, "wave.csv", "time,eta\n0,0\n40,3.0\n200,3.0\n");
    std::string out;
    ASSERT_EQ(test::run_cli("scene import --dem " + dir + "/dem.tif --features " + dir + "/features.toml --resolution 5 --out " +
                                dir + "/scene.nc",
                            &out),
              0)
        << out;
    EXPECT_NE(out.find("CRS EPSG:32653"), std::string::npos) << out;
    ASSERT_EQ(test::run_cli("hydro --scene " + dir + "/scene.nc --west level --west-series " + dir +
                                "/wave.csv --duration 120 --output-interval 10 --out " + dir + "/flow.nc",
                            &out),
              0)
        << out;
    EXPECT_NE(out.find("recommended settings: max-dt = 0.5, arrival-depth = 0.17"), std::string::npos) << out;
    ASSERT_EQ(test::run_cli("debris --flow " + dir + "/flow.nc --scene " + dir +
                                "/scene.nc --start CAR --body car --at 518120,3779960,90 "
                                "--output-interval 5 --quiet --out " +
                                dir + "/tracks.nc",
                            &out),
              0)
        << out;
    {
        const nc::File f = nc::File::open_read(dir + "/flow.nc");
        EXPECT_EQ(f.att_text(f.var("h"), "grid_mapping").value_or(""), "crs");
        EXPECT_EQ(f.att_text(f.var("arrival_time"), "grid_mapping").value_or(""), "crs");
        EXPECT_DOUBLE_EQ(f.att_double(f.var("arrival_time"), "arrival_depth").value_or(0), 0.17);
        const nc::File t = nc::File::open_read(dir + "/tracks.nc");
        EXPECT_EQ(t.att_text(t.var("yaw"), "grid_mapping").value_or(""), "crs");
        EXPECT_EQ(cf::read_crs(t, "yaw").name(), "EPSG:32653");
        EXPECT_DOUBLE_EQ(t.get_double(t.var("length"))[0], 4.5);  // the catalogue's car
    }
    {
        // The flow reads as one mesh in QGIS: every gridded variable georeferenced, u and v
        // named as one vector's components, the time origin stated.
        const nc::File f = nc::File::open_read(dir + "/flow.nc");
        for (const char* v : {"z", "h", "u", "v", "max_depth", "max_speed", "arrival_time", "max_level", "flooded"})
            EXPECT_EQ(f.att_text(f.var(v), "grid_mapping").value_or(""), "crs") << v;
        EXPECT_EQ(f.att_text(f.var("u"), "long_name").value_or(""), "x-component of depth-averaged velocity (0 where dry)");
        EXPECT_EQ(f.att_text(f.var("v"), "long_name").value_or(""), "y-component of depth-averaged velocity (0 where dry)");
        EXPECT_EQ(f.att_text(f.var("u"), "standard_name").value_or(""), "sea_water_x_velocity");
        EXPECT_NE(f.att_text(f.var("time"), "comment").value_or("").find("t = 0 is the start of the run"), std::string::npos);
    }
    // The car's source in the port's survey CRS (EPSG:6674), to be carried into the scene's.
    {
        OGRSpatialReference utm, survey;
        utm.importFromEPSG(32653);
        survey.importFromEPSG(6674);
        utm.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
        survey.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
        std::unique_ptr<OGRCoordinateTransformation> to(OGRCreateCoordinateTransformation(&utm, &survey));
        double px = 518120.0, py = 3779960.0;
        ASSERT_TRUE(to->Transform(1, &px, &py));
        gdal::Dataset d(
            GetGDALDriverManager()->GetDriverByName("GPKG")->Create((dir + "/port.gpkg").c_str(), 0, 0, 0, GDT_Unknown, nullptr));
        OGRLayer* l = d->CreateLayer("cars", &survey, wkbPoint, nullptr);
        OGRFieldDefn type("type", OFTString);
        l->CreateField(&type);
        OGRFeature feature(l->GetLayerDefn());
        feature.SetField("type", "car");
        OGRPoint point(px, py);
        feature.SetGeometry(&point);
        ASSERT_EQ(l->CreateFeature(&feature), OGRERR_NONE);
    }
    ASSERT_EQ(test::run_cli("export --flow " + dir + "/flow.nc --trajectories " + dir + "/tracks.nc --sources " + dir +
                                "/port.gpkg --scene " + dir + "/scene.nc --out-dir " + dir + "/gis",
                            &out),
              0)
        << out;
    EXPECT_NE(out.find("project.qgz (QGIS project: 8 layers"), std::string::npos) << out;
    {
        // The scene's start point, named, in its CRS.
        gdal::Dataset v = gdal::open_vector(dir + "/gis/scene_features.gpkg");
        OGRLayer* layer = v->GetLayerByName("starts");
        ASSERT_NE(layer, nullptr);
        EXPECT_EQ(v->GetLayerByName("regions"), nullptr);  // the scene has none
        std::unique_ptr<OGRFeature, void (*)(OGRFeature*)> f(layer->GetNextFeature(), OGRFeature::DestroyFeature);
        ASSERT_TRUE(f);
        EXPECT_STREQ(f->GetFieldAsString("name"), "CAR");
        EXPECT_DOUBLE_EQ(f->GetGeometryRef()->toPoint()->getX(), 518150.0);
        EXPECT_STREQ(layer->GetSpatialRef()->GetAuthorityCode(nullptr), "32653");
    }
    ASSERT_EQ(
        test::run_cli(
            "export --trajectories " + dir + "/tracks.nc --tracks-format geojson --project none --out-dir " + dir + "/gis", &out),
        0)
        << out;

    // The depth map: georeferenced like the DEM, wet in the west, dry on the high ground.
    gdal::Dataset m = gdal::open_raster(dir + "/gis/max_depth.tif");
    double gt[6];
    ASSERT_EQ(m->GetGeoTransform(gt), CE_None);
    EXPECT_DOUBLE_EQ(gt[0], east0);
    EXPECT_DOUBLE_EQ(gt[3], north0);
    EXPECT_DOUBLE_EQ(gt[1], 5.0);
    EXPECT_DOUBLE_EQ(gt[5], -5.0);
    EXPECT_STREQ(m->GetSpatialRef()->GetAuthorityCode(nullptr), "32653");
    std::vector<float> depth(1200);
    ASSERT_EQ(m->GetRasterBand(1)->RasterIO(GF_Read, 0, 0, 60, 20, depth.data(), 60, 20, GDT_Float32, 0, 0, nullptr), CE_None);
    EXPECT_GT(depth[10 * 60 + 2], 5.0f);           // the sea bed at -4.7 m under a 3 m rise
    EXPECT_TRUE(std::isnan(depth[10 * 60 + 59]));  // +6.8 m ground, far above the water: never flooded, no value
    // Onshore (bed above still water, from x = 25 m east) apart: the sea has no value there.
    gdal::Dataset land = gdal::open_raster(dir + "/gis/inundation_depth.tif");
    std::vector<float> onshore(1200);
    ASSERT_EQ(land->GetRasterBand(1)->RasterIO(GF_Read, 0, 0, 60, 20, onshore.data(), 60, 20, GDT_Float32, 0, 0, nullptr), CE_None);
    EXPECT_TRUE(std::isnan(onshore[10 * 60 + 2]));
    EXPECT_TRUE(std::isnan(onshore[10 * 60 + 59]));
    EXPECT_GT(onshore[10 * 60 + 27], 1.0f);  // bed +0.4 m under the 3 m rise
    EXPECT_EQ(onshore[10 * 60 + 27], depth[10 * 60 + 27]);
    for (const char* map : {"max_depth", "inundation_depth", "max_speed", "arrival_time"}) {
        std::ifstream qml(dir + "/gis/" + map + ".qml");
        const std::string style((std::istreambuf_iterator<char>(qml)), std::istreambuf_iterator<char>());
        EXPECT_NE(style.find("singlebandpseudocolor"), std::string::npos) << map;
    }
    gdal::Dataset arrival = gdal::open_raster(dir + "/gis/arrival_time.tif");
    std::vector<float> at(1200);
    ASSERT_EQ(arrival->GetRasterBand(1)->RasterIO(GF_Read, 0, 0, 60, 20, at.data(), 60, 20, GDT_Float32, 0, 0, nullptr), CE_None);
    EXPECT_TRUE(std::isnan(at[10 * 60 + 59]));  // never reached: nodata

    // The tracks: two lines in EPSG:32653 starting where the bodies started.
    for (const char* name : {"/gis/tracks_tracks.gpkg", "/gis/tracks_tracks.geojson"}) {
        gdal::Dataset v = gdal::open_vector(dir + name);
        OGRLayer* layer = v->GetLayer(0);
        ASSERT_NE(layer, nullptr) << name;
        EXPECT_EQ(layer->GetFeatureCount(), 2) << name;
        ASSERT_NE(layer->GetSpatialRef(), nullptr) << name;
        EXPECT_STREQ(layer->GetSpatialRef()->GetAuthorityCode(nullptr), "32653") << name;
        std::unique_ptr<OGRFeature, void (*)(OGRFeature*)> f(layer->GetNextFeature(), OGRFeature::DestroyFeature);
        ASSERT_TRUE(f) << name;
        EXPECT_STREQ(f->GetFieldAsString("trajectory_id"), "CAR") << name;
        EXPECT_DOUBLE_EQ(f->GetFieldAsDouble("length"), 4.5) << name;
        const auto* line = f->GetGeometryRef()->toLineString();
        EXPECT_NEAR(line->getX(0), 518150.0, 1e-6) << name;
        EXPECT_NEAR(line->getY(0), 3779950.0, 1e-6) << name;
        EXPECT_GT(f->GetFieldAsDouble("path_length"), 0.0) << name;
        EXPECT_STREQ(f->GetFieldAsString("source"), "CAR") << name;  // no GIS feature: the body itself
    }
    // The styles travel with the data: the GeoPackage's layer_styles, a .qml beside the GeoJSON.
    EXPECT_NE(gis::qgis::stored_style(dir + "/gis/tracks_tracks.gpkg", "tracks").find("categorizedSymbol"), std::string::npos);
    EXPECT_TRUE(std::filesystem::exists(dir + "/gis/tracks_tracks.qml"));
    // The source in the scene's CRS, where it was given.
    {
        gdal::Dataset v = gdal::open_vector(dir + "/gis/sources.gpkg");
        OGRLayer* layer = v->GetLayerByName("source_points");
        ASSERT_NE(layer, nullptr);
        EXPECT_STREQ(layer->GetSpatialRef()->GetAuthorityCode(nullptr), "32653");
        std::unique_ptr<OGRFeature, void (*)(OGRFeature*)> f(layer->GetNextFeature(), OGRFeature::DestroyFeature);
        ASSERT_TRUE(f);
        EXPECT_STREQ(f->GetFieldAsString("layer"), "cars");
        EXPECT_NEAR(f->GetGeometryRef()->toPoint()->getX(), 518120.0, 1e-3);
        EXPECT_NEAR(f->GetGeometryRef()->toPoint()->getY(), 3779960.0, 1e-3);
        EXPECT_NE(gis::qgis::stored_style(dir + "/gis/sources.gpkg", "source_points").find("labelsEnabled=\"1\""),
                  std::string::npos);
    }
    // The project: maps, the flow as a mesh, tracks and sources, paths relative to it.
    VSIStatBufL st;
    const std::string inside = "/vsizip/{" + dir + "/gis/project.qgz}/project.qgs";  // braces: not a .zip name
    ASSERT_EQ(VSIStatL(inside.c_str(), &st), 0);
    std::string project(std::size_t(st.st_size), '\0');
    VSILFILE* pf = VSIFOpenL(inside.c_str(), "rb");
    ASSERT_EQ(VSIFReadL(project.data(), 1, project.size(), pf), project.size());
    VSIFCloseL(pf);
    for (const char* source : {"./inundation_depth.tif", "./max_depth.tif", "./max_speed.tif", "./arrival_time.tif", "../flow.nc",
                               "./tracks_tracks.gpkg|layername=tracks", "./sources.gpkg|layername=source_points",
                               "./scene_features.gpkg|layername=starts"})
        EXPECT_NE(project.find(std::string("<datasource>") + source + "</datasource>"), std::string::npos) << source;
    EXPECT_NE(project.find("<authid>EPSG:32653</authid>"), std::string::npos);
}

TEST(GisExport, HazardRegionsBecomePolygonsInTheSceneCrs) {
    // Two sources on 10 m cells in UTM 53N: A's inflow region a 3 x 2 block, its return
    // flow none; B's return flow one cell.
    const std::string dir = test::scratch_dir("gis_hazard");
    const Grid g{.nx = 8, .ny = 5, .x0 = east0 + 5.0, .y0 = north0 - 45.0, .dx = 10.0, .dy = 10.0};
    {
        nc::File f = nc::File::create(dir + "/hazard_regions.nc");
        const int ds = f.def_dim("source", 2), dy = f.def_dim("y", std::size_t(g.ny)), dx = f.def_dim("x", std::size_t(g.nx));
        const cf::XYAxes axes = cf::def_xy(f, dx, dy, "cell centre");
        cf::def_crs(f, utm53());
        const int vs = f.def_text_var("source", {ds}, 1);
        const int vin = cf::def_var(f, {.name = "region_inflow", .type = NC_BYTE, .dims = {ds, dy, dx}, .grid_mapping = "crs"});
        const int vout = cf::def_var(f, {.name = "region_outflow", .type = NC_BYTE, .dims = {ds, dy, dx}, .grid_mapping = "crs"});
        f.enddef();
        std::vector<double> x(std::size_t(g.nx)), y(std::size_t(g.ny));
        for (int i = 0; i < g.nx; ++i) x[std::size_t(i)] = g.x(i);
        for (int j = 0; j < g.ny; ++j) y[std::size_t(j)] = g.y(j);
        f.put(axes.x, x);
        f.put(axes.y, y);
        f.put(vs, std::vector<std::string>{"A", "B"});
        std::vector<std::int8_t> in(2 * g.size(), 0), back(2 * g.size(), 0);
        for (int j = 1; j <= 2; ++j)
            for (int i = 2; i <= 4; ++i) in[g.index(i, j)] = 1;
        back[g.size() + g.index(6, 3)] = 1;
        f.put(vin, in);
        f.put(vout, back);
    }
    ASSERT_EQ(gis::write_hazard_regions(dir + "/hazard_regions.nc", dir + "/hazard_regions.gpkg"), 2u);
    gdal::Dataset v = gdal::open_vector(dir + "/hazard_regions.gpkg");
    OGRLayer* layer = v->GetLayerByName("hazard_regions");
    ASSERT_NE(layer, nullptr);
    EXPECT_STREQ(layer->GetSpatialRef()->GetAuthorityCode(nullptr), "32653");
    std::unique_ptr<OGRFeature, void (*)(OGRFeature*)> a(layer->GetNextFeature(), OGRFeature::DestroyFeature);
    ASSERT_TRUE(a);
    EXPECT_STREQ(a->GetFieldAsString("source"), "A");
    EXPECT_STREQ(a->GetFieldAsString("flow"), "inflow");
    EXPECT_DOUBLE_EQ(a->GetFieldAsDouble("area_m2"), 600.0);
    OGREnvelope e;
    a->GetGeometryRef()->getEnvelope(&e);
    EXPECT_DOUBLE_EQ(e.MinX, east0 + 20.0);  // columns 2..4, rows 1..2
    EXPECT_DOUBLE_EQ(e.MaxX, east0 + 50.0);
    EXPECT_DOUBLE_EQ(e.MinY, north0 - 40.0);
    EXPECT_DOUBLE_EQ(e.MaxY, north0 - 20.0);
    EXPECT_DOUBLE_EQ(a->GetGeometryRef()->toMultiPolygon()->get_Area(), 600.0);
    std::unique_ptr<OGRFeature, void (*)(OGRFeature*)> b(layer->GetNextFeature(), OGRFeature::DestroyFeature);
    ASSERT_TRUE(b);
    EXPECT_STREQ(b->GetFieldAsString("source"), "B");
    EXPECT_STREQ(b->GetFieldAsString("flow"), "return flow");
    EXPECT_NE(gis::qgis::stored_style(dir + "/hazard_regions.gpkg", "hazard_regions").find("categorizedSymbol"), std::string::npos);
}
