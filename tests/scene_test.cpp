// The generated scene keeps SCENE.md's numbers at every grid spacing and is reproducible;
// the importer reads the real layout, ASCII grids and TOML features, and rejects bad
// inputs naming file and variable or line.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <functional>

#include "common/error.hpp"
#include "common/netcdf.hpp"
#include "common/sha256.hpp"
#include "data/dem_import.hpp"
#include "data/resample.hpp"
#include "data/scene_generator.hpp"
#include "tests/test_support.hpp"

using namespace flotsam;
using test::error_of;
using test::write_file;

namespace {

double at(const Scene& s, const std::vector<double>& f, double x, double y) {
    return f[s.grid.index(s.grid.cell_i(x), s.grid.cell_j(y))];
}

class GeneratedScene_ : public ::testing::TestWithParam<double> {};

}  // namespace

TEST_P(GeneratedScene_, KeepsSceneNumbers) {
    const double res = GetParam();
    const GeneratedScene g = generate_scene({.resolution = res, .seed = 7});
    const Scene& s = g.scene;
    EXPECT_TRUE(s.synthetic);
    EXPECT_NEAR(s.grid.x_min_edge(), -12.365, 1e-9);
    EXPECT_NEAR(s.grid.y_min_edge(), -4.005, 1e-9);
    EXPECT_GE(s.grid.x_max_edge(), 8.005 - 1e-9);
    EXPECT_LT(s.grid.x_max_edge(), 8.005 + res);
    EXPECT_DOUBLE_EQ(at(s, s.z, -10.0, -2.0), -0.877);                       // flat flume bed
    EXPECT_NEAR(at(s, s.z, -4.0, -1.0), -0.877 + 0.1 * (-4.0 + 8.4), 0.02);  // 1:10 slope
    const double fd = at(s, s.z, 1.37, -2.15), ld = at(s, s.z, 2.94, -1.26);
    EXPECT_LE(fd, -0.02);  // FD rests on the seabed 2-3 cm below still water
    EXPECT_GE(fd, -0.03);
    EXPECT_GE(ld, 0.01);  // LD on land 1-2 cm above still water
    EXPECT_LE(ld, 0.02);
    std::size_t land = 0, roofs = 0;
    for (int j = 0; j < s.grid.ny; ++j)
        for (int i = 0; i < s.grid.nx; ++i) {
            const std::size_t k = s.grid.index(i, j);
            const double x = s.grid.x(i), y = s.grid.y(j);
            EXPECT_EQ(s.manning_n[k], x < -0.66 ? 0.025 : 0.013);
            if (std::hypot(x - 2.94, y + 1.26) < 0.2) {
                EXPECT_EQ(s.building[k], 0) << x << "," << y;
            }
            if (x < -0.65 || g.ground[k] < 0.0) continue;
            ++land;
            if (!s.building[k]) continue;
            ++roofs;
            if (x > 0.6) {  // city buildings (the breakwater wall stands at x = 0.1)
                EXPECT_GE(s.z[k] - g.ground[k], 0.04 - 1e-6);
                EXPECT_LE(s.z[k] - g.ground[k], 0.05 + 1e-6);
            }
        }
    const double fraction = double(roofs) / double(land);
    EXPECT_GT(fraction, 0.2);
    EXPECT_LT(fraction, 0.35);
    ASSERT_NE(s.find_point("FD"), nullptr);
    EXPECT_EQ(s.find_point("WG1")->x, -11.9);
    EXPECT_EQ(s.sections.front().x, 1.8);
    EXPECT_EQ(s.regions.size(), 4u);
}

INSTANTIATE_TEST_SUITE_P(Resolutions, GeneratedScene_, ::testing::Values(0.01, 0.02, 0.04));

TEST(GeneratedScene, ByteIdenticalForSameSeed) {
    const auto dir = test::scratch_dir("scene-det");
    const std::string p = dir + "/s.nc";
    write_scene(p, generate_scene({.resolution = 0.04, .seed = 3}).scene, "test");
    const std::string first = sha256_file(p);
    write_scene(p, generate_scene({.resolution = 0.04, .seed = 3}).scene, "test");
    EXPECT_EQ(sha256_file(p), first);
    write_scene(p, generate_scene({.resolution = 0.04, .seed = 4}).scene, "test");
    EXPECT_NE(sha256_file(p), first);
    const Scene back = read_scene(p);
    EXPECT_TRUE(back.synthetic);
    EXPECT_EQ(back.points.size(), 4u);
    EXPECT_EQ(back.building.size(), back.grid.size());
}

TEST(ImportScene, RealLayoutKeepsMeanAndStarts) {
    const std::string real = test::shared_data("city-topography-from-figure.nc");
    if (real.empty()) GTEST_SKIP() << "shared data not present";
    const Dem dem = read_dem(real);
    auto city_mean = [](const Grid& g, const std::vector<double>& z) {
        double sum = 0, area = 0;
        for (int j = 0; j < g.ny; ++j)
            for (int i = 0; i < g.nx; ++i) {
                const double w = std::clamp(std::min(g.x(i) + 0.5 * g.dx, 8.005) - std::max(g.x(i) - 0.5 * g.dx, 0.0), 0.0, g.dx) *
                                 std::clamp(std::min(g.y(j) + 0.5 * g.dy, -0.005) - (g.y(j) - 0.5 * g.dy), 0.0, g.dy);
                sum += w * z[g.index(i, j)];
                area += w;
            }
        return sum / area;
    };
    const double source_mean = city_mean(dem.grid, dem.z);
    for (double res : {0.02, 0.04}) {
        const Scene s = import_scene({real, "", res});
        EXPECT_NEAR(city_mean(s.grid, s.z), source_mean, 2e-4) << res;
        EXPECT_NEAR(at(s, s.z, 1.37, -2.15), -0.026, 0.004) << res;
        EXPECT_NEAR(at(s, s.z, 2.94, -1.26), 0.015, 0.004) << res;
        EXPECT_EQ(s.points.size(), 4u);  // Kainan defaults: the extent matches
        EXPECT_EQ(at(s, s.manning_n, -1.0, -2.0), 0.025);
        EXPECT_EQ(at(s, s.manning_n, 1.0, -2.0), 0.013);
        EXPECT_FALSE(s.synthetic);
    }
}

// The measured layout's channel regions lie on its channels: on cross-sections 5 cm apart
// the lowest ground of the 1 cm import (Channel B's trench, z a few mm below still water
// between banks at +5 to +10 mm; Channel A's north leg) lies inside `channel_b` and
// `channel_a`. The generated scene's polygons (its own channels) miss Channel B by
// some 0.3 m, which is why an import has its own.
TEST(ImportScene, RealLayoutChannelRegionsHoldTheChannelsLowestGround) {
    const std::string real = test::shared_data("city-topography-from-figure.nc");
    if (real.empty()) GTEST_SKIP() << "shared data not present";
    const Scene s = import_scene({real, "", 0.01});
    const Scene generated = generate_scene(SceneGenDef{}).scene;
    auto region = [](const Scene& sc, const std::string& name) -> const Region& {
        for (const Region& r : sc.regions)
            if (r.name == name) return r;
        ADD_FAILURE() << "no region " << name;
        return sc.regions.front();
    };
    // The lowest ground along x = const within [y0, y1], or along y = const within [x0, x1].
    auto lowest_in_column = [&](double x, double y0, double y1) {
        double best = 1e9, at_y = 0.0;
        for (double y = y0; y <= y1; y += 0.01)
            if (const double z = at(s, s.z, x, y); z < best) best = z, at_y = y;
        return at_y;
    };
    auto lowest_in_row = [&](double y, double x0, double x1) {
        double best = 1e9, at_x = 0.0;
        for (double x = x0; x <= x1; x += 0.01)
            if (const double z = at(s, s.z, x, y); z < best) best = z, at_x = x;
        return at_x;
    };
    int generated_misses = 0;
    for (double x = 3.80; x <= 4.60; x += 0.05) {
        const double y = lowest_in_column(x, -3.5, -2.85);
        EXPECT_TRUE(region(s, "channel_b").contains(x, y)) << x << ", " << y;
        generated_misses += region(generated, "channel_b").contains(x, y) ? 0 : 1;
    }
    EXPECT_GT(generated_misses, 10);
    for (double y = -1.76; y <= -1.48; y += 0.04) {
        const double x = lowest_in_row(y, 4.30, 4.60);
        EXPECT_TRUE(region(s, "channel_a").contains(x, y)) << x << ", " << y;
    }
    for (double x = 4.90; x <= 5.45; x += 0.05) {
        const double y = lowest_in_column(x, -1.85, -1.30);
        EXPECT_TRUE(region(s, "channel_a").contains(x, y)) << x << ", " << y;
    }
}

TEST(ImportScene, AsciiGridRoundTripAndCoarsening) {
    const auto dir = test::scratch_dir("asc");
    // 4 columns x 2 rows, rows north to south; cell 0.5 m, lower-left corner (10, 20).
    const std::string p = write_file(
        dir, "dem.asc", "ncols 4\nnrows 2\nxllcorner 10\nyllcorner 20\ncellsize 0.5\nNODATA_value -9999\n1 2 3 4\n5 6 7 8\n");
    const Dem d = read_dem(p);
    EXPECT_DOUBLE_EQ(d.grid.x0, 10.25);
    EXPECT_DOUBLE_EQ(d.grid.y0, 20.25);
    EXPECT_EQ(d.z[d.grid.index(0, 0)], 5.0);  // southern row first
    EXPECT_EQ(d.z[d.grid.index(3, 1)], 4.0);
    const Scene same = import_scene({p, "", 0.5});
    EXPECT_EQ(same.z, d.z);
    EXPECT_TRUE(same.points.empty());  // not the Kainan extent: no default features
    EXPECT_TRUE(same.manning_n.empty());
    const Scene coarse = import_scene({p, "", 1.0});
    ASSERT_EQ(coarse.grid.nx, 2);
    ASSERT_EQ(coarse.grid.ny, 1);
    EXPECT_DOUBLE_EQ(coarse.z[0], (1 + 2 + 5 + 6) / 4.0);
    EXPECT_DOUBLE_EQ(coarse.z[1], (3 + 4 + 7 + 8) / 4.0);
    const std::string c = write_file(dir, "centre.asc", "ncols 2\nnrows 1\nxllcenter 0\nyllcenter 0\ncellsize 1\n1 3\n");
    const Scene fine = import_scene({c, "", 0.5});  // refining: linear between centres
    EXPECT_EQ(fine.grid.nx, 4);
    EXPECT_DOUBLE_EQ(fine.z[1], 1.5);
}

TEST(ImportScene, BadInputsNameFileAndVariable) {
    const auto dir = test::scratch_dir("badimport");
    auto nc_dem = [&](const std::string& name, std::vector<double> x, bool with_z, double bad) {
        const std::string p = dir + "/" + name;
        nc::File f = nc::File::create(p);
        const int dx = f.def_dim("x", x.size()), dy = f.def_dim("y", 2);
        const int vx = f.def_var("x", NC_DOUBLE, {dx}), vy = f.def_var("y", NC_DOUBLE, {dy});
        const int vz = with_z ? f.def_var("z", NC_DOUBLE, {dy, dx}) : -1;
        f.enddef();
        f.put(vx, x);
        f.put(vy, std::vector<double>{0.0, 1.0});
        if (with_z) {
            std::vector<double> z(2 * x.size(), 0.0);
            z[1] = bad;
            f.put(vz, z);
        }
        f.close();
        return p;
    };
    std::string msg = error_of([&] { read_dem(nc_dem("noz.nc", {0, 1, 2}, false, 0)); });
    EXPECT_NE(msg.find("noz.nc"), std::string::npos) << msg;
    EXPECT_NE(msg.find("'z'"), std::string::npos) << msg;
    msg = error_of([&] { read_dem(nc_dem("nan.nc", {0, 1, 2}, true, std::nan(""))); });
    EXPECT_NE(msg.find("nan.nc"), std::string::npos) << msg;
    EXPECT_NE(msg.find("z"), std::string::npos) << msg;
    msg = error_of([&] { read_dem(nc_dem("uneven.nc", {0, 1, 3}, true, 0)); });
    EXPECT_NE(msg.find("uneven.nc"), std::string::npos) << msg;
    EXPECT_NE(msg.find("'x'"), std::string::npos) << msg;
    msg = error_of([&] { read_dem(write_file(dir, "nocell.asc", "ncols 2\nnrows 1\nxllcorner 0\nyllcorner 0\n1 2\n")); });
    EXPECT_NE(msg.find("nocell.asc: header 'cellsize': missing"), std::string::npos) << msg;
    msg = error_of([&] { read_dem(write_file(dir, "badhead.asc", "ncols two\nnrows 1\n")); });
    EXPECT_NE(msg.find("badhead.asc: line 1"), std::string::npos) << msg;
    msg = error_of([&] {
        read_dem(write_file(dir, "nodata.asc",
                            "ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\nnodata_value -9999\n1 2\n3 -9999\n"));
    });
    EXPECT_NE(msg.find("nodata.asc: line 8: NODATA"), std::string::npos) << msg;
    msg = error_of(
        [&] { read_dem(write_file(dir, "short.asc", "ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 2\n3\n")); });
    EXPECT_NE(msg.find("short.asc: data: expected"), std::string::npos) << msg;
}

TEST(ImportScene, FeaturesToml) {
    const auto dir = test::scratch_dir("features");
    const std::string dem =
        write_file(dir, "dem.asc", "ncols 4\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n0 0.05 0 0\n-0.02 0 0.01 0\n");
    const std::string toml = write_file(
        dir, "f.toml",
        "# test features\n[[point]]\nname = \"P\"\nkind = \"start\"\nx = 1.5\ny = 0.5\nheading = 90\n\n"
        "[[section]]\nname = \"S\"\nx = 2\ny_min = 0\ny_max = 2\n\n[[region]]\nname = \"R\"\nx = [0, 1, 1]\ny = [0, 0, 1]\n\n"
        "[[manning]]\nn = 0.03\nx_max = 2\n[[manning]]\nn = 0.01\n\n[buildings]\nmin_elevation = 0.03\n");
    const Scene s = import_scene({dem, toml, 1.0});
    ASSERT_EQ(s.points.size(), 1u);
    EXPECT_EQ(s.points[0].heading_deg, 90.0);
    ASSERT_EQ(s.sections.size(), 1u);
    ASSERT_EQ(s.regions.size(), 1u);
    EXPECT_EQ(s.regions[0].polygon.size(), 3u);
    EXPECT_EQ(s.manning_n[s.grid.index(1, 0)], 0.03);
    EXPECT_EQ(s.manning_n[s.grid.index(2, 0)], 0.01);
    EXPECT_EQ(s.building[s.grid.index(1, 1)], 1);  // 0.05 > 0.03
    EXPECT_EQ(s.building[s.grid.index(2, 0)], 0);
    std::string msg = error_of([&] {
        import_scene({dem, write_file(dir, "bad1.toml", "[[point]]\nname = \"P\"\nkind = \"start\"\nx = 1\ny = oops\n"), 1.0});
    });
    EXPECT_NE(msg.find("bad1.toml: line 5: key 'y'"), std::string::npos) << msg;
    msg = error_of([&] {
        import_scene(
            {dem, write_file(dir, "bad2.toml", "[[section]]\nname = \"S\"\nx = 1\ny_min = 0\ny_max = 1\nwidth = 3\n"), 1.0});
    });
    EXPECT_NE(msg.find("bad2.toml: line 6: unknown key 'width'"), std::string::npos) << msg;
    msg = error_of([&] { import_scene({dem, write_file(dir, "bad3.toml", "[[point]]\nname = \"P\"\nx = 1\ny = 1\n"), 1.0}); });
    EXPECT_NE(msg.find("bad3.toml: [point] at line 1: missing key 'kind'"), std::string::npos) << msg;
    msg = error_of([&] { import_scene({dem, write_file(dir, "bad4.toml", "[streets]\n"), 1.0}); });
    EXPECT_NE(msg.find("bad4.toml: line 1: unknown table"), std::string::npos) << msg;
}

TEST(SceneCli, GenerateImportAndErrors) {
    const auto dir = test::scratch_dir("scene-cli");
    std::string out;
    EXPECT_EQ(test::run_cli("scene generate --resolution 0.04 --seed 1 --out " + dir + "/g.nc", &out), 0) << out;
    EXPECT_EQ(test::run_cli("scene import --dem " + dir + "/g.nc --resolution 0.08 --out " + dir + "/i.nc", &out), 0) << out;
    EXPECT_EQ(read_scene(dir + "/i.nc").grid.nx, 255);
    EXPECT_EQ(test::run_cli("scene import --dem " + dir + "/missing.asc --out " + dir + "/x.nc", &out), 1);
    EXPECT_NE(out.find("missing.asc"), std::string::npos) << out;
    EXPECT_EQ(test::run_cli("scene generate --help", &out), 0);
    EXPECT_NE(out.find("--resolution"), std::string::npos);
    EXPECT_NE(test::run_cli("scene", &out), 0);  // a subcommand is required
}
