// One flotsam run driving a finer one through a box's outline, through the command line:
// --boundary-output writes the outline, --<side>-forcing reads it.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <sstream>

#include "common/netcdf.hpp"
#include "formats/scene.hpp"
#include "test_support.hpp"

using namespace flotsam;

namespace {

// A 4 m x 1.5 m basin of 0.1 m water, 5 cm cells, with a dry island (x 2.6-2.9 m,
// y 0.5-0.8 m) and a submerged bump; `i0` drops the cells west of x = i0 * 5 cm (the box).
std::string basin(const std::string& dir, const std::string& name, int i0) {
    Scene s;
    s.grid = Grid{80 - i0, 30, 0.025 + 0.05 * i0, 0.025, 0.05, 0.05};
    for (int j = 0; j < s.grid.ny; ++j)
        for (int i = 0; i < s.grid.nx; ++i) {
            const double x = s.grid.x(i), y = s.grid.y(j);
            double z = -0.1 + 0.04 * std::exp(-((x - 1.8) * (x - 1.8) + (y - 1.1) * (y - 1.1)) / 0.05);
            if (x > 2.6 && x < 2.9 && y > 0.5 && y < 0.8) z = 0.05;
            s.z.push_back(z);
        }
    s.points = {{"G1", "gauge", 2.2, 0.4, 0.0}, {"G2", "gauge", 3.5, 1.2, 0.0}};
    const std::string path = dir + "/" + name;
    write_scene(path, s, "test");
    return path;
}

std::vector<double> gauge_eta(const std::string& flow) {
    const nc::File f = nc::File::open_read(flow);
    return f.get_double(f.var("gauge_eta"));
}

}  // namespace

// The box run (x from 1 m) forced on the west by the outline the whole basin's run wrote at
// every step reproduces the whole run at the two gauges inside, within 2 % of the wave's
// height (measured: 1.06 %). What is left is the outline's value at the box's edge (the
// mean of the two cells beside it) standing in for the ghost cells' states half a cell and
// more beyond it: a first-order difference in the cell size, the same with the record's
// state imposed outright as with its incoming characteristic. The box with a wall in place
// of the forced side is off by the whole wave.
TEST(BoundaryForcingCli, ABoxForcedByTheOutlineOfTheWholeRunReproducesIt) {
    const std::string dir = test::scratch_dir("ForcingCli");
    std::ostringstream csv;
    csv << "time,eta\n";
    for (int k = 0; k <= 80; ++k) {
        const double t = 0.1 * k, s = std::sin(std::acos(-1.0) * std::min(t, 2.0) / 2.0);
        csv << t << "," << 0.02 * s * s << "\n";
    }
    const std::string hump = test::write_file(dir, "hump.csv", csv.str());
    const std::string whole = basin(dir, "whole.nc", 0), box = basin(dir, "box.nc", 20);
    std::string out;
    const std::string common = " --east wall --duration 8 --output-interval 1 --quiet";
    ASSERT_EQ(test::run_cli("hydro --scene " + whole + " --west-series " + hump + common + " --boundary-output " + dir +
                                "/outline.nc --boundary-box 1,4,0,1.5 --boundary-interval 0 --out " + dir + "/whole-flow.nc",
                            &out),
              0)
        << out;
    ASSERT_EQ(test::run_cli("hydro --scene " + box + " --west-forcing " + dir + "/outline.nc" + common + " --out " + dir +
                                "/box-flow.nc",
                            &out),
              0)
        << out;
    ASSERT_EQ(test::run_cli("hydro --scene " + box + " --west wall" + common + " --out " + dir + "/walled.nc", &out), 0) << out;
    const auto a = gauge_eta(dir + "/whole-flow.nc"), b = gauge_eta(dir + "/box-flow.nc"), w = gauge_eta(dir + "/walled.nc");
    ASSERT_EQ(a.size(), b.size());
    double peak = 0.0, worst = 0.0, walled = 0.0;
    for (std::size_t k = 0; k < a.size(); ++k) {
        peak = std::max(peak, std::abs(a[k]));
        worst = std::max(worst, std::abs(a[k] - b[k]));
        walled = std::max(walled, std::abs(a[k] - w[k]));
    }
    std::printf("gauges inside the box, 0-8 s: peak %.4f m; box run off by %.2e m (%.2f %%), a walled box by %.2e m\n", peak,
                worst, 100 * worst / peak, walled);
    EXPECT_GT(peak, 0.005);
    EXPECT_LT(worst, 0.02 * peak);
    EXPECT_GT(walled, 0.5 * peak);
    // The forced side is recorded (west = "forced", west-forcing = the file): the flow's
    // own settings give it again, to the bit.
    const nc::File flow = nc::File::open_read(dir + "/box-flow.nc");
    const std::string config = test::write_file(dir, "box.toml", *flow.att_text(NC_GLOBAL, "flotsam_config"));
    ASSERT_EQ(test::run_cli("hydro --config " + config + " --quiet --out " + dir + "/again.nc", &out), 0) << out;
    const nc::File again = nc::File::open_read(dir + "/again.nc");
    EXPECT_EQ(flow.get_float(flow.var("h")), again.get_float(again.var("h")));
}

// What a user gets wrong is named, and leaves no output.
TEST(BoundaryForcingCli, MisusedOptionsAreNamed) {
    const std::string dir = test::scratch_dir("ForcingCliErrors");
    const std::string whole = basin(dir, "whole.nc", 0), box = basin(dir, "box.nc", 20);
    std::string out;
    const std::string common = " --west wall --east wall --duration 1 --quiet --out " + dir + "/f.nc";
    EXPECT_NE(test::run_cli("hydro --scene " + whole + common + " --boundary-output " + dir + "/o.nc --boundary-box 1,5,0,1",
                            &out),
              0);
    EXPECT_NE(out.find("--boundary-box: 1,5,0,1 reaches outside the grid"), std::string::npos) << out;
    EXPECT_NE(test::run_cli("hydro --scene " + whole + common + " --boundary-output " + dir + "/o.nc", &out), 0);
    EXPECT_NE(out.find("--boundary-output: goes with --boundary-box"), std::string::npos) << out;
    ASSERT_EQ(test::run_cli("hydro --scene " + whole + common + " --boundary-output " + dir + "/o.nc --boundary-box 1,4,0,1.5",
                            &out),
              0)
        << out;
    EXPECT_NE(test::run_cli("hydro --scene " + box + " --west level --west-forcing " + dir + "/o.nc --east wall --duration 1 "
                            "--quiet --out " + dir + "/g.nc",
                            &out),
              0);
    EXPECT_NE(out.find("--west-forcing: forces the west side, which --west makes 'level'"), std::string::npos) << out;
    EXPECT_NE(test::run_cli("hydro --scene " + box + " --west-forcing " + dir + "/f.nc --east wall --duration 1 --quiet --out " +
                            dir + "/g.nc",
                            &out),
              0);
    EXPECT_NE(out.find("f.nc: flotsam_file_kind: is 'flow', not boundary values"), std::string::npos) << out;
    EXPECT_NE(test::run_cli("hydro --scene " + whole + " --west-forcing " + dir + "/o.nc --east wall --duration 1 --quiet --out " +
                            dir + "/g.nc",
                            &out),
              0);
    EXPECT_NE(out.find("o.nc: stations: none within"), std::string::npos) << out;
    EXPECT_FALSE(std::filesystem::exists(dir + "/g.nc"));
    EXPECT_NE(test::run_cli("hydro --scene " + whole + common + " --restart --boundary-output " + dir +
                                "/p.nc --boundary-box 1,4,0,1.5",
                            &out),
              0);
    EXPECT_NE(out.find("--boundary-output: is written from the start of a run"), std::string::npos) << out;
}
