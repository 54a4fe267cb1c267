// The table of `flotsam hydro`'s settings (run_settings.hpp).
#include "hydro/run_settings.hpp"

namespace flotsam::hydro {

namespace {

using S = Setting<HydroDef>;

// What a run reads and stores, and how it goes (restart, threads, progress).
void add_run_settings(Settings<HydroDef>& t) {
    t.push_back({"scene",
                 "",
                 "Scene NetCDF (x, y, z; optional manning_n, building, eta0/u0/v0)",
                 Range(),
                 member_of<&HydroDef::run, &RunDef::scene_file>(),
                 {.required = true, .existing_file = true, .no_default = true}});
    t.push_back({"out",
                 "",
                 "Output flow file (.nc); written as <out>.part and renamed when complete",
                 Range(),
                 member_of<&HydroDef::run, &RunDef::out_file>(),
                 {.required = true, .no_default = true}});
    t.push_back({"duration", "s", "Simulated time", Range::positive("s"), member_of<&HydroDef::run, &RunDef::duration>()});
    t.push_back({"output-interval", "s", "Time between stored frames", Range::positive("s"),
                 member_of<&HydroDef::run, &RunDef::output_interval>()});
    t.push_back({"output-window",
                 "m",
                 "Store frames only in x_min,x_max,y_min,y_max [m]",
                 Range::any("m"),
                 &HydroDef::output_window,
                 {.no_default = true, .items = 4}});
    t.push_back({"gauge-interval", "s", "Time between gauge samples", Range::positive("s"),
                 member_of<&HydroDef::run, &RunDef::gauge_interval>()});
    t.push_back({"gauge",
                 "",
                 "Extra gauge NAME,X,Y (repeatable); the scene's gauge points are always recorded",
                 Range(),
                 &HydroDef::gauges,
                 {.no_default = true}});
    t.push_back({"arrival-depth", "m", "Depth threshold of the arrival-time map [m] (the debris draft)", Range::positive("m"),
                 member_of<&HydroDef::run, &RunDef::arrival_depth>()});
    t.push_back({"flood-depth", "m",
                 "Depth a cell must exceed to count as flooded [m]: the flooded map, the inundation line and the runup",
                 Range::positive("m"), member_of<&HydroDef::run, &RunDef::flood_depth>()});
    t.push_back({"checkpoint-interval", "s", "Simulated time between checkpoints [s]; 0: none", Range::non_negative("s"),
                 member_of<&HydroDef::run, &RunDef::checkpoint_interval>()});
    t.push_back({"restart",
                 "",
                 "Continue an interrupted run from <out>.checkpoint.nc and <out>.part",
                 Range(),
                 member_of<&HydroDef::run, &RunDef::restart>(),
                 {.no_default = true}});
    t.push_back({"stop-after",
                 "s",
                 "Stop as if interrupted once past this time [s] (leaves a checkpoint)",
                 Range::non_negative("s"),
                 member_of<&HydroDef::run, &RunDef::stop_after>(),
                 {.no_default = true}});
    t.push_back({"realisation", "1", "Boundary realisation id recorded in the file", Range::count(-1, 1e9),
                 member_of<&HydroDef::run, &RunDef::realisation>()});
    t.push_back({"deflate", "1", "Deflate level of stored fields, 0-9", Range::count(0, 9),
                 member_of<&HydroDef::run, &RunDef::deflate_level>()});
    t.push_back({"label", "", "Progress label", Range(), member_of<&HydroDef::run, &RunDef::label>()});
    t.push_back({"quiet", "", "No progress output", Range(), member_of<&HydroDef::run, &RunDef::quiet>(), {.no_default = true}});
    t.push_back({"allow-large-run",
                 "",
                 "Run even when the estimated work (cells x steps) passes the bound flotsam stops at (docs/reliability.md)",
                 Range(),
                 member_of<&HydroDef::run, &RunDef::allow_large_run>(),
                 {.no_default = true}});
    t.push_back({"threads", "1", "OpenMP threads (0: OMP_NUM_THREADS or all cores)", Range::count(0, 4096), &HydroDef::threads});
    t.push_back({"boundary-output",
                 "",
                 "Write the level, depth and velocity on the outline of --boundary-box to this NetCDF, to force a finer run "
                 "over the box (its --<side>-forcing)",
                 Range(),
                 member_of<&HydroDef::run, &RunDef::boundary_output, &BoundaryOutputDef::file>(),
                 {.no_default = true}});
    t.push_back({"boundary-box",
                 "m",
                 "The box of --boundary-output: x_min,x_max,y_min,y_max [m]",
                 Range::any("m"),
                 &HydroDef::boundary_box,
                 {.no_default = true, .items = 4}});
    t.push_back({"boundary-interval", "s", "Simulated time between --boundary-output samples [s]; 0: every step",
                 Range::non_negative("s"), member_of<&HydroDef::run, &RunDef::boundary_output, &BoundaryOutputDef::interval>()});
}

// The scheme, its step and its study variants, the nesting and the friction.
void add_scheme_settings(Settings<HydroDef>& t) {
    t.push_back({"scheme",
                 "",
                 "fv: finite volumes (MUSCL + HLL + Heun); leapfrog: staggered leap-frog of the classic tsunami codes",
                 Range(),
                 choice_of<&HydroDef::run, &RunDef::scheme>(),
                 {.names_in_type = true}});
    t.push_back({"courant", "1",
                 "Leap-frog only: Courant number of the fixed step, dt sqrt(g h_max) sqrt(1/dx^2 + 1/dy^2), at most 1",
                 Range::positive().up_to(10.0), member_of<&HydroDef::run, &RunDef::leapfrog, &LeapfrogDef::courant>()});
    t.push_back({"order", "1", "1: first order; 2: second order (limited slopes, MUSCL)", Range::count(1, 2),
                 member_of<&HydroDef::run, &RunDef::finite_volume, &FiniteVolumeDef::order>()});
    t.push_back({"cfl", "1",
                 "Finite volumes: Courant number, dt*max(a_x/dx, a_y/dy) for the split step and dt*max(a_x/dx + a_y/dy) "
                 "for Heun's (a = |u| + sqrt(g h)), at most 1; above 0.5 a step that would make a depth negative is redone "
                 "at 0.45",
                 Range::positive().up_to(1.0), member_of<&HydroDef::run, &RunDef::finite_volume, &FiniteVolumeDef::cfl>()});
    t.push_back({"precision",
                 "",
                 "Finite volumes: the state's type, 'float32' or 'float64' (the leap-frog and the tracked fronts: float64)",
                 Range(),
                 choice_of<&HydroDef::run, &RunDef::finite_volume, &FiniteVolumeDef::precision>(),
                 {.names_in_help = true}});
    t.push_back({"max-dt", "s", "Upper bound on the time step", Range::positive("s"),
                 member_of<&HydroDef::physics, &PhysicsDef::max_dt>()});
    t.push_back({"limiter-theta", "1", "Slope limiter: 1 minmod ... 2 monotonised central", Range::closed(1.0, 2.0),
                 member_of<&HydroDef::run, &RunDef::finite_volume, &FiniteVolumeDef::limiter_theta>()});
    t.push_back({"dry-depth", "m", "Dry tolerance [m]: velocities desingularised and reconstruction first order below it",
                 Range::positive("m").up_to(1.0), member_of<&HydroDef::physics, &PhysicsDef::dry_depth>()});
    t.push_back({"friction",
                 "",
                 "Finite volumes: Manning friction 'implicit', or 'explicit' (for the stability study only)",
                 Range(),
                 choice_of<&HydroDef::run, &RunDef::finite_volume, &FiniteVolumeDef::friction>(),
                 {.group = study_group, .names_in_help = true}});
    t.push_back({"fronts",
                 "",
                 "Finite volumes: dry-bed fronts 'plain' (cell averages) or 'tracked' (a wet fraction and an invariant "
                 "correction; with --time-stepping heun only; it fails Thacker's planar case and Ritter's dam break, "
                 "docs/studies/wetdry_suite.md)",
                 Range(),
                 choice_of<&HydroDef::run, &RunDef::finite_volume, &FiniteVolumeDef::fronts>(),
                 {.group = study_group, .names_in_help = true}});
    t.push_back({"time-stepping",
                 "",
                 "Finite volumes: 'split' (an x and a y sweep of MUSCL-Hancock per step, their order alternating; the step "
                 "limited by each direction's own speed) or 'heun' (unsplit MUSCL with Heun's method)",
                 Range(),
                 choice_of<&HydroDef::run, &RunDef::finite_volume, &FiniteVolumeDef::stepping>(),
                 {.group = study_group, .names_in_help = true}});
    t.push_back({"study-past-stability-limit",
                 "",
                 "Stability study only: accept --cfl above 1, step above 0.5 without the positivity redo, and let the leap-frog "
                 "run past Courant number 1 (to see the failure)",
                 Range(),
                 member_of<&HydroDef::physics, &PhysicsDef::study_past_stability_limit>(),
                 {.group = study_group, .no_default = true}});
    t.push_back({"nest-ratio", "1",
                 "Grids of this many times the scene's spacing, west to east between the --nest-x interfaces, sub-cycled: "
                 "'4' is a coarse grid west of the interface and the scene's own east of it, '4,1,2' adds one twice as "
                 "coarse east of a second interface, '4,1,1' splits the scene's grid in two parts with steps of their own "
                 "(1: one uniform grid; docs/accuracy.md, docs/studies/hydro_speed_levers.md)",
                 Range::count(1, 16), member_of<&HydroDef::run, &RunDef::nest, &NestDef::ratio>()});
    t.push_back({"nest-x", "m",
                 "x of the nesting interfaces, west to east [m]; keep them in water that stays wet or on ground the flow "
                 "does not reach",
                 Range::any("m"), member_of<&HydroDef::run, &RunDef::nest, &NestDef::x>()});
    t.push_back({"manning-n", "s m^-1/3", "Manning n where the scene has no manning_n [s m^-1/3]",
                 Range::non_negative("s m^-1/3").below(1.0), member_of<&HydroDef::physics, &PhysicsDef::default_manning_n>()});
}

const char* const kSideNames[4] = {"west", "east", "south", "north"};
const char* const kSideTitles[4] = {"West", "East", "South", "North"};

template <BoundaryDef PhysicsDef::*Side>
S side_kind(int k) {
    return {kSideNames[k],
            "",
            std::string(kSideTitles[k]) +
                " boundary: wall, transmissive, level, discharge, pump or forced (--" + kSideNames[k] +
                "-forcing; zero-gradient: finite-volume study only)",
            Range(),
            choice_of<&HydroDef::physics, Side, &BoundaryDef::kind>(),
            {.names_in_help = true}};
}

template <BoundaryDef PhysicsDef::*Side>
S side_series(int k, const std::string& help) {
    return {std::string(kSideNames[k]) + "-series",
            "",
            help,
            Range(),
            member_of<&HydroDef::physics, Side, &BoundaryDef::series_file>(),
            {.no_default = true}};
}

template <BoundaryDef PhysicsDef::*Side>
S side_forcing(int k) {
    const std::string side = kSideNames[k];
    return {side + "-forcing",
            "",
            "CF NetCDF of another run's water level (and velocity and depth, where it has them) on the " + side +
                " side, gridded or at stations, in any CRS (docs/gis.md, \"Forcing from a regional model\"); makes the "
                "side 'forced'; outside the file's times the side is transmissive",
            Range(),
            member_of<&HydroDef::physics, Side, &BoundaryDef::forcing_file>(),
            {.no_default = true}};
}

template <BoundaryDef PhysicsDef::*Side>
void add_side_modes(Settings<HydroDef>& t, int k) {
    const std::string side = kSideNames[k];
    t.push_back({side + "-level-mode",
                 "",
                 "A " + side +
                     " level series is the 'total' measured level (velocity from the outgoing characteristic) or only "
                     "the 'incident' wave (reflections leave)",
                 Range(),
                 choice_of<&HydroDef::physics, Side, &BoundaryDef::level_mode>(),
                 {.names_in_type = true}});
    t.push_back(
        {side + "-series-end",
         "",
         "After the " + side + " series ends: 'error' (it must cover the run) or 'transmissive' (the side lets the water leave)",
         Range(),
         choice_of<&HydroDef::physics, Side, &BoundaryDef::series_end>(),
         {.names_in_type = true}});
}

// The four sides, the level mode of all of them, and the pump.
void add_boundary_settings(Settings<HydroDef>& t) {
    t.push_back(side_kind<&PhysicsDef::west>(0));
    t.push_back(side_kind<&PhysicsDef::east>(1));
    t.push_back(side_kind<&PhysicsDef::south>(2));
    t.push_back(side_kind<&PhysicsDef::north>(3));
    t.push_back(side_series<&PhysicsDef::west>(0, "CSV time,value for a west level [m] or discharge [m^3/s] boundary"));
    t.push_back(side_series<&PhysicsDef::east>(1, "CSV for an east level/discharge boundary"));
    t.push_back(side_series<&PhysicsDef::south>(2, "CSV for a south level/discharge boundary"));
    t.push_back(side_series<&PhysicsDef::north>(3, "CSV for a north level/discharge boundary"));
    const Choice<HydroDef> every_side{
        [](const HydroDef& d) { return d.level_mode ? enum_name(*d.level_mode) : ""; },
        [](HydroDef& d, std::string_view name, const std::string& where) { d.level_mode = parse_enum<LevelMode>(name, where); },
        [] { return enum_list<LevelMode>(); }};
    t.push_back({"level-mode",
                 "",
                 "The level mode of every side (total or incident); --<side>-level-mode wins",
                 Range(),
                 every_side,
                 {.no_default = true, .names_in_type = true}});
    add_side_modes<&PhysicsDef::west>(t, 0);
    add_side_modes<&PhysicsDef::east>(t, 1);
    add_side_modes<&PhysicsDef::south>(t, 2);
    add_side_modes<&PhysicsDef::north>(t, 3);
    t.push_back(side_forcing<&PhysicsDef::west>(0));
    t.push_back(side_forcing<&PhysicsDef::east>(1));
    t.push_back(side_forcing<&PhysicsDef::south>(2));
    t.push_back(side_forcing<&PhysicsDef::north>(3));
    t.push_back({"forcing-time", "", "How forced sides read their files in time: linear, or cubic (Hermite, exact for a "
                 "quadratic level)", Range(), choice_of<&HydroDef::forcing_time>(), {.names_in_type = true}});
    t.push_back({"pump-discharge", "m^3/s", "Pump boundary: mass source", Range::non_negative("m^3/s"),
                 member_of<&HydroDef::physics, &PhysicsDef::pump, &PumpDef::discharge>()});
    t.push_back({"pump-stop", "s", "Pump boundary: end of pumping", Range::non_negative("s"),
                 member_of<&HydroDef::physics, &PhysicsDef::pump, &PumpDef::stop>()});
    t.push_back({"pump-relax", "s", "Pump boundary: relaxation time of the level after pumping", Range::positive("s"),
                 member_of<&HydroDef::physics, &PhysicsDef::pump, &PumpDef::relax_time>()});
    t.push_back({"pump-length", "m", "Pump boundary: width of the source strip along x", Range::positive("m"),
                 member_of<&HydroDef::physics, &PhysicsDef::pump, &PumpDef::length>()});
}

}  // namespace

const Settings<HydroDef>& hydro_settings() {
    static const Settings<HydroDef> table = [] {
        Settings<HydroDef> t;
        add_run_settings(t);
        add_scheme_settings(t);
        add_boundary_settings(t);
        return t;
    }();
    return table;
}

}  // namespace flotsam::hydro
