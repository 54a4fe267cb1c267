// `flotsam hydro`: one shallow-water run of a scene, written as a CF flow file.
#include <omp.h>

#include <cstdio>
#include <memory>
#include <sstream>

#include "app/commands.hpp"
#include "common/error.hpp"
#include "hydro/run.hpp"

namespace flotsam {

namespace {

struct HydroOptions {
    hydro::RunDef run;
    hydro::SolverDef solver = hydro::default_solver_def();
    std::vector<double> window;
    std::vector<std::string> gauges;
    std::string west = "level", east = "transmissive", south = "wall", north = "wall";
    std::string level_mode = "total";
    std::string scheme = "fv";
    std::string friction = "implicit";
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
    SolverDef& s = o.solver;
    o.run.scheme = parse_scheme(o.scheme, "--scheme");
    s.friction = parse_friction(o.friction, "--friction");
    s.west.kind = parse_boundary_kind(o.west, "--west");
    s.east.kind = parse_boundary_kind(o.east, "--east");
    s.south.kind = parse_boundary_kind(o.south, "--south");
    s.north.kind = parse_boundary_kind(o.north, "--north");
    const LevelMode mode = parse_level_mode(o.level_mode, "--level-mode");
    for (BoundaryDef* b : {&s.west, &s.east, &s.south, &s.north}) {
        b->level_mode = mode;
        b->pump_discharge = s.west.pump_discharge;
        b->pump_stop = s.west.pump_stop;
        b->pump_relax_time = s.west.pump_relax_time;
        b->pump_length = s.west.pump_length;
    }
    if (!o.window.empty()) o.run.window = std::array<double, 4>{o.window[0], o.window[1], o.window[2], o.window[3]};
    for (const auto& g : o.gauges) {
        const auto a = g.find(','), b = g.rfind(',');
        if (a == std::string::npos || a == b) fail("", "--gauge '" + g + "'", "expected NAME,X,Y");
        try {
            o.run.gauges.push_back({g.substr(0, a), std::stod(g.substr(a + 1, b - a - 1)), std::stod(g.substr(b + 1))});
        } catch (const std::exception&) {
            fail("", "--gauge '" + g + "'", "X and Y must be numbers");
        }
    }
    if (o.threads > 0) omp_set_num_threads(o.threads);
    o.run.command_line = command_line;
    o.run.config_text = result_settings(sub->config_to_str(true, false));
    const RunResult r = run_hydro(o.run, s);
    if (!o.run.quiet)
        std::fprintf(stderr,
                     "%s: %s after %ld steps in %.1f s wall (%.1f s processor), %.3g cell-updates/s (%.0f%% dry land skipped), "
                     "volume %.6g -> %.6g m^3%s%s\n",
                     o.run.label.c_str(), r.completed ? "complete" : "stopped (checkpoint written; continue with --restart)",
                     r.steps, r.wall_seconds, r.cpu_seconds, r.cell_updates_per_second, 100.0 * r.dry_skipped_fraction,
                     r.volume_start, r.volume_end, r.negative_depth_fixes ? ", negative depths clamped" : "",
                     r.outflow_limits ? (", outflow limited in " + std::to_string(r.outflow_limits) + " cell-steps").c_str() : "");
}

}  // namespace

void register_hydro_commands(CLI::App& app, const std::string& command_line) {
    auto o = std::make_shared<HydroOptions>();
    CLI::App* sub = app.add_subcommand("hydro", "Run the shallow-water solver on a scene and write a CF NetCDF flow file");
    add_config_option(sub);
    auto& r = o->run;
    auto& s = o->solver;
    sub->add_option("--scene", r.scene_file, "Scene NetCDF (x, y, z; optional manning_n, building, eta0/u0/v0)")
        ->required()
        ->check(CLI::ExistingFile);
    sub->add_option("--out", r.out_file, "Output flow file (.nc); written as <out>.part and renamed when complete")->required();
    sub->add_option("--duration", r.duration, "Simulated time [s]")->capture_default_str();
    sub->add_option("--output-interval", r.output_interval, "Time between stored frames [s]")->capture_default_str();
    sub->add_option("--output-window", o->window, "Store frames only in x_min,x_max,y_min,y_max [m]")->expected(4)->delimiter(',');
    sub->add_option("--gauge-interval", r.gauge_interval, "Time between gauge samples [s]")->capture_default_str();
    sub->add_option("--gauge", o->gauges, "Extra gauge NAME,X,Y (repeatable); the scene's gauge points are always recorded");
    sub->add_option("--arrival-depth", r.arrival_depth, "Depth threshold of the arrival-time map [m] (the debris draft)")
        ->capture_default_str();
    sub->add_option("--checkpoint-interval", r.checkpoint_interval, "Simulated time between checkpoints [s]; 0: none")
        ->capture_default_str();
    sub->add_flag("--restart", r.restart, "Continue an interrupted run from <out>.checkpoint.nc and <out>.part");
    sub->add_option("--stop-after", r.stop_after, "Stop as if interrupted once past this time [s] (leaves a checkpoint)");
    sub->add_option("--realisation", r.realisation, "Boundary realisation id recorded in the file")->capture_default_str();
    sub->add_option("--deflate", r.deflate_level, "Deflate level of stored fields, 0-9")
        ->check(CLI::Range(0, 9))
        ->capture_default_str();
    sub->add_option("--label", r.label, "Progress label")->capture_default_str();
    sub->add_flag("--quiet", r.quiet, "No progress output");
    sub->add_option("--threads", o->threads, "OpenMP threads (0: OMP_NUM_THREADS or all cores)")->capture_default_str();
    // Scheme.
    sub->add_option("--scheme", o->scheme,
                    "fv: finite volumes (MUSCL + HLL + Heun); leapfrog: staggered leap-frog of the classic tsunami codes")
        ->check(CLI::IsMember({"fv", "leapfrog"}))
        ->capture_default_str();
    sub->add_option("--courant", r.leapfrog.courant,
                    "Leap-frog only: Courant number of the fixed step, dt sqrt(g h_max) sqrt(1/dx^2 + 1/dy^2), at most 1")
        ->capture_default_str();
    sub->add_option("--order", s.order, "1: first order; 2: MUSCL + Heun (default)")
        ->check(CLI::IsMember({1, 2}))
        ->capture_default_str();
    sub->add_option("--cfl", s.cfl, "Finite volumes: Courant number dt*max(a_x/dx + a_y/dy), at most 0.5")->capture_default_str();
    sub->add_option("--max-dt", s.max_dt, "Upper bound on the time step [s]")->capture_default_str();
    sub->add_option("--limiter-theta", s.limiter_theta, "Slope limiter: 1 minmod ... 2 monotonised central")
        ->check(CLI::Range(1.0, 2.0))
        ->capture_default_str();
    sub->add_option("--dry-depth", s.dry_depth, "Dry tolerance [m]: no velocity or friction below it")->capture_default_str();
    sub->add_option("--friction", o->friction,
                    "Finite volumes: Manning friction 'implicit', or 'explicit' (for the stability study only)")
        ->capture_default_str();
    sub->add_flag(
        "--study-past-stability-limit", s.study_past_stability_limit,
        "Stability study only: accept --cfl above 0.5 and let the leap-frog run past Courant number 1 (to see the failure)");
    sub->add_option("--nest-ratio", r.nest.ratio,
                    "Coarse grid of this many times the scene's spacing west of --nest-x, sub-cycled (1: one uniform grid)")
        ->check(CLI::Range(1, 16))
        ->capture_default_str();
    sub->add_option("--nest-x", r.nest.x, "x of the nesting interface [m]; keep it in water that stays wet")->capture_default_str();
    sub->add_option("--manning-n", s.default_manning_n, "Manning n where the scene has no manning_n [s m^-1/3]")
        ->capture_default_str();
    // Boundaries.
    const std::string kinds = "wall, transmissive, level, discharge or pump";
    sub->add_option("--west", o->west, "West boundary: " + kinds)->capture_default_str();
    sub->add_option("--east", o->east, "East boundary: " + kinds)->capture_default_str();
    sub->add_option("--south", o->south, "South boundary: " + kinds)->capture_default_str();
    sub->add_option("--north", o->north, "North boundary: " + kinds)->capture_default_str();
    sub->add_option("--west-series", s.west.series_file, "CSV time,value for a west level [m] or discharge [m^3/s] boundary");
    sub->add_option("--east-series", s.east.series_file, "CSV for an east level/discharge boundary");
    sub->add_option("--south-series", s.south.series_file, "CSV for a south level/discharge boundary");
    sub->add_option("--north-series", s.north.series_file, "CSV for a north level/discharge boundary");
    sub->add_option("--level-mode", o->level_mode,
                    "A level series is the 'total' measured level (velocity from the outgoing characteristic) or only the "
                    "'incident' wave (reflections leave)")
        ->capture_default_str();
    sub->add_option("--pump-discharge", s.west.pump_discharge, "Pump boundary: mass source [m^3/s]")->capture_default_str();
    sub->add_option("--pump-stop", s.west.pump_stop, "Pump boundary: end of pumping [s]")->capture_default_str();
    sub->add_option("--pump-relax", s.west.pump_relax_time, "Pump boundary: relaxation time of the level after pumping [s]")
        ->capture_default_str();
    sub->add_option("--pump-length", s.west.pump_length, "Pump boundary: width of the source strip along x [m]")
        ->capture_default_str();
    sub->callback([o, sub, command_line] { run_command(*o, sub, command_line); });
}

}  // namespace flotsam
