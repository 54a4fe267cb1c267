// flotsam: one executable, one subcommand per pipeline step. Each stage registers its
// own subcommands (see the register_* functions); settings come from the command line
// or from a TOML file given with --config, where unknown keys are an error.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <new>

#include "app/commands.hpp"
#include "common/checks.hpp"
#include "common/error.hpp"
#include "common/version.hpp"

// After an error, the outputs are already closed or removed (the stack has unwound), but
// libhdf5 may still hold a file whose close failed (a full disk): its exit handler would
// then flush it again and crash (rc 139 after "close: NetCDF: HDF error"). Leave without
// running exit handlers.
[[noreturn]] void exit_after_error(int code) {
    std::fflush(stdout);
    std::fflush(stderr);
    std::_Exit(code);
}

int main(int argc, char** argv) {
    CLI::App app{
        "flotsam: tsunami debris transport in a port city (shallow-water flows, then rigid-body debris replayed through them)"};
    app.set_version_flag("--version", flotsam::version_string());
    app.require_subcommand(1);
    const std::string command_line = flotsam::join_command_line(argc, argv);
    flotsam::register_hydro_commands(app, flotsam::join_command_line(argc, argv, flotsam::hydro_run_control_options()));
    flotsam::register_data_commands(app, command_line);
    flotsam::register_debris_commands(app, command_line);
    flotsam::register_pipeline_commands(app, command_line);
    flotsam::register_export_commands(app);
    try {
        std::vector<std::string> args = flotsam::expand_config_files(app, argc, argv);
        std::reverse(args.begin(), args.end());  // CLI11 takes the vector last-first
        app.parse(args);
    } catch (const CLI::ParseError& e) {
        return app.exit(e);
    } catch (const flotsam::Error& e) {
        std::fprintf(stderr, "flotsam: error: %s\n", e.what());
        exit_after_error(1);
    } catch (const std::bad_alloc&) {
        // The inputs and options that size a run are checked before it allocates
        // (docs/reliability.md); what is left is the machine's memory itself.
        std::fprintf(stderr, "flotsam: error: out of memory (%.3g GB this process may use): the inputs or options ask for more\n",
                     flotsam::memory_limit_bytes() / 1e9);
        exit_after_error(1);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "flotsam: internal error: %s\n", e.what());
        exit_after_error(2);
    }
    return 0;
}
