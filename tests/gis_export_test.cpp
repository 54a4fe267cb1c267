// GIS out: the Cloud-Optimised GeoTIFFs read back through GDAL with the right
// origin, pixel size, north-up orientation, CRS and values, and gdalinfo reports a COG;
// and the whole chain from a GeoTIFF through hydro, debris (a catalogue body) and export
// carries the CRS into every file, the maps and the track lines.
#include "export/gis_export.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>

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
    ASSERT_EQ(
        test::run_cli("export --flow " + dir + "/flow.nc --trajectories " + dir + "/tracks.nc --out-dir " + dir + "/gis", &out), 0)
        << out;
    ASSERT_EQ(test::run_cli("export --trajectories " + dir + "/tracks.nc --tracks-format geojson --out-dir " + dir + "/gis", &out),
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
    EXPECT_GT(depth[10 * 60 + 2], 5.0f);   // the sea bed at -4.7 m under a 3 m rise
    EXPECT_EQ(depth[10 * 60 + 59], 0.0f);  // +6.8 m ground, far above the water
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
    }
}
