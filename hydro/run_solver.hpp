// The solver of a run behind one interface: the run driver (run.cpp, run_steps.cpp) steps,
// samples, stores and checkpoints any scheme, nesting and precision through RunSolver,
// and make_run_solver builds the one a run asks for.
#pragma once
#include <concepts>
#include <memory>
#include <string>
#include <vector>

#include "common/grid.hpp"
#include "formats/scene.hpp"
#include "hydro/column_range.hpp"
#include "hydro/physics.hpp"

namespace flotsam::hydro {

struct RunDef;

// What the run driver needs of a solver: stepping, the state for frames, gauges and
// maxima, the exact state for checkpoints, and how to describe itself.
template <class S>
concept RunnableSolver = requires(S& s, const S& c, double t, int i, int j, double* row) {
    { c.stable_dt() } -> std::same_as<double>;         // the step to take now [s]
    s.step(t);                                         // advance by t [s]
    { c.time() } -> std::same_as<double>;              // [s]
    s.set_time(t);                                     // land exactly on a frame time
    { c.grid() } -> std::convertible_to<const Grid&>;  // the scene's grid (output, gauges)
    { c.level(i, j) } -> std::same_as<double>;         // [m], gauges
    { c.depth(i, j) } -> std::same_as<double>;         // [m]
    { c.x_velocity(i, j) } -> std::same_as<double>;    // [m/s]
    { c.y_velocity(i, j) } -> std::same_as<double>;    // [m/s]
    c.state_row(j, i, i, row, row, row);               // depth, velocities of a row (frames, maxima)
    { c.wet_columns(j) } -> std::same_as<ColumnRange>;  // outside them row j's state is exactly zero
    { c.volume() } -> std::same_as<double>;            // [m^3]
    { c.stats() } -> std::convertible_to<SolverStats>;
    { c.cell_updates() } -> std::same_as<double>;                   // cells x steps done by this object
    { s.state_arrays() } -> std::same_as<std::vector<StateArray>>;  // the exact state (checkpoints)
    { c.pump_level_at_stop() } -> std::same_as<double>;             // the pump side's restart state [m]
    s.set_pump_level_at_stop(t);
    { c.description() } -> std::same_as<std::string>;  // the scheme, for the file's `source`
};

// A RunnableSolver as a virtual interface: the driver is compiled once, not per solver
// type (a few calls per step and per row, nothing per cell).
class RunSolver {
public:
    virtual ~RunSolver() = default;
    virtual double stable_dt() const = 0;
    virtual void step(double dt) = 0;
    virtual double time() const = 0;
    virtual void set_time(double t) = 0;
    virtual const Grid& grid() const = 0;
    virtual double level(int i, int j) const = 0;
    virtual double depth(int i, int j) const = 0;
    virtual double x_velocity(int i, int j) const = 0;
    virtual double y_velocity(int i, int j) const = 0;
    virtual void state_row(int j, int i0, int i1, double* h, double* u, double* v) const = 0;
    virtual ColumnRange wet_columns(int j) const = 0;
    virtual double volume() const = 0;
    virtual SolverStats stats() const = 0;
    virtual double cell_updates() const = 0;
    virtual std::vector<StateArray> state_arrays() = 0;
    virtual double pump_level_at_stop() const = 0;
    virtual void set_pump_level_at_stop(double v) = 0;
    virtual std::string description() const = 0;
};

// The solver `run` asks for on `scene`: the leap-frog, or finite volumes in the run's
// precision, nested or on the scene's grid. Errors name the option (the leap-frog refuses
// nesting).
std::unique_ptr<RunSolver> make_run_solver(const Scene& scene, const RunDef& run, const PhysicsDef& physics);

}  // namespace flotsam::hydro
