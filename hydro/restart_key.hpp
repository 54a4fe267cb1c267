// The restart key of a hydro run: what decides its result, and nothing else.
//
// A checkpoint may be continued only by a run whose key is the same. The key is the
// run's result-defining settings (RunDef::config_text, one `name=value` per line: the
// physics, numerics, boundaries, frames and gauges), with the scene and boundary-series
// *paths* replaced by the SHA-256 of their bytes (a moved or renamed file with the same
// bytes restarts; an edited one does not). Run control — --restart, --threads, --quiet,
// --label, --out, --stop-after, --checkpoint-interval, the command line — is not in it:
// the CLI leaves those out of config_text (app/hydro_cli.cpp, hydro_run_control_options).
#pragma once
#include <string>

#include "hydro/physics.hpp"

namespace flotsam::hydro {

struct RunDef;

// One "name = value" per line, sorted by name.
std::string restart_key(const RunDef& run, const PhysicsDef& solver);

// "cfl: 0.8 in the checkpoint, 0.4 now; scene sha256: ... " — the settings whose values
// differ between two keys (empty when the keys are equal).
std::string differing_settings(const std::string& checkpoint_key, const std::string& current_key);

}  // namespace flotsam::hydro
