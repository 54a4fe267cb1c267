#include "hydro/run.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>

#include "common/checks.hpp"
#include "common/error.hpp"
#include "common/output_lock.hpp"
#include "hydro/run_driver.hpp"

namespace flotsam::hydro {

std::string checkpoint_path(const std::string& out_file) { return out_file + ".checkpoint.nc"; }

void request_stop(int signal) { stop_signal = signal; }

namespace {

// Processor time of this process, all threads [s].
double cpu_seconds() {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

// The counters of a run that stepped from `started` to where the solver is now.
RunResult result_of(const RunSolver& solver, const RunOutput& o, long signed_steps, long steps_before, double started,
                    double wall, double cpu) {
    RunResult res;
    res.wall_seconds = wall;
    res.cpu_seconds = cpu;
    res.completed = signed_steps >= 0;
    res.stop_signal = res.completed ? 0 : int(stop_signal);
    res.steps = std::abs(signed_steps) - steps_before;
    res.started = started;
    res.simulated = solver.time();
    res.cell_updates_per_second = solver.cell_updates() / std::max(wall, 1e-9);
    res.volume_start = o.state.volume_start;
    res.volume_end = solver.volume();
    const SolverStats stats = solver.stats();
    res.negative_depth_fixes = stats.negative_depth_fixes;
    res.positivity_redos = stats.positivity_redos;
    res.outflow_limits = stats.outflow_limits;
    res.dry_skipped_fraction = stats.cell_stages_dry / std::max(stats.cell_stages, 1.0);
    return res;
}

// The file's last parts (the gauges, maxima and runup), then its final name.
void finish_run(const Scene& scene, const RunDef& run, RunOutput& o) {
    o.gauges.flush(*o.writer);
    o.writer->write_summary(o.sum.max_depth, o.sum.max_speed, o.sum.arrival);
    o.writer->write_runup(runup_summary(o.win.grid, window_bed(scene, o.win), o.sum.max_depth, run.flood_depth));
    o.writer->close();
    if (o.outline) o.outline->commit();
    o.file.commit();
    std::filesystem::remove(o.checkpoint);
}

RunResult run_with(RunSolver& solver, const Scene& scene, const RunDef& run, const PhysicsDef& def) {
    const std::string ckpt = checkpoint_path(run.out_file);
    if (!run.restart && std::filesystem::exists(ckpt))
        fail(ckpt, "",
             "holds an interrupted run of " + run.out_file + ": continue it with --restart, or remove " + ckpt + " and " +
                 run.out_file + ".part to start afresh");
    RunOutput o(scene, run, def);
    if (run.restart)
        resume_run(solver, o);
    else
        start_run(solver, scene, run, def, o);
    const long steps_before = o.state.steps;  // 0 unless restarted
    const double started = solver.time();
    const auto wall0 = std::chrono::steady_clock::now();
    const double cpu0 = cpu_seconds();
    Progress progress(run.label, run.duration, 10.0, run.quiet);
    long signed_steps = 0;
    try {
        signed_steps = step_to_end(solver, run, def, o, progress);
    } catch (const Error& e) {
        // A checkpoint and the partial output it continues are kept (save_checkpoint):
        // say so, so that the run can be continued once its cause is gone (a full disk).
        if (!std::filesystem::exists(o.checkpoint)) throw;
        throw Error(std::string(e.what()) + "; the run up to t = " + number_text(read_checkpoint_time(o.checkpoint)) +
                    " s is kept in " + o.checkpoint + " and " + o.file.temp_path() +
                    ": continue it with the same command and --restart, or remove both to start afresh");
    }
    const RunResult res = result_of(solver, o, signed_steps, steps_before, started,
                                    std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count(),
                                    cpu_seconds() - cpu0);
    if (!res.completed) {
        o.writer->close();
        o.file.keep_partial();
        RunResult stopped = res;
        if (std::filesystem::exists(o.checkpoint)) stopped.checkpoint_time = read_checkpoint_time(o.checkpoint);
        return stopped;
    }
    finish_run(scene, run, o);
    progress.finish(solver.time(), std::abs(signed_steps));
    RunResult done = res;
    done.file_bytes = std::filesystem::file_size(run.out_file);
    return done;
}

// The run's work, estimated before it starts (docs/reliability.md, "Every run is
// bounded"): every cell of the scene's grid updated at a step of cfl x cell / (2 (|u| +
// c)), with c = sqrt(g h) over the deepest still water plus the highest boundary level
// and |u| = c, or --max-dt when smaller, and at least one step per stored frame (steps
// land on frames); and the bytes it writes: the frames, the gauges and the boundary
// outline, uncompressed. Estimates from above (nesting and dry land make real runs
// cheaper, deflate smaller files); refused past max_cell_updates or
// max_output_bytes unless --allow-large-run.
void check_hydro_work(const RunDef& run, const PhysicsDef& physics, const Scene& scene, double highest_level) {
    double deepest = 0.0;
    for (double z : scene.z) deepest = std::max(deepest, -z);
    // No water is deeper than the oceans (a deeper state stops the run: state_checks).
    const double depth = std::clamp(deepest + highest_level, 0.01, 11000.0);
    const double cfl = run.scheme == Scheme::leapfrog ? run.leapfrog.courant : run.finite_volume.cfl;
    const double cell = std::min(scene.grid.dx, scene.grid.dy);
    const double dt_cfl = cfl * cell / (4.0 * std::sqrt(9.81 * depth));
    const double frames = double(frame_times(run.duration, run.output_interval).size());  // memory checked first
    const double dt = std::min({dt_cfl, physics.max_dt, run.duration / frames});
    const char* binding = dt == run.duration / frames ? "--output-interval" : dt == physics.max_dt ? "--max-dt" : "--duration";
    const double cells = double(scene.grid.nx) * double(scene.grid.ny);
    const double steps = run.duration / dt;
    char text[400];
    std::snprintf(text, sizeof text, "%s s of %s over %s cells of %s m (steps of about %.2g s)", number_text(run.duration).c_str(),
                  run.scene_file.c_str(), number_text(cells).c_str(), number_text(cell).c_str(), dt);
    check_work(binding, text, cells * steps, max_cell_updates, "cell updates", run.allow_large_run);
    // The bytes written: h, u, v per window cell per frame; time and 4 values per gauge
    // sample; per outline station per sample (every step with interval 0) the same.
    const Window win = make_window(scene.grid, run.window);
    const double frame_bytes = frames * double(win.grid.size()) * 3.0 * sizeof(float);
    double gauges = double(run.gauges.size());
    for (const auto& p : scene.points) gauges += p.kind == "gauge" ? 1.0 : 0.0;
    const double gauge_bytes = gauges * (run.duration / run.gauge_interval + 1.0) * 5.0 * sizeof(float);
    const BoundaryOutputDef& b = run.boundary_output;
    const double stations =
        b.file.empty() ? 0.0 : 2.0 * ((b.box[3] - b.box[2]) / scene.grid.dy + (b.box[1] - b.box[0]) / scene.grid.dx + 2.0);
    const double outline_samples = b.interval > 0.0 ? run.duration / b.interval + 1.0 : steps + 1.0;
    const double outline_bytes = stations * outline_samples * 5.0 * sizeof(float);
    struct Part {
        const char* option;
        double bytes;
        std::string what;
    };
    for (const Part& p : {Part{"--output-interval", frame_bytes,
                               number_text(frames) + " frames of " + number_text(double(win.grid.size())) + " cells"},
                          Part{"--gauge-interval", gauge_bytes, number_text(gauges) + " gauges every " + number_text(run.gauge_interval) + " s"},
                          Part{"--boundary-interval", outline_bytes,
                               number_text(std::ceil(stations)) + " outline stations " +
                                   (b.interval > 0.0 ? "every " + number_text(b.interval) + " s" : "at every step")}})
        check_work(p.option, p.what + " over " + number_text(run.duration) + " s", p.bytes, max_output_bytes,
                   "bytes written", run.allow_large_run);
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
    const std::unique_ptr<RunSolver> solver = make_run_solver(scene, run, physics);
    return run_with(*solver, scene, run, physics);
}

}  // namespace flotsam::hydro
