// The design standard's hazard region beside a simulation (pipelines/hazard_region.py):
// a point source in a uniform current at 30 degrees gets the +-22.5 degree wedge from its
// origin, cell by cell as worked out by hand, and the buildings in it and outside it are
// told apart.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "cases/debris_flows.hpp"
#include "common/netcdf.hpp"
#include "formats/scene.hpp"
#include "tests/test_support.hpp"

using namespace flotsam;

// Origin (0.21, 0.15), a cell centre; current 0.15 m/s toward 30 degrees. A cell is in the
// region when the direction to its centre lies within 7.5..52.5 degrees:
//   (0.51, 0.33) atan(0.18/0.30) = 31.0  in      (0.41, 0.49) atan(0.34/0.20) = 59.5  out
//   (0.51, 0.49) atan(0.34/0.30) = 48.6  in      (0.31, 0.29) atan(0.14/0.10) = 54.5  out
//   (0.33, 0.29) atan(0.14/0.12) = 49.4  in      (0.71, 0.21) atan(0.06/0.50) =  6.8  out
//   (0.71, 0.23) atan(0.08/0.50) =  9.1  in      (0.11, 0.09) behind the origin      out
// Building 2 (x 0.90..0.96, y 0.30..0.36: 13.9 degrees from the origin) is in the region
// and the body never reaches it; building 1 (x 0.50..0.56, y 0.02..0.08: -17 degrees) is
// not. The body drifts along 30 degrees through 19 cells; one, (0.23, 0.15), lies at 0
// degrees from the origin (the track enters it at x = 0.22, y = 0.156): 18/19 = 0.9474 of
// the passages lie in the region, and the body ends in it.
TEST(HazardRegion, APointSourceInAUniformCurrentGetsTheWedgeByHand) {
    const auto dir = test::scratch_dir("hazard_region");
    const Grid g{60, 40, 0.01, 0.01, 0.02, 0.02};
    const double speed = 0.15, angle = 30.0 * M_PI / 180.0;
    const std::string flow = test::uniform_flow(dir + "/flow.nc", g, 6.0, 0.06, speed * std::cos(angle), speed * std::sin(angle));
    Scene scene;
    scene.grid = g;
    scene.z.assign(g.size(), -0.1);
    scene.building.assign(g.size(), 0);
    auto block = [&](double x0, double x1, double y0, double y1) {
        for (int j = 0; j < g.ny; ++j)
            for (int i = 0; i < g.nx; ++i)
                if (g.x(i) > x0 && g.x(i) < x1 && g.y(j) > y0 && g.y(j) < y1) scene.building[g.index(i, j)] = 1;
    };
    block(0.50, 0.56, 0.02, 0.08);  // numbered first: its cells come first in the south-first scan
    block(0.90, 0.96, 0.30, 0.36);
    write_scene(dir + "/scene.nc", scene, "test");
    // The flow's bed under the buildings is the open bed: buildings stand in the scene's mask only.
    const std::string spec = test::write_file(dir, "spec.toml",
                                              "[sweep]\noutput-interval = 0.25\nscene = \"" + dir + "/scene.nc\"\n[flows]\npaths = [\"" +
                                                  flow + "\"]\n[[body]]\nname = \"P\"\nat = [0.21, 0.15, 30]\n");
    std::string out;
    ASSERT_EQ(test::run_cli("sweep --spec " + spec + " --out " + dir + "/sweep.nc --quiet --threads 1", &out), 0) << out;
    const std::string cmd = "cd " FLOTSAM_SOURCE_DIR " && /usr/bin/python3 -m pipelines.hazard_region --sweep " + dir +
                            "/sweep.nc --out " + dir + "/hazard --no-charts > " + dir + "/log.txt 2>&1";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << test::read_text(dir + "/log.txt");

    nc::File f = nc::File::open_read(dir + "/hazard/hazard_regions.nc");
    const std::vector<int> region = f.get_int(f.var("region_inflow")), back = f.get_int(f.var("region_outflow"));
    auto in = [&](double x, double y) { return region[g.index(g.cell_i(x), g.cell_j(y))] == 1; };
    for (auto [x, y] : {std::pair{0.51, 0.33}, {0.51, 0.49}, {0.33, 0.29}, {0.71, 0.23}, {0.21, 0.15}}) EXPECT_TRUE(in(x, y)) << x << ", " << y;
    for (auto [x, y] : {std::pair{0.41, 0.49}, {0.31, 0.29}, {0.71, 0.21}, {0.11, 0.09}}) EXPECT_FALSE(in(x, y)) << x << ", " << y;
    for (int k : back) EXPECT_EQ(k, 0);  // a steady current has no return flow

    const std::string table = test::read_text(dir + "/hazard/hazard_regions.csv");
    std::istringstream rows(table);
    std::string header, row;
    std::getline(rows, header);
    std::getline(rows, row);
    // source, origins (start positions), members, origin x, y, inflow, outflow, shares (3), ending inside, in region, hit, hit outside, never hit
    EXPECT_EQ(row, "P,1,1,0.210,0.150,30.00,,0.9474,0.0000,0.9474,1.0000,1,0,,2");
    const std::string buildings = test::read_text(dir + "/hazard/hazard_buildings.csv");
    EXPECT_NE(buildings.find("P,2,1,0.0000"), std::string::npos) << buildings;
    EXPECT_EQ(buildings.find("P,1,"), std::string::npos) << buildings;
}
