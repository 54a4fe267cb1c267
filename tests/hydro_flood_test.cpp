// The generated scene floods like the paper's city: when the water rises more than 1 cm
// the low land by the shore floods, and roofs 5 cm above the water stay dry.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>

#include "common/netcdf.hpp"
#include "data/scene_generator.hpp"
#include "hydro/run.hpp"
#include "tests/test_support.hpp"

using namespace flotsam;

TEST(GeneratedSceneFlood, ShoreFloodsRoofsStayDry) {
    const auto dir = test::scratch_dir("flood");
    // The city end of the generated scene at 4 cm, from x = -1 m (0.13 m deep) eastward:
    // the deep flume only delays the wave and costs time steps.
    SceneGenDef gd;
    gd.resolution = 0.04;
    const Scene full = generate_scene(gd).scene;
    const int i0 = full.grid.cell_i(-1.0);
    Scene s = full;
    s.grid.nx = full.grid.nx - i0;
    s.grid.x0 = full.grid.x(i0);
    s.z.clear();
    s.manning_n.clear();
    s.building.clear();
    for (int j = 0; j < full.grid.ny; ++j)
        for (int i = i0; i < full.grid.nx; ++i) {
            const std::size_t k = full.grid.index(i, j);
            s.z.push_back(full.z[k]);
            s.manning_n.push_back(full.manning_n[k]);
            s.building.push_back(full.building[k]);
        }
    s.points.clear();
    write_scene(dir + "/scene.nc", s, "test");
    {
        std::ofstream f(dir + "/level.csv");
        f << "time,eta\n";  // rises to 3.5 cm in 60 s: above the 1 cm shore, below 5 cm roofs
        for (int t = 0; t <= 120; t += 5) f << t << "," << 0.035 * std::min(1.0, t / 60.0) << "\n";
    }
    hydro::PhysicsDef sd = hydro::default_physics_def();
    sd.west.series_file = dir + "/level.csv";
    sd.west.level_mode = hydro::LevelMode::total;
    hydro::RunDef rd;
    rd.scene_file = dir + "/scene.nc";
    rd.out_file = dir + "/flow.nc";
    rd.duration = 90.0;
    rd.output_interval = 90.0;
    rd.quiet = true;
    ASSERT_TRUE(hydro::run_hydro(rd, sd).completed);

    const nc::File f = nc::File::open_read(rd.out_file);
    const auto maxd = f.get_float(f.var("max_depth"));
    long shore = 0, shore_wet = 0, roofs = 0, roofs_wet = 0;
    for (int j = 0; j < s.grid.ny; ++j)
        for (int i = 0; i < s.grid.nx; ++i) {
            const std::size_t k = s.grid.index(i, j);
            const double x = s.grid.x(i);
            // Low open land (ground 0.5-1.5 cm above still water) in the port area.
            if (!s.building[k] && s.z[k] > 0.005 && s.z[k] < 0.015 && x > 0.5 && x < 4.0) {
                ++shore;
                shore_wet += maxd[k] > 0.005f;
            }
            if (s.building[k] && s.z[k] > 0.045) {
                ++roofs;
                roofs_wet += maxd[k] > 0.0f;
            }
        }
    std::printf("low shore cells wetted by > 5 mm: %ld of %ld; roofs wetted: %ld of %ld\n", shore_wet, shore, roofs_wet, roofs);
    ASSERT_GT(shore, 50);
    ASSERT_GT(roofs, 500);
    EXPECT_GT(double(shore_wet) / double(shore), 0.8);
    EXPECT_EQ(roofs_wet, 0);
}
