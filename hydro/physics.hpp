// What every scheme of stage one reads (finite volumes, solver.hpp; leap-frog,
// leapfrog.hpp): the physics of the equations (docs/hydro.md), what drives the four
// sides, the limits on the step that both schemes honour, and the counters a run
// reports. The settings that only one scheme has are in its own definition
// (FiniteVolumeDef, LeapfrogDef).
#pragma once
#include <variant>
#include <vector>

#include "hydro/boundary.hpp"

namespace flotsam::hydro {

struct PhysicsDef {
    double gravity = 9.81;  // [m s^-2]
    // The one dry tolerance: below it velocities are desingularised (swe_kernels.hpp,
    // inverse_depth) and the reconstruction is first order; the leap-frog's faces do not
    // open (and the tracked fronts start a tip only where the water stands this far above
    // a dry cell). 1e-6 m, a thousandth of a millimetre, for scenes whose water is
    // centimetres to a metre deep: thinner films, left on the ground a receding shore
    // gave up, otherwise race down slopes at many times the flow's speed and set the step
    // (Thacker's bowl: docs/studies/wetdry_suite.md), and no depth a user reads is
    // near it. Scale it with the scene (a scene at 250 times the size: 2.5e-4 m).
    double dry_depth = 1e-6;           // [m]
    double default_manning_n = 0.013;  // [s m^-1/3] where the scene has no manning_n
    BoundaryDef west, east, south, north;
    PumpDef pump;  // the west side's, when it is a pump
    // Limits on the step, for both schemes.
    double max_dt = 0.05;  // [s] upper bound on the step
    // Study only, never for a real run: accept cfl above 1 (finite volumes) and run steps
    // above 0.5 without the positivity redo, and let the leap-frog run on past its Courant
    // limit instead of failing, to show the failures.
    bool study_past_stability_limit = false;
};
// West: a level series; east: transmissive; south and north: walls.
PhysicsDef default_physics_def();

// Counters that say how the run went.
struct SolverStats {
    long steps = 0;
    long negative_depth_fixes = 0;  // cells where round-off made h < 0 (set to 0)
    double min_depth_seen = 0.0;    // most negative h before the fix [m]
    double cell_stages = 0.0;       // interior cells x stages stepped
    double cell_stages_dry = 0.0;   // of which skipped as dry land (all of the stencil exactly zero)
    long outflow_limits = 0;        // leap-frog: cell-steps whose outflow was scaled down to keep h >= 0
    long positivity_redos = 0;      // finite volumes at cfl > 0.5: steps redone at cfl 0.45 (they clamped a depth)
};

// One array of a solver's exact state in the solver's own precision (checkpoints store
// each in its type, so that a restart continues from the same bits).
using StateArray = std::variant<std::vector<double>*, std::vector<float>*>;

}  // namespace flotsam::hydro
