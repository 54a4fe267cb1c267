// Registration of the subcommands. Each stage owns its command-line surface in its own
// folder (hydro/cli.cpp, data/cli.cpp, debris/cli.cpp, pipelines/cli.cpp); the callbacks
// run the work and throw flotsam::Error on bad input.
#pragma once
#include <CLI/CLI.hpp>

#include <string>

namespace flotsam {

// The command line as typed, for the `history` attribute of outputs.
std::string join_command_line(int argc, char** argv);

// Adds --config FILE (TOML, keys are the long option names, unknown keys rejected) to a
// subcommand.
void add_config_option(CLI::App* sub);

void register_hydro_commands(CLI::App& app, const std::string& command_line);     // hydro/cli.cpp
void register_data_commands(CLI::App& app, const std::string& command_line);      // data/cli.cpp: scene, boundary
void register_debris_commands(CLI::App& app, const std::string& command_line);    // debris/cli.cpp: debris
void register_pipeline_commands(CLI::App& app, const std::string& command_line);  // pipelines/cli.cpp: sweep, stats

}  // namespace flotsam
