// Debris stability maps as CSV on stdout, for docs/img/debris_stability.png (make
// -f Makefile.pipeline accuracy-debris). The cases are those of
// tests/debris_stability_test.cpp (cases/debris_stability_cases.hpp), over a finer grid
// of parameters:
//   added_mass: Cm × {explicit, implicit}: growth per step of the explicit oscillation
//               (from steps 1 to 4) and |v|/U after 2 s (the analytic relaxation for
//               the implicit scheme is about 0.1);
//   tunnelling: cell size × heading × vertex_step_fraction f (dt_max 0.1 s, so the
//               vertex limit sets the step: f cells per step at 3 m/s): of eight runs
//               started at evenly spaced phases of the step, how many went through a
//               wall one cell thick.
//
//   build/debris_stability [scratch_dir] > debris_stability.csv
#include <cstdio>
#include <filesystem>

#include "cases/debris_stability_cases.hpp"

using namespace flotsam;
using namespace flotsam::debris;

int main(int argc, char** argv) {
    const std::string dir = argc > 1 ? argv[1] : (std::filesystem::temp_directory_path() / "flotsam-debris-stability").string();
    std::filesystem::create_directories(dir);
    const std::string am_flow = test::added_mass_flow(dir);
    std::printf(
        "map,cm,method,growth_per_step,speed_ratio_2s,cell_m,heading_deg,vertex_step_fraction,step_travel_m,tunnelled_of_8\n");
    for (double cm = 1.25; cm <= 4.0 + 1e-9; cm += 0.25) {
        const auto imp = test::added_mass_velocities(am_flow, cm, AddedMass::implicit, 200);
        const auto exp = test::added_mass_velocities(am_flow, cm, AddedMass::explicit_, 200);
        const double growth = test::explicit_growth_per_step(exp, imp, 1, 4);
        std::printf("added_mass,%g,explicit,%.4f,%.4g,,,,,\n", cm, growth, std::fabs(exp.back()) / test::added_mass_current);
        std::printf("added_mass,%g,implicit,,%.4g,,,,,\n", cm, std::fabs(imp.back()) / test::added_mass_current);
    }
    for (double cell : {0.01, 0.04}) {
        const std::string wall = test::wall_flow(dir, cell);
        for (double heading : {0.0, 20.0, 90.0})
            for (double f : {0.25, 0.5, 1.0, 1.5, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 10.0, 12.0, 16.0, 20.0, 24.0}) {
                if (f * cell > 0.3) continue;  // a step longer than dt_max = 0.1 s at 3 m/s
                const int n = test::wall_tunnelling_count(wall, cell, heading, f, 8);
                std::printf("tunnelling,,,,,%g,%g,%g,%g,%d\n", cell, heading, f, f * cell, n);
            }
    }
    return 0;
}
