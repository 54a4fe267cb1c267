// Registration of the subcommands. Each stage's command-line surface is a file of its own
// here (hydro_cli.cpp, data_cli.cpp, debris_cli.cpp, sweep_cli.cpp); the callbacks
// run the work and throw flotsam::Error on bad input.
#pragma once
#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "common/checks.hpp"

namespace flotsam {

// A CLI11 check that an option's value is a finite number in `r` (common/checks.hpp):
// "--cfl: nan is not a finite number (allowed: (0, 1])". Values from a settings file go
// through the same check, with the file and key named (expand_config_files).
CLI::Validator in_range(const Range& r);

// An option left out of a recorded command line: its name without "--", and whether it
// takes a value.
struct DroppedOption {
    std::string name;
    bool takes_value = true;
};

// The command line as typed, for the `history` attribute of outputs, without the
// options in `drop` (and their values).
std::string join_command_line(int argc, char** argv, const std::vector<DroppedOption>& drop = {});

// hydro's run-control options: how a run goes (restart, threads, progress, where the
// output goes, when to stop and checkpoint), not what it computes. They are left out of
// the restart key, of `flotsam_config` and of `history`, so a run that was stopped and
// restarted, or run on another thread count, writes the same bytes.
const std::vector<DroppedOption>& hydro_run_control_options();

// Adds --config FILE (TOML, keys are the long option names, unknown keys rejected) to a
// subcommand.
void add_config_option(CLI::App* sub);

// The arguments (without argv[0]) with a subcommand's --config FILE replaced by the
// settings it holds; options given on the command line win over the file. Throws
// flotsam::Error naming the file and key for an unknown setting, a section that is no
// command ([hydor]), a key given twice, an array for a one-value setting, or a value
// that fails the option's check.
std::vector<std::string> expand_config_files(CLI::App& app, int argc, char** argv);

// Sets the hydro options that the scene recommends (its flotsam_hydro_defaults: settings
// tuned to its scale, written by `scene import` from a features file's [hydro] table)
// and that the command line and --config leave out. Returns what it set, for the log.
std::string apply_scene_hydro_defaults(CLI::App* sub, const std::string& scene_path);

void register_hydro_commands(CLI::App& app, const std::string& command_line);     // app/hydro_cli.cpp
void register_data_commands(CLI::App& app, const std::string& command_line);      // app/data_cli.cpp: scene, boundary
void register_debris_commands(CLI::App& app, const std::string& command_line);    // app/debris_cli.cpp: debris
void register_pipeline_commands(CLI::App& app, const std::string& command_line);  // app/sweep_cli.cpp: sweep, stats
void register_export_commands(CLI::App& app);                                     // app/export_cli.cpp: export

}  // namespace flotsam
