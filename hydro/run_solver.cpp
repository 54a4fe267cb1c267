// The solvers of a run behind RunSolver (run_solver.hpp).
#include "hydro/run_solver.hpp"

#include <utility>

#include "common/error.hpp"
#include "hydro/leapfrog.hpp"
#include "hydro/nesting.hpp"
#include "hydro/run.hpp"
#include "hydro/solver.hpp"

namespace flotsam::hydro {

namespace {

template <RunnableSolver S>
class RunSolverOf final : public RunSolver {
public:
    template <class... Args>
    explicit RunSolverOf(Args&&... args) : s_(std::forward<Args>(args)...) {}
    double stable_dt() const override { return s_.stable_dt(); }
    void step(double dt) override { s_.step(dt); }
    double time() const override { return s_.time(); }
    void set_time(double t) override { s_.set_time(t); }
    const Grid& grid() const override { return s_.grid(); }
    double level(int i, int j) const override { return s_.level(i, j); }
    double depth(int i, int j) const override { return s_.depth(i, j); }
    double x_velocity(int i, int j) const override { return s_.x_velocity(i, j); }
    double y_velocity(int i, int j) const override { return s_.y_velocity(i, j); }
    void state_row(int j, int i0, int i1, double* h, double* u, double* v) const override { s_.state_row(j, i0, i1, h, u, v); }
    ColumnRange wet_columns(int j) const override { return s_.wet_columns(j); }
    double volume() const override { return s_.volume(); }
    SolverStats stats() const override { return s_.stats(); }
    double cell_updates() const override { return s_.cell_updates(); }
    std::vector<StateArray> state_arrays() override { return s_.state_arrays(); }
    double pump_level_at_stop() const override { return s_.pump_level_at_stop(); }
    void set_pump_level_at_stop(double v) override { s_.set_pump_level_at_stop(v); }
    std::string description() const override { return s_.description(); }

private:
    S s_;
};

// Finite volumes in precision Real, nested or not.
template <class Real>
std::unique_ptr<RunSolver> finite_volume_solver(const Scene& scene, const RunDef& run, const PhysicsDef& physics) {
    if (run.nest.nested())
        return std::make_unique<RunSolverOf<BasicNestedSolver<Real>>>(scene, physics, run.finite_volume, run.nest);
    return std::make_unique<RunSolverOf<BasicSolver<Real>>>(scene, physics, run.finite_volume);
}

}  // namespace

std::unique_ptr<RunSolver> make_run_solver(const Scene& scene, const RunDef& run, const PhysicsDef& physics) {
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
        return std::make_unique<RunSolverOf<LeapfrogSolver>>(scene, physics, lf);
    }
    if (run.finite_volume.precision == Precision::float32) return finite_volume_solver<float>(scene, run, physics);
    return finite_volume_solver<double>(scene, run, physics);
}

}  // namespace flotsam::hydro
