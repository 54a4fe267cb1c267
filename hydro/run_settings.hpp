// The settings of `flotsam hydro`, one definition each (common/settings.hpp): what the
// run reads, stores and computes (RunDef), the scheme and its step (FiniteVolumeDef,
// LeapfrogDef), the nesting (NestDef), the physics and the four sides (PhysicsDef). The
// command line, `--config` files and the `flotsam_config` a flow file records (which
// given back with --config reproduces the flow) all come from this one table.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "common/settings.hpp"
#include "hydro/run.hpp"

namespace flotsam::hydro {

// Everything `flotsam hydro` sets: the run and its physics, and the settings given as
// text that the command resolves into them.
struct HydroDef {
    RunDef run;
    PhysicsDef physics = default_physics_def();
    std::vector<double> output_window;    // x_min, x_max, y_min, y_max [m]: run.window when given
    std::vector<std::string> gauges;      // NAME,X,Y [-, m, m]: added to run.gauges
    std::optional<LevelMode> level_mode;  // every side's, where the side's own is not given
    std::vector<double> boundary_box;     // x_min, x_max, y_min, y_max [m]: run.boundary_output.box when given
    ForcingTime forcing_time = ForcingTime::linear;  // how every forced side reads its file in time
    int threads = 0;                      // OpenMP threads; 0: OMP_NUM_THREADS or all cores
};

// The --help section of the options kept for the studies and tests that compare the
// default with what it replaced (docs/studies/).
inline const std::string study_group = "Study options (comparisons with the default; docs/studies/)";

// In the order of --help and of `flotsam_config`.
const Settings<HydroDef>& hydro_settings();

}  // namespace flotsam::hydro
