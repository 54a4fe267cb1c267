// The stepping loop of a hydro run (run_driver.hpp): a step at a time to the last frame,
// the gauges, boundary outline and maxima after every step, a frame at every frame time,
// checkpoints and stops on frames.
#include <chrono>
#include <cmath>

#include "common/checks.hpp"
#include "common/error.hpp"
#include "hydro/run_driver.hpp"
#include "hydro/state_checks.hpp"

namespace flotsam::hydro {

volatile std::sig_atomic_t stop_signal = 0;

namespace {

// After a signal, the longest the run goes on to reach its next frame [s of wall time]:
// there it writes a checkpoint, and --restart continues it; a frame further off (a slow
// or stalled step) is not waited for, and the run stops at once with its last
// checkpoint, if any, and its partial output as they are.
constexpr double stop_wait_wall = 1.0;

class StepLoop {
public:
    StepLoop(RunSolver& solver, const RunDef& run, const PhysicsDef& def, RunOutput& o, Progress& progress)
        : s_(solver), run_(run), def_(def), o_(o), progress_(progress), steps_(o.state.steps), before_(o.gauges.read(solver)) {
        if (o.outline) outline_before_ = o.outline->read(solver);
        next_checkpoint_ = run.checkpoint_interval > 0.0 ? next_multiple(solver.time(), run.checkpoint_interval) : 1e300;
    }

    long run() {
        while (o_.state.next_frame < o_.times.size()) {
            const double target = o_.times[o_.state.next_frame];
            double dt = s_.stable_dt();
            const double t0 = s_.time();
            check_step(s_, s_.grid(), run_.out_file, t0, dt, o_.state.volume_start);
            if (watch_.stalled(dt)) fail_stalled(run_.out_file, t0, dt, watch_, fastest_cell(s_, s_.grid(), def_.gravity));
            if (stop_signal != 0 && (target - t0) / dt * wall_per_step_ > stop_wait_wall) return -steps_;
            // A step that would stop within a millionth of itself short of the frame goes to
            // it (a fixed step that divides the interval lands there despite round-off in t).
            const bool reaches = t0 + dt >= target - 1e-6 * dt;
            if (reaches) dt = target - t0;
            s_.step(dt);
            if (reaches) s_.set_time(target);  // land exactly on the frame time
            ++steps_;
            const double t1 = s_.time();
            record_samples(t0, t1);
            if (reaches) store_frame(t1);
            if (checkpoint_or_stop(reaches, t1)) return -steps_;
            time_the_step();
            progress_.update(t1, dt, steps_);
        }
        return steps_;
    }

private:
    static double next_multiple(double t, double interval) { return (std::floor(t / interval + 1e-9) + 1.0) * interval; }

    // The gauges and the boundary outline between the step's two states, and the maxima.
    void record_samples(double t0, double t1) {
        auto after = o_.gauges.read(s_);
        o_.gauges.record(t0, before_, t1, after);
        before_ = std::move(after);
        if (o_.outline) {
            auto outline_after = o_.outline->read(s_);
            o_.outline->record(t0, outline_before_, t1, outline_after);
            outline_before_ = std::move(outline_after);
        }
        accumulate(o_.sum, s_, o_.win, t1, run_.arrival_depth);
    }

    // The frame at t1 after the state is checked (never write NaN), with the gauges and
    // the outline so far, synced: a full disk shows here, at this frame, not at the end.
    void store_frame(double t1) {
        check_state(s_, s_.grid(), run_.out_file, t1, o_.state.volume_start);
        try {
            write_frame(*o_.writer, o_.state.next_frame, s_, o_.win);
            o_.gauges.flush(*o_.writer);
            if (o_.outline) o_.outline->flush();
            o_.writer->sync();
        } catch (const Error& e) {
            throw Error(std::string(e.what()) + "; while writing frame " + std::to_string(o_.state.next_frame) +
                        " (t = " + number_text(t1) + " s)");
        }
        ++o_.state.next_frame;
    }

    // Checkpoints and stops fall on stored frames, and every frame ends with a sync: the
    // file then has the same bytes (HDF5's layout included) whether the run was
    // checkpointed, stopped and restarted, or never interrupted. Not at frame 1, though: a
    // run continued from there has the same values but a file 1 kB smaller (libhdf5 leaves
    // 1 kB unused in the uninterrupted run, h5stat's "unaccounted space"), so the first
    // checkpoint or stop waits for frame 2. True when the run stops here.
    bool checkpoint_or_stop(bool on_frame, double t1) {
        const bool stop = (run_.stop_after >= 0.0 && t1 >= run_.stop_after) || stop_signal != 0;
        if (!on_frame || o_.state.next_frame <= 2 || !(t1 >= next_checkpoint_ - 1e-12 || stop)) return false;
        save_checkpoint(s_, def_, o_, t1, steps_);
        if (run_.checkpoint_interval > 0.0) next_checkpoint_ = next_multiple(t1, run_.checkpoint_interval);
        return stop;
    }

    // A running mean of the steps' wall time, for how long a signal may wait for a frame.
    void time_the_step() {
        const auto now = Clock::now();
        wall_per_step_ = 0.9 * wall_per_step_ + 0.1 * std::chrono::duration<double>(now - last_step_end_).count();
        last_step_end_ = now;
    }

    using Clock = std::chrono::steady_clock;
    RunSolver& s_;
    const RunDef& run_;
    const PhysicsDef& def_;
    RunOutput& o_;
    Progress& progress_;
    long steps_;
    std::vector<GaugeSample> before_;
    std::vector<PointSample> outline_before_;
    double next_checkpoint_ = 1e300;
    StepWatch watch_;
    Clock::time_point last_step_end_ = Clock::now();
    double wall_per_step_ = 0.0;  // [s]
};

}  // namespace

long step_to_end(RunSolver& solver, const RunDef& run, const PhysicsDef& def, RunOutput& o, Progress& progress) {
    return StepLoop(solver, run, def, o, progress).run();
}

}  // namespace flotsam::hydro
