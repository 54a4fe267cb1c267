// Stability maps pinned: each test shows the chosen method holding where the other one
// fails (docs/debris.md, "Stability maps"; the full maps: build/debris_stability).
#include <gtest/gtest.h>

#include <cmath>

#include "cases/debris_stability_cases.hpp"
#include "tests/test_support.hpp"

using namespace flotsam;
using namespace flotsam::debris;

// Added mass ρ C_a V_s (= C_a m afloat) on the right-hand side with last step's
// acceleration multiplies an error in the acceleration by −C_a each step: it decays for
// Cm < 2, is neutral at Cm = 2 and grows for Cm > 2 (the paper's 1.5 × 2 = 3 among
// them). On the left-hand side (implicit) the same body follows the analytic relaxation
// at every Cm. Map: Cm 1.5, 2, 2.5, 3, 4 × {explicit, implicit}.
TEST(DebrisStability, ExplicitAddedMassFailsAboveCm2WhereImplicitHolds) {
    const auto dir = test::scratch_dir("stab_added_mass");
    const auto flow = test::added_mass_flow(dir);
    const double U = test::added_mass_current;
    for (double cm : {1.5, 2.0, 2.5, 3.0, 4.0}) {
        const auto imp = test::added_mass_velocities(flow, cm, AddedMass::implicit, 200);
        const auto exp = test::added_mass_velocities(flow, cm, AddedMass::explicit_, 200);
        EXPECT_NEAR(imp.back(), test::relaxation_velocity(cm, 2.0), 0.002 * U) << "implicit, Cm " << cm;
        const double growth = test::explicit_growth_per_step(exp, imp, 1, 4);
        EXPECT_NEAR(growth, cm - 1.0, 0.05 * (cm - 1.0)) << "Cm " << cm;  // the −C_a factor
        if (cm < 2.0) {
            EXPECT_NEAR(exp.back(), imp.back(), 0.01 * U) << "explicit, Cm " << cm;  // stable, and close
        }
        if (cm == 2.0) {
            EXPECT_LT(std::fabs(exp.back()), 2.0 * U);  // neutral: bounded, but the oscillation is never damped
        }
        if (cm > 2.0) {
            EXPECT_TRUE(!std::isfinite(exp.back()) || std::fabs(exp.back()) > 1e3 * U) << "Cm " << cm << ": " << exp.back();
        }
    }
}

// A body at 3 m/s against a wall one cell thick, eight start phases per case. At the
// default vertex_step_fraction 0.25 (and up to 1: a corner moves at most a cell per
// step) nothing goes through, on 1 cm and on 4 cm cells. Broadside (heading 90, moving
// across its 10 cm width) the first runs go through at 10 cm steps (1 cm cells) and 8 cm
// (4 cm cells): a step longer than about its width carries it past the wall before any
// contact is seen, and at the longest steps mapped (24 cm on 1 cm cells, 28 cm on 4 cm
// cells) 6 or 7 of the 8 do. End-on and at 20 degrees most are held: no move out carries
// a corner further than the margin in one pass, so what the step put deep in the wall is
// not pushed out through its far side; the jam rule puts the body back.
TEST(DebrisStability, StepLimitKeepsBodyOutOfOneCellWallWhereLongStepsTunnel) {
    const auto dir = test::scratch_dir("stab_tunnel");
    for (double cell : {0.01, 0.04}) {
        const auto flow = test::wall_flow(dir, cell);
        for (double heading : {0.0, 20.0, 90.0}) {
            for (double f : {0.25, 1.0})
                EXPECT_EQ(test::wall_tunnelling_count(flow, cell, heading, f, 8), 0)
                    << cell << " m cells, heading " << heading << ", f " << f;
            const double longest = cell < 0.02 ? 0.24 : 0.28;  // [m]
            if (heading == 90.0) {
                EXPECT_GE(test::wall_tunnelling_count(flow, cell, heading, longest / cell, 8), 6) << cell << " m cells";
            }
        }
    }
}
