// `flotsam hydro`: one shallow-water run of a scene, written as a CF flow file.
#include <omp.h>
#include <signal.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <memory>
#include <optional>

#include "app/commands.hpp"
#include "app/settings_cli.hpp"
#include "common/checks.hpp"
#include "common/error.hpp"
#include "common/output_lock.hpp"
#include "data/boundary_forcing.hpp"
#include "formats/scene.hpp"
#include "hydro/run.hpp"
#include "hydro/run_settings.hpp"

namespace flotsam {

namespace {

constexpr const char* kSideNames[4] = {"west", "east", "south", "north"};

// The settings given as text (the output window, the gauges, the level mode of every
// side), resolved into the run and its physics.
void resolve_text_settings(hydro::HydroDef& o, const CLI::App* sub) {
    hydro::BoundaryDef* sides[4] = {&o.physics.west, &o.physics.east, &o.physics.south, &o.physics.north};
    for (std::size_t k = 0; k < 4; ++k)
        if (o.level_mode && sub->get_option("--" + std::string(kSideNames[k]) + "-level-mode")->count() == 0)
            sides[k]->level_mode = *o.level_mode;
    if (!o.output_window.empty())
        o.run.window = std::array<double, 4>{o.output_window[0], o.output_window[1], o.output_window[2], o.output_window[3]};
    if (!o.boundary_box.empty())
        o.run.boundary_output.box = {o.boundary_box[0], o.boundary_box[1], o.boundary_box[2], o.boundary_box[3]};
    for (const auto& g : o.gauges) {
        const auto a = g.find(','), b = g.rfind(',');
        if (a == std::string::npos || a == b) fail("", "--gauge '" + g + "'", "expected NAME,X,Y");
        try {
            o.run.gauges.push_back({g.substr(0, a), std::stod(g.substr(a + 1, b - a - 1)), std::stod(g.substr(b + 1))});
        } catch (const std::exception&) {
            fail("", "--gauge '" + g + "'", "X and Y must be numbers");
        }
        check_range("--gauge '" + g + "': x", o.run.gauges.back().x, Range::any("m"));
        check_range("--gauge '" + g + "': y", o.run.gauges.back().y, Range::any("m"));
    }
}

// A side given a forcing file is forced (and recorded so); its file is read and placed
// along the side here, where GDAL is at hand (data/boundary_forcing.hpp).
void resolve_forced_sides(hydro::HydroDef& o, const CLI::App* sub) {
    using namespace hydro;
    BoundaryDef* sides[4] = {&o.physics.west, &o.physics.east, &o.physics.south, &o.physics.north};
    std::optional<Scene> scene;
    for (std::size_t k = 0; k < 4; ++k) {
        const std::string side = kSideNames[k];
        BoundaryDef& b = *sides[k];
        if (b.forcing_file.empty()) {
            if (b.kind == BoundaryKind::forced) fail("", "--" + side + " forced", "needs --" + side + "-forcing FILE");
            continue;
        }
        if (sub->get_option("--" + side)->count() > 0 && b.kind != BoundaryKind::forced)
            fail("", "--" + side + "-forcing",
                 "forces the " + side + " side, which --" + side + " makes '" + std::string(enum_name(b.kind)) + "'");
        b.kind = BoundaryKind::forced;
        b.forcing_time = o.forcing_time;
        if (!scene) scene = read_scene(o.run.scene_file);
        // The file is checked for what this run needs of it: levels near the scene's, its
        // times over the whole run (data/boundary_forcing.hpp).
        const data::ForcingNeeds needs{*std::min_element(scene->z.begin(), scene->z.end()), 0.0, o.run.duration,
                                       "--" + side + "-forcing"};
        b.record = std::make_shared<const SideRecord>(data::read_side_forcing(b.forcing_file, side, scene->grid, scene->crs, needs));
    }
    if (o.boundary_box.empty() != o.run.boundary_output.file.empty())
        fail("", o.boundary_box.empty() ? "--boundary-output" : "--boundary-box",
             "goes with " +
                 std::string(o.boundary_box.empty() ? "--boundary-box x_min,x_max,y_min,y_max" : "--boundary-output FILE"));
}

void run_command(hydro::HydroDef& o, CLI::App* sub, const std::string& command_line) {
    using namespace hydro;
    if (const std::string applied = apply_scene_hydro_defaults(sub, o.run.scene_file); !applied.empty() && !o.run.quiet)
        std::fprintf(stderr, "hydro: the scene's recommended settings: %s\n", applied.c_str());
    PhysicsDef& s = o.physics;
    resolve_text_settings(o, sub);
    resolve_forced_sides(o, sub);
    // More threads than processors only slow a run down, and thousands cannot be started.
    if (const int threads = capped_threads(o.threads > 0 ? o.threads : omp_get_max_threads(), "--threads", o.run.quiet);
        o.threads > 0 || threads != omp_get_max_threads())
        omp_set_num_threads(threads);
    o.run.command_line = command_line;
    // The settings that define the result, from the table: given back with --config they
    // reproduce the run.
    std::vector<std::string> control;
    for (const auto& d : hydro_run_control_options()) control.push_back(d.name);
    o.run.config_text = settings_toml(hydro_settings(), o, control);
    // SIGTERM (a batch system's notice before it kills the job, Slurm's at its time limit
    // or on preemption), SIGINT (Ctrl-C) and SIGHUP (the terminal gone) stop the run at
    // its next frame with a checkpoint there, or at once when that frame is more than a
    // second away (hydro/run.hpp). A second one kills at once (SA_RESETHAND).
    // Set before the output's lock is taken: a signal sent to the lock's holder is caught.
    struct sigaction stop{};
    stop.sa_handler = [](int sig) { request_stop(sig); };
    stop.sa_flags = SA_RESETHAND;
    sigemptyset(&stop.sa_mask);
    for (int sig : {SIGTERM, SIGINT, SIGHUP}) sigaction(sig, &stop, nullptr);
    // One writer per output, and no output over an input (common/output_lock.hpp).
    std::vector<NamedPath> outputs{{"--out", o.run.out_file}, {"--out (its checkpoint)", checkpoint_path(o.run.out_file)}};
    if (!o.run.boundary_output.file.empty()) outputs.push_back({"--boundary-output", o.run.boundary_output.file});
    std::vector<NamedPath> inputs{{"--scene", o.run.scene_file}};
    const BoundaryDef* sides[4] = {&s.west, &s.east, &s.south, &s.north};
    for (std::size_t k = 0; k < 4; ++k) {
        inputs.push_back({"--" + std::string(kSideNames[k]) + "-series", sides[k]->series_file});
        inputs.push_back({"--" + std::string(kSideNames[k]) + "-forcing", sides[k]->forcing_file});
    }
    const OutputGuard guard(outputs, inputs);
    const RunResult r = run_hydro(o.run, s);
    const std::string stop_name = r.stop_signal != 0 ? std::string("SIG") + sigabbrev_np(r.stop_signal) : "";
    // Every run that stepped says what it cost, an interrupted one too: the parts of a flow
    // continued with --restart, their spans chained from t = 0, add up to its whole cost
    // (pipelines/resolution_cost.py sums them from a make log).
    if (!o.run.quiet) {
        const std::string status = r.completed            ? "complete"
                                   : r.stop_signal != 0 ? "interrupted (" + stop_name + ")"
                                                        : "stopped (checkpoint written; continue with --restart)";
        std::fprintf(stderr,
                     "%s: %s after %ld steps (t = %s to %s s) in %.1f s wall (%.1f s processor), %.3g cell-updates/s "
                     "(%.0f%% dry land skipped), volume %.6g -> %.6g m^3%s%s%s\n",
                     o.run.label.c_str(), status.c_str(), r.steps, number_text(r.started).c_str(), number_text(r.simulated).c_str(),
                     r.wall_seconds, r.cpu_seconds, r.cell_updates_per_second, 100.0 * r.dry_skipped_fraction, r.volume_start,
                     r.volume_end, r.negative_depth_fixes ? ", negative depths clamped" : "",
                     r.outflow_limits ? (", outflow limited in " + std::to_string(r.outflow_limits) + " cell-steps").c_str() : "",
                     r.positivity_redos
                         ? (", " + std::to_string(r.positivity_redos) + " steps redone at cfl 0.45 for positive depths").c_str()
                         : "");
    }
    if (r.stop_signal != 0 && r.checkpoint_time >= 0.0)
        fail(o.run.out_file, "",
             "interrupted (" + stop_name + ") at t = " + number_text(r.simulated) + " s; the run up to t = " +
                 number_text(r.checkpoint_time) + " s is kept in " + checkpoint_path(o.run.out_file) + " and " + o.run.out_file +
                 ".part: continue it with the same command and --restart");
    if (r.stop_signal != 0)
        fail(o.run.out_file, "",
             "interrupted (" + stop_name + ") at t = " + number_text(r.simulated) +
                 " s, before its first checkpoint (--checkpoint-interval); its frames so far are in " + o.run.out_file +
                 ".part, and the run starts afresh when given again");
}

}  // namespace

void register_hydro_commands(CLI::App& app, const std::string& command_line) {
    auto o = std::make_shared<hydro::HydroDef>();
    CLI::App* sub = app.add_subcommand("hydro", "Run the shallow-water solver on a scene and write a CF NetCDF flow file");
    add_config_option(sub);
    add_setting_options(sub, hydro::hydro_settings(), *o);
    sub->callback([o, sub, command_line] { run_command(*o, sub, command_line); });
}

}  // namespace flotsam
