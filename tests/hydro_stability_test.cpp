// Stability limits of the hydro schemes, pinned: each test shows the chosen method
// holding where the other fails (the map over all step sizes: bench/hydro_stability.cpp,
// docs/hydro.md).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "cases/hydro_cases.hpp"
#include "hydro/leapfrog.hpp"
#include "hydro/solver.hpp"
#include "tests/test_support.hpp"

using namespace flotsam;
using namespace flotsam::hydro;

namespace {

PhysicsDef study_def(double manning_n) {
    PhysicsDef d = test::closed_def();
    d.default_manning_n = manning_n;
    d.study_past_stability_limit = true;
    return d;
}

test::Watch leapfrog_run(const Scene& s, PhysicsDef d, double courant, double t_end) {
    LeapfrogDef lf = default_leapfrog_def();
    lf.courant = courant;
    LeapfrogSolver solver(s, d, lf);
    return test::run_watched(solver, s, t_end);
}

// Heun's stepping, the one the explicit friction of the study is written for.
test::Watch fv_run(const Scene& s, PhysicsDef d, double cfl, double t_end, Friction friction = Friction::implicit) {
    FiniteVolumeDef fv;
    fv.stepping = TimeStepping::heun;
    fv.cfl = cfl;
    fv.friction = friction;
    Solver solver(s, d, fv);
    return test::run_watched(solver, s, t_end);
}

}  // namespace

// The 2-D staggered leap-frog is stable for c dt sqrt(1/dx^2 + 1/dy^2) <= 1 (linear, at
// rest). Measured on a 1 cm wave in a 0.5 m deep basin: holds at 1.00, blows up at 1.02.
TEST(CourantLimit, LeapfrogHoldsUpToOneAndBlowsUpAbove) {
    const Scene s = test::basin_wave(40);
    const test::Watch at_limit = leapfrog_run(s, study_def(0.0), 1.0, 1.5);
    const test::Watch above = leapfrog_run(s, study_def(0.0), 1.05, 1.5);
    std::printf("leap-frog wave: Courant 1.00 level rise %.2e m; 1.05: %.3f m after %ld steps\n", at_limit.level_rise,
                above.level_rise, above.steps);
    EXPECT_FALSE(at_limit.blew_up());
    EXPECT_EQ(at_limit.level_rise, 0.0);  // the hump only spreads
    EXPECT_TRUE(above.blew_up());
    EXPECT_GT(above.level_rise, 0.01);  // grid-scale growth, not the wave
    // Outside the study the setting is refused, and a run whose flow outgrows the step stops.
    PhysicsDef guarded = study_def(0.0);
    guarded.study_past_stability_limit = false;
    LeapfrogDef lf = default_leapfrog_def();
    lf.courant = 1.05;
    EXPECT_NE(test::error_of([&] { LeapfrogSolver(s, guarded, lf); }).find("--courant: must be at most 1"), std::string::npos);
}

// Finite volumes, both steppings: the default cfl 0.8 holds (the split step against each
// direction's own rate, Heun's against their sum; above 0.5 a step that would make a
// depth negative is redone); past the linear limit (1.0) the wave grows: the level passes
// 10 cm above the 1 cm wave within 1.5 s (Heun's also dries cells and has its depths
// clamped).
TEST(CourantLimit, FiniteVolumesHoldAtTheDefaultAndFailAbove) {
    const Scene s = test::basin_wave(40);
    PhysicsDef d = study_def(0.0);
    for (TimeStepping stepping : {TimeStepping::split, TimeStepping::heun}) {
        const char* name = stepping == TimeStepping::split ? "split" : "heun";
        FiniteVolumeDef fv;
        fv.stepping = stepping;
        Solver at_default(s, d, fv);
        const test::Watch held = test::run_watched(at_default, s, 1.5);
        fv.cfl = 1.2;
        Solver over(s, d, fv);
        const test::Watch failed = test::run_watched(over, s, 1.5, 0.1);  // until the level has risen 10 cm
        std::printf("finite volumes wave (%s): cfl 0.8 level rise %.2e m; cfl 1.2: %.3f m, %ld depths clamped (worst %.2e m)\n",
                    name, held.level_rise, failed.level_rise, over.stats().negative_depth_fixes, over.stats().min_depth_seen);
        EXPECT_FALSE(held.blew_up()) << name;
        EXPECT_EQ(held.level_rise, 0.0) << name;
        EXPECT_TRUE(failed.blew_up()) << name;
    }
    FiniteVolumeDef fv;
    fv.cfl = 1.2;
    d.study_past_stability_limit = false;
    EXPECT_NE(test::error_of([&] { Solver(s, d, fv); }).find("--cfl: must be in (0, 1]"), std::string::npos);
}

// Manning friction in a 0.1 mm film draining down a 1:10 slope: the implicit treatment
// (finite volumes) and the semi-implicit one (leap-frog) never reverse the film; the
// explicit one reverses it at cfl 0.2 and blows up at the default 0.45, where
// dt g n^2 |u| / h^(4/3) >> 1.
TEST(Friction, ImplicitHoldsInThinFilmsWhereExplicitFails) {
    const Scene s = test::film_on_slope();
    PhysicsDef d = study_def(0.025);
    d.max_dt = 1.0;  // the step follows the cfl
    const test::Watch implicit = fv_run(s, d, 0.45, 20.0);
    const test::Watch explicit_small = fv_run(s, d, 0.2, 20.0, Friction::explicit_);
    const test::Watch explicit_default = fv_run(s, d, 0.45, 20.0, Friction::explicit_);
    const test::Watch leapfrog = leapfrog_run(s, d, 0.1, 20.0);
    std::printf(
        "thin film: implicit max speed %.3f m/s, %ld reversals; explicit at 0.2: %ld reversals; at 0.45: speed %.3g m/s after %ld "
        "steps; leap-frog: %ld reversals\n",
        implicit.max_speed, implicit.reversals, explicit_small.reversals, explicit_default.max_speed, explicit_default.steps,
        leapfrog.reversals);
    EXPECT_FALSE(implicit.blew_up());
    EXPECT_EQ(implicit.reversals, 0);
    EXPECT_LT(implicit.max_speed, 0.05);  // normal flow of a 0.1 mm film: ~0.03 m/s
    EXPECT_GT(explicit_small.reversals, 0);
    EXPECT_TRUE(explicit_default.blew_up());
    EXPECT_FALSE(leapfrog.blew_up());
    EXPECT_EQ(leapfrog.reversals, 0);
}

// A 3 cm bore over a 1 mm film into a block of 4 and 5 cm buildings, both schemes at
// their defaults: depth never negative, mass conserved, roofs dry, no level above the
// bore's. The leap-frog's one failure: with a step 0.9 of its limit at rest, the bore's
// speed takes its Courant number past 1 and levels overshoot by centimetres; its check
// stops such a run.
TEST(WetDryFronts, BoreIntoBuildingsHoldsInBothSchemes) {
    const Scene s = test::bore_into_buildings();
    PhysicsDef d = test::closed_def();
    d.default_manning_n = 0.013;
    Solver fv(s, d);
    const test::Watch f = test::run_watched(fv, s, 2.0);
    LeapfrogSolver lf(s, d, default_leapfrog_def());
    const test::Watch l = test::run_watched(lf, s, 2.0);
    std::printf(
        "bore into buildings: fv min depth %.1e, volume error %.1e, roof %.1e; leap-frog min depth %.1e, volume error %.1e, roof "
        "%.1e, outflow limits %ld, max Courant %.2f\n",
        f.min_depth, f.volume_error, f.roof_depth, l.min_depth, l.volume_error, l.roof_depth, lf.stats().outflow_limits,
        lf.max_courant_seen());
    for (const test::Watch* w : {&f, &l}) {
        EXPECT_FALSE(w->blew_up());
        EXPECT_GE(w->min_depth, 0.0);
        EXPECT_LT(std::abs(w->volume_error), 1e-12);
        EXPECT_EQ(w->roof_depth, 0.0);
        EXPECT_EQ(w->level_rise, 0.0);
    }
    EXPECT_EQ(fv.stats().negative_depth_fixes, 0);
    EXPECT_EQ(lf.stats().negative_depth_fixes, 0);
    // Past its limit in the flow: overshoot when studied, a clear stop otherwise.
    const test::Watch over = leapfrog_run(s, study_def(0.013), 0.9, 2.0);
    EXPECT_GT(over.level_rise, 0.01);
    LeapfrogDef near = default_leapfrog_def();
    near.courant = 0.9;
    LeapfrogSolver checked(s, d, near);
    const std::string msg = test::error_of([&] { test::run_watched(checked, s, 2.0); });
    EXPECT_NE(msg.find("--courant: the leap-frog step"), std::string::npos) << msg;
}

namespace {

// Two jets of water 2 mm deep, 0.19 m long, meeting head-on at 2 m/s on dry flat ground
// (1 cm cells, 8 rows, walls, no friction), stepped for 2 s at `cfl`. `raw`: without the
// positivity redo (the study switch). Returns the clamped depths; `redos` and the
// volume error [m^3] through the references.
long colliding_jets(double cfl, bool raw, long& redos, double& volume_error) {
    Scene s;
    s.grid = Grid{100, 8, 0.005, 0.005, 0.01, 0.01};
    s.z.assign(s.grid.size(), 0.0);
    s.eta0.assign(s.grid.size(), 0.0);
    s.u0.assign(s.grid.size(), 0.0);
    s.v0.assign(s.grid.size(), 0.0);
    for (int j = 0; j < 8; ++j)
        for (int i = 41; i < 60; ++i) {
            s.eta0[s.grid.index(i, j)] = 0.002;
            s.u0[s.grid.index(i, j)] = i < 50 ? 2.0 : -2.0;
        }
    PhysicsDef d = test::closed_def();
    d.study_past_stability_limit = raw;
    FiniteVolumeDef fv;
    fv.cfl = cfl;
    Solver solver(s, d, fv);
    const double v0 = solver.volume();
    while (solver.time() < 2.0) solver.step(std::min(solver.stable_dt(), 2.0 - solver.time()));
    volume_error = solver.volume() - v0;
    redos = solver.stats().positivity_redos;
    return solver.stats().negative_depth_fixes;
}

}  // namespace

// Above cfl 0.5 a Heun step can drive a depth negative where thin water collides; the
// clamp then creates water. The checked step redoes such a step at cfl 0.45, so no depth
// is clamped and the volume (3.04e-5 m^3) holds to round-off; without the redo the same
// run clamps and gains volume.
TEST(PositivityRedo, StepsAboveTheBoundAreRedoneWhereADepthWouldGoNegative) {
    long redos = 0;
    double error = 0.0;
    const long raw = colliding_jets(0.95, true, redos, error);
    std::printf("cfl 0.95 without the redo: %ld clamped depths, volume error %.3g m^3\n", raw, error);
    EXPECT_GT(raw, 10);
    EXPECT_GT(error, 1e-8);
    const long checked = colliding_jets(0.95, false, redos, error);
    std::printf("cfl 0.95 with the redo: %ld clamped depths, %ld steps redone, volume error %.3g m^3\n", checked, redos, error);
    EXPECT_EQ(checked, 0);
    EXPECT_GT(redos, 0);
    EXPECT_LT(std::abs(error), 1e-15);
    EXPECT_EQ(colliding_jets(0.45, false, redos, error), 0);  // within the bound nothing is redone
    EXPECT_EQ(redos, 0);
}
