#include "hydro/run.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <ctime>
#include <filesystem>

#include "common/atomic_file.hpp"
#include "common/checks.hpp"
#include "common/error.hpp"
#include "common/netcdf.hpp"
#include "common/output_lock.hpp"
#include "common/progress.hpp"
#include "common/sha256.hpp"
#include "common/version.hpp"
#include "hydro/restart_key.hpp"
#include "hydro/run_checkpoint.hpp"
#include "hydro/run_frames.hpp"
#include "hydro/state_checks.hpp"

namespace flotsam::hydro {

std::string checkpoint_path(const std::string& out_file) { return out_file + ".checkpoint.nc"; }

namespace {

std::string boundary_files(const PhysicsDef& d) {
    std::string s;
    const BoundaryDef* sides[4] = {&d.west, &d.east, &d.south, &d.north};
    const char* names[4] = {"west", "east", "south", "north"};
    for (int k = 0; k < 4; ++k)
        for (const std::string& f : {sides[k]->series_file, sides[k]->forcing_file})
            if (!f.empty()) s += std::string(s.empty() ? "" : "; ") + names[k] + ": " + f;
    return s;
}

std::string boundary_checksums(const PhysicsDef& d) {
    std::string s;
    for (const BoundaryDef* b : {&d.west, &d.east, &d.south, &d.north})
        for (const std::string& f : {b->series_file, b->forcing_file})
            if (!f.empty()) s += std::string(s.empty() ? "" : "; ") + "sha256:" + sha256_file(f);
    return s;
}

// Processor time of this process, all threads [s].
double cpu_seconds() {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

// ---- the run, step by step ----

// The scene's bed on the output window [m].
std::vector<float> window_bed(const Scene& scene, const Window& win) {
    std::vector<float> z(win.grid.size());
    for (int j = win.j0; j <= win.j1; ++j)
        for (int i = win.i0; i <= win.i1; ++i) z[win.grid.index(i - win.i0, j - win.j0)] = float(scene.z[scene.grid.index(i, j)]);
    return z;
}

std::vector<FlowGauge> gauge_points_of(const Scene& scene, const RunDef& run) {
    std::vector<FlowGauge> points;
    for (const auto& p : scene.points)
        if (p.kind == "gauge") points.push_back({p.name, p.x, p.y});
    for (const auto& g : run.gauges) points.push_back(g);
    return points;
}

// What a run carries from start to end besides the solver: the output window and frame
// times, the gauges and the maxima, the file being written and the checkpoint's
// bookkeeping.
struct RunOutput {
    RunOutput(const Scene& scene, const RunDef& run, const PhysicsDef& def)
        : win(make_window(scene.grid, run.window)),
          times(frame_times(run.duration, run.output_interval)),
          gauge_points(gauge_points_of(scene, run)),
          gauges(gauge_points, scene.grid, run.gauge_interval, run.duration),
          key(restart_key(run, def)),
          file(run.out_file),
          checkpoint(checkpoint_path(run.out_file)) {
        sum.max_depth.assign(win.grid.size(), 0.0f);
        sum.max_speed.assign(win.grid.size(), 0.0f);
        sum.arrival.assign(win.grid.size(), float(kFill));
    }
    Window win;
    std::vector<double> times;
    std::vector<FlowGauge> gauge_points;
    Gauges gauges;
    Summary sum;
    std::string key;  // restart_key() of this run
    AtomicOutput file;
    std::string checkpoint;
    std::optional<FlowWriter> writer;
    std::optional<BoundaryOutput> outline;  // --boundary-output
    Checkpoint state;  // where the run stands (its time and counters are set when saved)
};

// The flow file's definition: the window's bed, the axes, the gauges and the global
// attributes that say how the flow was made.
FlowFileDef flow_file_def(const Scene& scene, const RunDef& run, const PhysicsDef& def, const RunOutput& o,
                          const std::string& scheme) {
    FlowFileDef fd;
    fd.window = o.win.grid;
    fd.z = window_bed(scene, o.win);
    fd.frame_times = o.times;
    fd.gauges = o.gauge_points;
    fd.gauge_samples = o.gauges.samples();
    fd.gauge_interval = run.gauge_interval;
    fd.arrival_depth = run.arrival_depth;
    fd.flood_depth = run.flood_depth;
    fd.deflate_level = run.deflate_level;
    fd.crs = scene.crs;
    fd.attributes["title"] = "flotsam shallow-water flow" + std::string(scene.synthetic ? " (synthetic scene)" : "");
    fd.attributes["source"] = version_string() + "; " + scheme;
    fd.attributes["history"] = run.command_line;
    fd.attributes["flotsam_config"] = run.config_text;
    fd.attributes["scene_file"] = run.scene_file;
    fd.attributes["scene_sha256"] = sha256_file(run.scene_file);  // debris replays check it (debris/scene_match.hpp)
    fd.attributes["scene_buildings_sha256"] = scene_buildings_sha256(scene);  // debris checks the building mask
    fd.attributes["scene_title"] = scene.title;
    fd.attributes["realisation"] = std::to_string(run.realisation);
    fd.attributes["boundary_file"] = boundary_files(def);
    fd.attributes["boundary_checksum"] = boundary_checksums(def);
    char dry[32];
    std::snprintf(dry, sizeof dry, "%g", def.dry_depth);  // std::to_string's "%f" would write 1e-9 as 0.000000
    fd.attributes["dry_depth_m"] = dry;
    return fd;
}

// A fresh run: creates the file and stores the initial state (frame 0, the maxima and
// the gauges at t = 0).
template <RunnableSolver S>
void start(S& solver, const Scene& scene, const RunDef& run, const PhysicsDef& def, RunOutput& o) {
    const FlowFileDef fd = flow_file_def(scene, run, def, o, solver.description());
    o.writer.emplace(o.file.temp_path(), fd);
    if (!run.boundary_output.file.empty()) {
        o.outline.emplace(run.boundary_output, scene.grid, scene.crs, fd.attributes);
        o.outline->record(0.0, o.outline->read(solver), 0.0, o.outline->read(solver));
    }
    o.state.volume_start = solver.volume();
    write_frame(*o.writer, 0, solver, o.win);
    o.state.next_frame = 1;
    accumulate(o.sum, solver, o.win, 0.0, run.arrival_depth);
    o.gauges.record(0.0, o.gauges.read(solver), 0.0, o.gauges.read(solver));
}

// A restart: the state, maxima and partial file of the interrupted run, if they were
// written with the same settings, scene and boundary files.
template <RunnableSolver S>
void resume(S& solver, RunOutput& o) {
    o.file.keep_partial();  // the interrupted run's work: never removed, whatever happens next
    if (!std::filesystem::exists(o.checkpoint)) fail(o.checkpoint, "", "no checkpoint to restart from");
    if (!std::filesystem::exists(o.file.temp_path()))
        fail(o.file.temp_path(), "", "the partial output of the interrupted run is missing");
    // The settings first (attributes only), so that a refusal touches no state.
    const std::string written_with = read_checkpoint_key(o.checkpoint);
    if (written_with != o.key)
        fail(o.checkpoint, "",
             "was written with other settings, scene or boundary files (" + differing_settings(written_with, o.key) +
                 "): restart with the checkpoint's settings, or remove " + o.checkpoint + " and " + o.file.temp_path() +
                 " to start afresh");
    o.state = read_checkpoint(o.checkpoint, solver, o.sum);
    solver.set_time(o.state.time);
    if (o.state.pump_stopped) solver.set_pump_level_at_stop(o.state.pump_level);
    o.writer.emplace(FlowWriter::reopen(o.file.temp_path()));
    o.gauges.resume_at(o.state.next_gauge);
}

// Saves the exact state at time t after `steps` steps, so that --restart continues to
// the same result.
template <RunnableSolver S>
void save_checkpoint(S& solver, const PhysicsDef& def, RunOutput& o, double t, long steps) {
    o.gauges.flush(*o.writer);
    o.writer->sync();
    o.state.time = t;
    o.state.steps = steps;
    o.state.next_gauge = o.gauges.next();
    o.state.pump_stopped = def.west.kind == BoundaryKind::pump && t >= def.pump.stop;
    o.state.pump_level = solver.pump_level_at_stop();
    o.state.key = o.key;
    write_checkpoint(o.checkpoint, solver, o.sum, o.state);
}

// Set by request_stop (a signal handler): the run stops at its next frame when that is
// near, else at once (step_to_end).
volatile std::sig_atomic_t stop_signal = 0;

// After a signal, the longest the run goes on to reach its next frame [s of wall time]:
// there it writes a checkpoint, and --restart continues it; a frame further off (a slow
// or stalled step) is not waited for, and the run stops at once with its last
// checkpoint, if any, and its partial output as they are.
constexpr double stop_wait_wall = 1.0;

// Steps to the last frame, storing frames, gauges, maxima and checkpoints on the way.
// Returns the step count since the start of the run (restarts included), negated when
// the run stopped early at run.stop_after.
template <RunnableSolver S>
long step_to_end(S& solver, const RunDef& run, const PhysicsDef& def, RunOutput& o, Progress& progress) {
    double next_checkpoint = run.checkpoint_interval > 0.0
                                 ? (std::floor(solver.time() / run.checkpoint_interval + 1e-9) + 1.0) * run.checkpoint_interval
                                 : 1e300;
    long steps = o.state.steps;
    auto before = o.gauges.read(solver);
    auto outline_before = o.outline ? o.outline->read(solver) : std::vector<PointSample>{};
    StepWatch watch;
    using Clock = std::chrono::steady_clock;
    auto last_step_end = Clock::now();
    double wall_per_step = 0.0;  // [s] a running mean of the last steps' wall time
    while (o.state.next_frame < o.times.size()) {
        const double t0 = solver.time();
        const double target = o.times[o.state.next_frame];
        double dt = solver.stable_dt();
        check_step(solver, solver.grid(), run.out_file, t0, dt, o.state.volume_start);
        if (watch.stalled(dt)) fail_stalled(run.out_file, t0, dt, watch, fastest_cell(solver, solver.grid(), def.gravity));
        if (stop_signal != 0 && (target - t0) / dt * wall_per_step > stop_wait_wall) return -steps;
        // A step that would stop within a millionth of itself short of the frame goes to
        // it (a fixed step that divides the interval lands there despite round-off in t).
        const bool reaches = t0 + dt >= target - 1e-6 * dt;
        if (reaches) dt = target - t0;
        solver.step(dt);
        if (reaches) solver.set_time(target);  // land exactly on the frame time
        ++steps;
        const double t1 = solver.time();
        auto after = o.gauges.read(solver);
        o.gauges.record(t0, before, t1, after);
        before = std::move(after);
        if (o.outline) {
            auto outline_after = o.outline->read(solver);
            o.outline->record(t0, outline_before, t1, outline_after);
            outline_before = std::move(outline_after);
        }
        accumulate(o.sum, solver, o.win, t1, run.arrival_depth);
        if (reaches) {
            check_state(solver, solver.grid(), run.out_file, t1, o.state.volume_start);  // never write NaN
            try {
                write_frame(*o.writer, o.state.next_frame, solver, o.win);
                o.gauges.flush(*o.writer);
                if (o.outline) o.outline->flush();
                o.writer->sync();  // a full disk shows here, at this frame, not at the end
            } catch (const Error& e) {
                throw Error(std::string(e.what()) + "; while writing frame " + std::to_string(o.state.next_frame) +
                            " (t = " + number_text(t1) + " s)");
            }
            ++o.state.next_frame;
        }
        // Checkpoints and stops fall on stored frames, and every frame ends with a sync:
        // the file then has the same bytes (HDF5's layout included) whether the run was
        // checkpointed, stopped and restarted, or never interrupted.
        // Not at frame 1, though: a run continued from there has the same values but a file
        // 1 kB smaller (libhdf5 leaves 1 kB unused in the uninterrupted run, h5stat's
        // "unaccounted space"), so the first checkpoint or stop waits for frame 2.
        const bool stop = (run.stop_after >= 0.0 && t1 >= run.stop_after) || stop_signal != 0;
        if (reaches && o.state.next_frame > 2 && (t1 >= next_checkpoint - 1e-12 || stop)) {
            save_checkpoint(solver, def, o, t1, steps);
            if (run.checkpoint_interval > 0.0)
                next_checkpoint = (std::floor(t1 / run.checkpoint_interval + 1e-9) + 1.0) * run.checkpoint_interval;
            if (stop) return -steps;
        }
        const auto now = Clock::now();
        wall_per_step = 0.9 * wall_per_step + 0.1 * std::chrono::duration<double>(now - last_step_end).count();
        last_step_end = now;
        progress.update(t1, dt, steps);
    }
    return steps;
}

template <RunnableSolver S>
RunResult run_with(S& solver, const Scene& scene, const RunDef& run, const PhysicsDef& def) {
    const std::string ckpt = checkpoint_path(run.out_file);
    if (!run.restart && std::filesystem::exists(ckpt))
        fail(ckpt, "",
             "holds an interrupted run of " + run.out_file + ": continue it with --restart, or remove " + ckpt + " and " +
                 run.out_file + ".part to start afresh");
    RunOutput o(scene, run, def);
    if (run.restart)
        resume(solver, o);
    else
        start(solver, scene, run, def, o);
    const long steps_before = o.state.steps;  // 0 unless restarted
    const double started = solver.time();
    const auto wall0 = std::chrono::steady_clock::now();
    const double cpu0 = cpu_seconds();
    Progress progress(run.label, run.duration, 10.0, run.quiet);
    const long signed_steps = step_to_end(solver, run, def, o, progress);

    RunResult res;
    res.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
    res.cpu_seconds = cpu_seconds() - cpu0;
    res.completed = signed_steps >= 0;
    res.stop_signal = res.completed ? 0 : int(stop_signal);
    res.steps = std::abs(signed_steps) - steps_before;
    res.started = started;
    res.simulated = solver.time();
    res.cell_updates_per_second = solver.cell_updates() / std::max(res.wall_seconds, 1e-9);
    res.volume_start = o.state.volume_start;
    res.volume_end = solver.volume();
    res.negative_depth_fixes = solver.stats().negative_depth_fixes;
    res.positivity_redos = solver.stats().positivity_redos;
    res.outflow_limits = solver.stats().outflow_limits;
    res.dry_skipped_fraction = solver.stats().cell_stages_dry / std::max(solver.stats().cell_stages, 1.0);
    if (!res.completed) {
        o.writer->close();
        o.file.keep_partial();
        if (std::filesystem::exists(o.checkpoint)) res.checkpoint_time = read_checkpoint_time(o.checkpoint);
        return res;
    }
    o.gauges.flush(*o.writer);
    o.writer->write_summary(o.sum.max_depth, o.sum.max_speed, o.sum.arrival);
    o.writer->write_runup(runup_summary(o.win.grid, window_bed(scene, o.win), o.sum.max_depth, run.flood_depth));
    o.writer->close();
    if (o.outline) o.outline->commit();
    o.file.commit();
    std::filesystem::remove(o.checkpoint);
    progress.finish(solver.time(), std::abs(signed_steps));
    res.file_bytes = std::filesystem::file_size(run.out_file);
    return res;
}

}  // namespace

static_assert(RunnableSolver<Solver> && RunnableSolver<NestedSolver> && RunnableSolver<LeapfrogSolver>);

void request_stop(int signal) { stop_signal = signal; }

namespace {

// The run's work, estimated before it starts (docs/reliability.md, "Every run is
// bounded"): every cell of the scene's grid updated at a step of cfl x cell / (2 (|u| +
// c)), with c = sqrt(g h) over the deepest still water plus the highest boundary level
// and |u| = c, or --max-dt when smaller. An estimate from above (nesting and dry land
// make real runs cheaper); refused past max_cell_updates unless --allow-large-run.
void check_hydro_work(const RunDef& run, const PhysicsDef& physics, const Scene& scene, double highest_level) {
    double deepest = 0.0;
    for (double z : scene.z) deepest = std::max(deepest, -z);
    // No water is deeper than the oceans (a deeper state stops the run: state_checks).
    const double depth = std::clamp(deepest + highest_level, 0.01, 11000.0);
    const double cfl = run.scheme == Scheme::leapfrog ? run.leapfrog.courant : run.finite_volume.cfl;
    const double cell = std::min(scene.grid.dx, scene.grid.dy);
    const double dt_cfl = cfl * cell / (4.0 * std::sqrt(9.81 * depth));
    const bool max_dt_binds = physics.max_dt < dt_cfl;
    const double dt = std::min(dt_cfl, physics.max_dt);
    const double cells = double(scene.grid.nx) * double(scene.grid.ny);
    const double updates = cells * run.duration / dt;
    char text[320];
    std::snprintf(text, sizeof text, "%s s of %s over %s cells of %s m (steps of about %.2g s)", number_text(run.duration).c_str(),
                  run.scene_file.c_str(), number_text(cells).c_str(), number_text(cell).c_str(), dt);
    check_work(max_dt_binds ? "--max-dt" : "--duration", text, updates, max_cell_updates, "cell updates", run.allow_large_run);
}

}  // namespace

RunResult run_hydro(const RunDef& run, const PhysicsDef& physics) {
    if (run.out_file.empty()) fail("", "--out", "an output file is required");
    const OutputLock lock(run.out_file);  // one writer per output: a second run stops here
    if (!(run.duration > 0.0)) fail("", "--duration", "must be positive");
    const Scene scene = read_scene(run.scene_file);
    if (run.restart && !run.boundary_output.file.empty())
        fail("", "--boundary-output",
             "is written from the start of a run and not continued by --restart: run it again without --restart");
    // Boundary series must cover the whole run (or its start, where the side hands over
    // to a transmissive one when the series ends) before any work starts.
    double highest_level = 0.0;  // [m] of any boundary series
    for (const BoundaryDef* b : {&physics.west, &physics.east, &physics.south, &physics.north})
        if (b->kind == BoundaryKind::forced && b->record) {
            for (double v : b->record->level) highest_level = std::max(highest_level, std::fabs(v));
        } else if (!b->series_file.empty()) {
            const TimeSeries series = read_time_series_csv(b->series_file);
            require_coverage(series, 0.0, b->series_end == SeriesEnd::error ? run.duration : 0.0);
            for (double v : series.value) highest_level = std::max(highest_level, std::fabs(v));
        }
    check_hydro_work(run, physics, scene, highest_level);
    if (run.scheme == Scheme::leapfrog) {
        if (run.nest.nested()) {
            std::string ratios;
            for (int r : run.nest.ratio) {
                if (!ratios.empty()) ratios += ',';
                ratios += std::to_string(r);
            }
            fail("", "--nest-ratio",
                 "nested grids are written for the finite-volume scheme: use --scheme fv with --nest-ratio " + ratios +
                     ", or --scheme leapfrog with --nest-ratio 1");
        }
        LeapfrogDef lf = run.leapfrog;
        lf.step_divides = run.output_interval;
        LeapfrogSolver solver(scene, physics, lf);
        return run_with(solver, scene, run, physics);
    }
    if (run.nest.nested()) {
        NestedSolver solver(scene, physics, run.finite_volume, run.nest);
        return run_with(solver, scene, run, physics);
    }
    Solver solver(scene, physics, run.finite_volume);
    return run_with(solver, scene, run, physics);
}

}  // namespace flotsam::hydro
