// GIS inputs through the command line: every path GDAL opens is a file (a FIFO in its
// place, or beside it, is refused before GDAL would wait on it for ever), and the layers'
// values mean something: yards that cross themselves, headings beyond a turn and yards too
// large to lay out are refused naming the feature (docs/reliability.md).
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>

#include "data/gdal_support.hpp"
#include "formats/scene.hpp"
#include "tests/reliability_cases.hpp"

using namespace flotsam;
using namespace flotsam::test;
namespace fs = std::filesystem;

namespace {

// One feature of a debris-source layer: its geometry (WKT, local metres) and attributes.
struct Feature {
    std::string wkt;
    std::string type = "car";
    double heading = 0.0;
    int count = 0;  // yards; 0: not set
};

// A GeoPackage layer "sources" without a CRS (the small scene is in local metres).
std::string write_sources(const std::string& path, const std::vector<Feature>& features) {
    gdal::init();
    GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GPKG");
    gdal::Dataset ds(driver->Create(path.c_str(), 0, 0, 0, GDT_Unknown, nullptr));
    OGRLayer* layer = ds->CreateLayer("sources", nullptr, wkbUnknown, nullptr);
    for (const auto& [name, type] : {std::pair{"type", OFTString}, std::pair{"heading", OFTReal}, std::pair{"count", OFTInteger}}) {
        OGRFieldDefn d(name, type);
        layer->CreateField(&d);
    }
    for (const Feature& f : features) {
        OGRFeature feature(layer->GetLayerDefn());
        feature.SetField("type", f.type.c_str());
        feature.SetField("heading", f.heading);
        if (f.count > 0) feature.SetField("count", f.count);
        OGRGeometry* g = nullptr;
        OGRGeometryFactory::createFromWkt(f.wkt.c_str(), nullptr, &g);
        feature.SetGeometryDirectly(g);
        EXPECT_EQ(layer->CreateFeature(&feature), OGRERR_NONE);
    }
    return path;
}

// "POINT (x y)" and a square yard of side `side` [m] from (x, y), or a bow tie over it.
std::string point(double x, double y) { return "POINT (" + std::to_string(x) + " " + std::to_string(y) + ")"; }
std::string square(double x, double y, double side, bool bow_tie = false) {
    const std::string a = std::to_string(x), b = std::to_string(x + side), c = std::to_string(y), d = std::to_string(y + side);
    return bow_tie ? "POLYGON ((" + a + " " + c + "," + b + " " + d + "," + b + " " + c + "," + a + " " + d + "," + a + " " + c + "))"
                   : "POLYGON ((" + a + " " + c + "," + b + " " + c + "," + b + " " + d + "," + a + " " + d + "," + a + " " + c + "))";
}

}  // namespace

// A FIFO where a GIS input goes (or beside a shapefile, where GDAL reads its .dbf): every
// command refuses it at once, naming the option and the path; none waits on it.
TEST(ReliabilityCli, GisInputsThatAreNotFilesAreRefusedBeforeGdalOpensThem) {
    const SmallCase c = small_case("cli_gis_fifo");
    const Outputs o = flow_and_sweep(c);
    const std::string fifo = c.dir + "/port.gpkg";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0644), 0);
    // A shapefile whose .dbf is a FIFO.
    const Scene scene = read_scene(c.scene);
    const ScenePoint* fd = scene.find_point("FD");
    ASSERT_NE(fd, nullptr);
    write_sources(c.dir + "/ok.gpkg", {{point(fd->x, fd->y), "paper_box"}});
    ASSERT_EQ(test::run_cli("debris --flow " + o.flow + " --scene " + c.scene + " --sources " + c.dir +
                                "/ok.gpkg --end-time 0.5 --quiet --out " + c.dir + "/ok.nc"),
              0);
    gdal::Dataset shp(GetGDALDriverManager()->GetDriverByName("ESRI Shapefile")->Create((c.dir + "/yard.shp").c_str(), 0, 0, 0,
                                                                                       GDT_Unknown, nullptr));
    ASSERT_NE(shp->CreateLayer("yard", nullptr, wkbPolygon, nullptr), nullptr);
    shp.reset();
    fs::remove(c.dir + "/yard.dbf");
    ASSERT_EQ(::mkfifo((c.dir + "/yard.dbf").c_str(), 0644), 0);
    const std::string spec = test::write_file(c.dir, "fifo.toml",
                                              "[sweep]\nscene = \"" + c.scene + "\"\n[flows]\npaths = [\"" + o.flow +
                                                  "\"]\n[[sources]]\nfile = \"" + fifo + "\"\n");
    const std::string import = "scene import --dem " + c.scene + " --resolution 0.32 --out " + c.dir + "/i.nc ";
    const std::string fifo_message = "is a FIFO (named pipe), not a regular file";
    for (const Case& k : std::vector<Case>{
             {"debris --flow " + o.flow + " --scene " + c.scene + " --sources " + fifo + " --quiet --out " + c.dir + "/d.nc",
              "--sources: " + fifo + ": " + fifo_message},
             {"debris --flow " + o.flow + " --scene " + c.scene + " --sources " + c.dir + "/yard.shp --quiet --out " + c.dir + "/d.nc",
              c.dir + "/yard.dbf: " + fifo_message},
             {"sweep --spec " + spec + " --quiet --out " + c.dir + "/w.nc", fifo + ": " + fifo_message},
             {import + "--buildings " + fifo, "--buildings: " + fifo + ": " + fifo_message},
             {import + "--manning-raster " + fifo, "--manning-raster: " + fifo + ": " + fifo_message},
             {import + "--manning-polygons " + fifo, "--manning-polygons: " + fifo + ": " + fifo_message},
             {import + "--crs " + fifo, "--crs: " + fifo + ": " + fifo_message},
         }) {
        std::string out;
        // Under `timeout`: a command that waits on the FIFO ends with 124 instead of hanging the test.
        const int rc = test::finish_cli(test::start_cli(k.args, "timeout 60"), &out);
        EXPECT_EQ(rc, 1) << k.args << "\n" << out;
        EXPECT_NE(out.find(k.expect), std::string::npos) << k.args << "\n" << out;
    }
}

// A yard that crosses itself (a bow tie) has no inside to fill; a heading of 1e300 degrees
// is no direction; a yard of 1e12 m² would lay out 1e11 places (3.2 GB and minutes): each
// is refused naming the file, the feature and what is wrong, before any body moves.
TEST(ReliabilityCli, YardsAndHeadingsThatMeanNothingAreRefused) {
    const SmallCase c = small_case("cli_gis_values");
    const Outputs o = flow_and_sweep(c);
    const Scene scene = read_scene(c.scene);
    const ScenePoint* fd = scene.find_point("FD");
    ASSERT_NE(fd, nullptr);
    const double x = fd->x, y = fd->y;
    const std::string bow = write_sources(c.dir + "/bow.gpkg", {{square(x - 0.4, y - 0.4, 0.8, true), "paper_box", 0.0, 2}});
    Feature far{point(x, y), "paper_box", 1e300};
    const std::string heading = write_sources(c.dir + "/heading.gpkg", {far});
    const std::string huge = write_sources(c.dir + "/huge.gpkg", {{square(x - 5e5, y - 5e5, 1e6), "paper_box", 0.0, 100}});
    const auto debris = [&](const std::string& sources) {
        return "debris --flow " + o.flow + " --scene " + c.scene + " --sources " + sources + " --quiet --out " + c.dir + "/d.nc";
    };
    expect_named_errors({
        {debris(bow), "bow.gpkg:sources feature 1: polygon: crosses itself: the edge from ("},
        {debris(heading), "heading.gpkg:sources feature 1: attribute 'heading': 1e+300 is outside the allowed range [-360, 360] degree"},
        {debris(huge), "huge.gpkg:sources feature 1: yard: a yard of 1e+12 m² for bodies of 0.25 x 0.1 m would make 4e+13 places to "
                       "lay out, more than the 1e+07 flotsam runs without being asked to"},
    });
    EXPECT_FALSE(fs::exists(c.dir + "/d.nc"));
}
