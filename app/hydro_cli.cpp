// `flotsam hydro`: one shallow-water run of a scene, written as a CF flow file.
#include <omp.h>
#include <signal.h>

#include <array>
#include <cstdio>
#include <memory>
#include <sstream>

#include "app/commands.hpp"
#include "common/checks.hpp"
#include "common/error.hpp"
#include "common/output_lock.hpp"
#include "data/boundary_forcing.hpp"
#include "formats/scene.hpp"
#include "hydro/run.hpp"

namespace flotsam {

namespace {

// The options kept for the studies and tests that compare the default with what it
// replaced (docs/studies/); listed apart in --help.
const char* const kStudyGroup = "Study options (comparisons with the default; docs/studies/)";

constexpr const char* kSideNames[4] = {"west", "east", "south", "north"};

struct HydroOptions {
    hydro::RunDef run;
    hydro::PhysicsDef physics = hydro::default_physics_def();
    std::vector<double> window;
    std::vector<std::string> gauges;
    std::string west = "level", east = "transmissive", south = "wall", north = "wall";
    std::array<std::string, 4> level_mode{"total", "total", "total", "total"};  // west, east, south, north
    std::array<std::string, 4> series_end{"error", "error", "error", "error"};
    std::string level_mode_all;  // --level-mode: every side at once (a side's own option wins)
    std::array<std::string, 4> forcing;  // --<side>-forcing: another run's NetCDF
    std::string forcing_time = "linear";
    std::vector<double> boundary_box;
    std::string scheme = "fv";
    std::string friction = "implicit";
    std::string fronts = "plain";
    std::string stepping = "split";
    int threads = 0;
};

// The settings dump (TOML, one name=value per line) without the run-control options.
std::string result_settings(const std::string& dump) {
    std::string out, line;
    std::istringstream in(dump);
    while (std::getline(in, line)) {
        const std::string name = line.substr(0, line.find('='));
        bool control = name == "config";
        for (const auto& d : hydro_run_control_options()) control = control || name == d.name;
        if (!control) out += line + "\n";
    }
    return out;
}

void run_command(HydroOptions& o, CLI::App* sub, const std::string& command_line) {
    using namespace hydro;
    if (const std::string applied = apply_scene_hydro_defaults(sub, o.run.scene_file); !applied.empty() && !o.run.quiet)
        std::fprintf(stderr, "hydro: the scene's recommended settings: %s\n", applied.c_str());
    PhysicsDef& s = o.physics;
    o.run.scheme = parse_enum<Scheme>(o.scheme, "--scheme");
    o.run.finite_volume.friction = parse_enum<Friction>(o.friction, "--friction");
    o.run.finite_volume.fronts = parse_enum<FrontTreatment>(o.fronts, "--fronts");
    o.run.finite_volume.stepping = parse_enum<TimeStepping>(o.stepping, "--time-stepping");
    // A side given a forcing file is forced (recorded so, for --config to reproduce it).
    for (std::size_t k = 0; k < 4; ++k) {
        if (o.forcing[k].empty()) continue;
        const std::string side = kSideNames[k];
        CLI::Option* kind = sub->get_option("--" + side);
        std::string& given = k == 0 ? o.west : k == 1 ? o.east : k == 2 ? o.south : o.north;
        if (kind->count() > 0 && given != "forced")
            fail("", "--" + side + "-forcing", "forces the " + side + " side, which --" + side + " makes '" + given + "'");
        if (kind->count() == 0) kind->add_result("forced");
        given = "forced";
    }
    s.west.kind = parse_enum<BoundaryKind>(o.west, "--west");
    s.east.kind = parse_enum<BoundaryKind>(o.east, "--east");
    s.south.kind = parse_enum<BoundaryKind>(o.south, "--south");
    s.north.kind = parse_enum<BoundaryKind>(o.north, "--north");
    BoundaryDef* sides[4] = {&s.west, &s.east, &s.south, &s.north};
    for (std::size_t k = 0; k < 4; ++k) {
        const std::string side = kSideNames[k];
        const bool own = sub->get_option("--" + side + "-level-mode")->count() > 0;
        sides[k]->level_mode = own || o.level_mode_all.empty() ? parse_enum<LevelMode>(o.level_mode[k], "--" + side + "-level-mode")
                                                               : parse_enum<LevelMode>(o.level_mode_all, "--level-mode");
        sides[k]->series_end = parse_enum<SeriesEnd>(o.series_end[k], "--" + side + "-series-end");
        if (sides[k]->kind == BoundaryKind::forced && o.forcing[k].empty())
            fail("", "--" + side + " forced", "needs --" + side + "-forcing FILE");
    }
    if (std::any_of(o.forcing.begin(), o.forcing.end(), [](const std::string& f) { return !f.empty(); })) {
        const Scene scene = read_scene(o.run.scene_file);
        for (std::size_t k = 0; k < 4; ++k)
            if (!o.forcing[k].empty()) {
                sides[k]->series_file = o.forcing[k];
                sides[k]->forcing_time = parse_enum<ForcingTime>(o.forcing_time, "--forcing-time");
                sides[k]->record = std::make_shared<const SideRecord>(
                    data::read_side_forcing(o.forcing[k], kSideNames[k], scene.grid, scene.crs));
            }
    }
    if (!o.boundary_box.empty() != !o.run.boundary_output.file.empty())
        fail("", o.boundary_box.empty() ? "--boundary-output" : "--boundary-box",
             "goes with " + std::string(o.boundary_box.empty() ? "--boundary-box x_min,x_max,y_min,y_max" : "--boundary-output FILE"));
    if (!o.boundary_box.empty())
        o.run.boundary_output.box = {o.boundary_box[0], o.boundary_box[1], o.boundary_box[2], o.boundary_box[3]};
    if (!o.window.empty()) o.run.window = std::array<double, 4>{o.window[0], o.window[1], o.window[2], o.window[3]};
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
    // More threads than processors only slow a run down, and thousands cannot be started.
    if (const int threads = capped_threads(o.threads > 0 ? o.threads : omp_get_max_threads(), "--threads", o.run.quiet);
        o.threads > 0 || threads != omp_get_max_threads())
        omp_set_num_threads(threads);
    o.run.command_line = command_line;
    o.run.config_text = result_settings(sub->config_to_str(true, false));
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
    std::vector<NamedPath> outputs{{"--out", o.run.out_file},
                                                             {"--out (its checkpoint)", checkpoint_path(o.run.out_file)}};
    if (!o.run.boundary_output.file.empty()) outputs.push_back({"--boundary-output", o.run.boundary_output.file});
    std::vector<NamedPath> inputs{{"--scene", o.run.scene_file}};
    for (std::size_t k = 0; k < 4; ++k)
        inputs.push_back({std::string("--") + kSideNames[k] + (sides[k]->kind == BoundaryKind::forced ? "-forcing" : "-series"),
                          sides[k]->series_file});
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
    auto o = std::make_shared<HydroOptions>();
    CLI::App* sub = app.add_subcommand("hydro", "Run the shallow-water solver on a scene and write a CF NetCDF flow file");
    add_config_option(sub);
    auto& r = o->run;
    auto& s = o->physics;
    auto& fv = o->run.finite_volume;
    sub->add_option("--scene", r.scene_file, "Scene NetCDF (x, y, z; optional manning_n, building, eta0/u0/v0)")
        ->required()
        ->check(CLI::ExistingFile);
    sub->add_option("--out", r.out_file, "Output flow file (.nc); written as <out>.part and renamed when complete")->required();
    sub->add_option("--duration", r.duration, "Simulated time [s]")->capture_default_str()->check(in_range(Range::positive("s")));
    sub->add_option("--output-interval", r.output_interval, "Time between stored frames [s]")
        ->capture_default_str()
        ->check(in_range(Range::positive("s")));
    sub->add_option("--output-window", o->window, "Store frames only in x_min,x_max,y_min,y_max [m]")
        ->expected(4)
        ->delimiter(',')
        ->check(in_range(Range::any("m")));
    sub->add_option("--gauge-interval", r.gauge_interval, "Time between gauge samples [s]")
        ->capture_default_str()
        ->check(in_range(Range::positive("s")));
    sub->add_option("--gauge", o->gauges, "Extra gauge NAME,X,Y (repeatable); the scene's gauge points are always recorded");
    sub->add_option("--arrival-depth", r.arrival_depth, "Depth threshold of the arrival-time map [m] (the debris draft)")
        ->capture_default_str()
        ->check(in_range(Range::positive("m")));
    sub->add_option("--flood-depth", r.flood_depth,
                    "Depth a cell must exceed to count as flooded [m]: the flooded map, the inundation line and the runup")
        ->capture_default_str()
        ->check(in_range(Range::positive("m")));
    sub->add_option("--checkpoint-interval", r.checkpoint_interval, "Simulated time between checkpoints [s]; 0: none")
        ->capture_default_str()
        ->check(in_range(Range::non_negative("s")));
    sub->add_flag("--restart", r.restart, "Continue an interrupted run from <out>.checkpoint.nc and <out>.part");
    sub->add_option("--stop-after", r.stop_after, "Stop as if interrupted once past this time [s] (leaves a checkpoint)")
        ->check(in_range(Range::non_negative("s")));
    sub->add_option("--realisation", r.realisation, "Boundary realisation id recorded in the file")
        ->capture_default_str()
        ->check(in_range(Range::count(-1, 1e9)));
    sub->add_option("--deflate", r.deflate_level, "Deflate level of stored fields, 0-9")
        ->capture_default_str()
        ->check(in_range(Range::count(0, 9)));
    sub->add_option("--label", r.label, "Progress label")->capture_default_str();
    sub->add_flag("--quiet", r.quiet, "No progress output");
    sub->add_flag("--allow-large-run", r.allow_large_run,
                  "Run even when the estimated work (cells x steps) passes the bound flotsam stops at (docs/reliability.md)");
    sub->add_option("--threads", o->threads, "OpenMP threads (0: OMP_NUM_THREADS or all cores)")
        ->capture_default_str()
        ->check(in_range(Range::count(0, 4096)));
    // Scheme.
    sub->add_option("--scheme", o->scheme,
                    "fv: finite volumes (MUSCL + HLL + Heun); leapfrog: staggered leap-frog of the classic tsunami codes")
        ->check(CLI::IsMember({"fv", "leapfrog"}))
        ->capture_default_str();
    sub->add_option("--courant", r.leapfrog.courant,
                    "Leap-frog only: Courant number of the fixed step, dt sqrt(g h_max) sqrt(1/dx^2 + 1/dy^2), at most 1")
        ->capture_default_str()
        ->check(in_range(Range::positive().up_to(10.0)));
    sub->add_option("--order", fv.order, "1: first order; 2: second order (limited slopes, MUSCL)")
        ->check(CLI::IsMember({1, 2}))
        ->capture_default_str();
    sub->add_option("--cfl", fv.cfl,
                    "Finite volumes: Courant number, dt*max(a_x/dx, a_y/dy) for the split step and dt*max(a_x/dx + a_y/dy) "
                    "for Heun's (a = |u| + sqrt(g h)), at most 1; above 0.5 a step that would make a depth negative is redone "
                    "at 0.45")
        ->capture_default_str()
        ->check(in_range(Range::positive().up_to(1.0)));
    sub->add_option("--max-dt", s.max_dt, "Upper bound on the time step [s]")
        ->capture_default_str()
        ->check(in_range(Range::positive("s")));
    sub->add_option("--limiter-theta", fv.limiter_theta, "Slope limiter: 1 minmod ... 2 monotonised central")
        ->capture_default_str()
        ->check(in_range(Range::closed(1.0, 2.0)));
    sub->add_option("--dry-depth", s.dry_depth,
                    "Dry tolerance [m]: velocities desingularised and reconstruction first order below it")
        ->capture_default_str()
        ->check(in_range(Range::positive("m").up_to(1.0)));
    sub->add_option("--friction", o->friction,
                    "Finite volumes: Manning friction 'implicit', or 'explicit' (for the stability study only)")
        ->capture_default_str()
        ->group(kStudyGroup);
    sub->add_option("--fronts", o->fronts,
                    "Finite volumes: dry-bed fronts 'plain' (cell averages) or 'tracked' (a wet fraction and an invariant "
                    "correction; with --time-stepping heun only; it fails Thacker's planar case and Ritter's dam break, docs/studies/wetdry_suite.md)")
        ->capture_default_str()
        ->group(kStudyGroup);
    sub->add_option("--time-stepping", o->stepping,
                    "Finite volumes: 'split' (an x and a y sweep of MUSCL-Hancock per step, their order alternating; the step "
                    "limited by each direction's own speed) or 'heun' (unsplit MUSCL with Heun's method)")
        ->capture_default_str()
        ->group(kStudyGroup);
    sub->add_flag("--study-past-stability-limit", s.study_past_stability_limit,
                  "Stability study only: accept --cfl above 1, step above 0.5 without the positivity redo, and let the leap-frog "
                  "run past Courant number 1 (to see the failure)")
        ->group(kStudyGroup);
    sub->add_option("--nest-ratio", r.nest.ratio,
                    "Grids of this many times the scene's spacing, west to east between the --nest-x interfaces, sub-cycled: "
                    "'4' is a coarse grid west of the interface and the scene's own east of it, '4,1,2' adds one twice as "
                    "coarse east of a second interface, '4,1,1' splits the scene's grid in two parts with steps of their own "
                    "(1: one uniform grid; docs/accuracy.md, docs/studies/hydro_speed_levers.md)")
        ->capture_default_str()
        ->delimiter(',')
        ->check(in_range(Range::count(1, 16)));
    sub->add_option("--nest-x", r.nest.x,
                    "x of the nesting interfaces, west to east [m]; keep them in water that stays wet or on ground the flow "
                    "does not reach")
        ->capture_default_str()
        ->delimiter(',')
        ->check(in_range(Range::any("m")));
    sub->add_option("--manning-n", s.default_manning_n, "Manning n where the scene has no manning_n [s m^-1/3]")
        ->capture_default_str()
        ->check(in_range(Range::non_negative("s m^-1/3").below(1.0)));
    // Boundaries.
    const std::string kinds =
        "wall, transmissive, level, discharge, pump or forced (zero-gradient: finite-volume study only)";
    sub->add_option("--west", o->west, "West boundary: " + kinds)->capture_default_str();
    sub->add_option("--east", o->east, "East boundary: " + kinds)->capture_default_str();
    sub->add_option("--south", o->south, "South boundary: " + kinds)->capture_default_str();
    sub->add_option("--north", o->north, "North boundary: " + kinds)->capture_default_str();
    sub->add_option("--west-series", s.west.series_file, "CSV time,value for a west level [m] or discharge [m^3/s] boundary");
    sub->add_option("--east-series", s.east.series_file, "CSV for an east level/discharge boundary");
    sub->add_option("--south-series", s.south.series_file, "CSV for a south level/discharge boundary");
    sub->add_option("--north-series", s.north.series_file, "CSV for a north level/discharge boundary");
    sub->add_option("--level-mode", o->level_mode_all, "The level mode of every side (total or incident); --<side>-level-mode wins")
        ->check(CLI::IsMember({"total", "incident"}));
    for (std::size_t k = 0; k < 4; ++k) {
        const std::string side = kSideNames[k];
        sub->add_option("--" + side + "-level-mode", o->level_mode[k],
                        "A " + side +
                            " level series is the 'total' measured level (velocity from the outgoing characteristic) or only "
                            "the 'incident' wave (reflections leave)")
            ->check(CLI::IsMember({"total", "incident"}))
            ->capture_default_str();
        sub->add_option("--" + side + "-series-end", o->series_end[k],
                        "After the " + side +
                            " series ends: 'error' (it must cover the run) or 'transmissive' (the side lets the water "
                            "leave)")
            ->check(CLI::IsMember({"error", "transmissive"}))
            ->capture_default_str();
    }
    for (std::size_t k = 0; k < 4; ++k) {
        const std::string side = kSideNames[k];
        sub->add_option("--" + side + "-forcing", o->forcing[k],
                        "CF NetCDF of another run's water level (and velocity, where it has them) on the " + side +
                            " side, gridded or at stations, in any CRS (docs/gis.md, \"Forcing from a regional model\"); "
                            "makes the side 'forced'. Outside its times the side is transmissive");
    }
    sub->add_option("--forcing-time", o->forcing_time, "How forced sides read their files in time: linear or cubic")
        ->check(CLI::IsMember({"linear", "cubic"}))
        ->capture_default_str();
    sub->add_option("--boundary-output", r.boundary_output.file,
                    "Write the level, depth and velocity on the outline of --boundary-box to this NetCDF, to force a finer "
                    "run over the box (its --<side>-forcing)");
    sub->add_option("--boundary-box", o->boundary_box, "The box of --boundary-output: x_min,x_max,y_min,y_max [m]")
        ->expected(4)
        ->delimiter(',')
        ->check(in_range(Range::any("m")));
    sub->add_option("--boundary-interval", r.boundary_output.interval,
                    "Simulated time between --boundary-output samples [s]; 0: every step")
        ->capture_default_str()
        ->check(in_range(Range::non_negative("s")));
    sub->add_option("--pump-discharge", s.pump.discharge, "Pump boundary: mass source [m^3/s]")
        ->capture_default_str()
        ->check(in_range(Range::non_negative("m^3/s")));
    sub->add_option("--pump-stop", s.pump.stop, "Pump boundary: end of pumping [s]")
        ->capture_default_str()
        ->check(in_range(Range::non_negative("s")));
    sub->add_option("--pump-relax", s.pump.relax_time, "Pump boundary: relaxation time of the level after pumping [s]")
        ->capture_default_str()
        ->check(in_range(Range::positive("s")));
    sub->add_option("--pump-length", s.pump.length, "Pump boundary: width of the source strip along x [m]")
        ->capture_default_str()
        ->check(in_range(Range::positive("m")));
    sub->callback([o, sub, command_line] { run_command(*o, sub, command_line); });
}

}  // namespace flotsam
