// Two grids for one scene: model no more than the scene needs.
//
// In the flume the water is 0.88 m deep, so the long-wave speed sqrt(g h) ≈ 2.9 m/s sets
// the time step of the whole grid, while the flow there is a smooth, nearly 1D wave that
// a coarse grid resolves. The city, a few centimetres deep, needs the fine grid but
// tolerates a step several times longer. So: a coarse grid (`ratio` × the scene's
// spacing, the scene's cells averaged in blocks) west of x = `x`, the scene's own grid
// east of it, and per coarse step as many fine sub-steps as the fine grid's CFL asks.
//
// Coupling across the north-south interface (two-way, with time sub-cycling):
//   1. the coarse grid steps from t to t + Δt; its east ghost cells hold the block
//      averages of the fine cells next to the interface at t;
//   2. the fine grid sub-steps to t + Δt; its west ghost cells take the coarse level
//      and velocity (linear in y, linear in time between t and t + Δt) over the fine
//      ghost cells' own ground, so a lake at rest stays at rest across the interface;
//   3. refluxing: the coarse cells along the interface get the volume the fine faces
//      actually passed instead of the coarse face's estimate, so the total volume is
//      conserved to round-off. (Momentum is not refluxed: the momentum mismatch is of
//      the size of the interface's truncation error.)
//
// Keep the interface in water that stays wet and smooth (the flume's slope at
// 0.2–0.3 m depth is a good place): the coupling is first order there in x.
#pragma once
#include <string>
#include <vector>

#include "formats/scene.hpp"
#include "hydro/solver.hpp"

namespace flotsam::hydro {

struct NestDef {
    double x = -2.0;  // interface [m]; moved west to the nearest multiple of `ratio` cells
    int ratio = 1;    // coarse spacing / scene spacing (2, 3, 4 ...); 1: one uniform grid, no nesting
};
// The coarse grid's ratio along y: `ratio`, or where the scene's rows are not a multiple
// of it, the largest number below it that divides them (50 rows, ratio 4: 2), so that
// nesting works at any resolution with the flume's exact width (the coarse cells are
// then ratio x that times the scene's; 1 for a prime number of rows).
int rows_ratio(int rows, int ratio);
NestDef default_nest_def();

class NestedSolver {
public:
    // `def`'s west/south/north boundaries apply to the coarse grid, its east/south/north
    // ones to the fine grid. The coarse cells are nest.ratio x rows_ratio(rows, ratio)
    // scene cells. Errors (naming the option) when the interface leaves fewer than 2
    // coarse or 2 × ratio fine columns.
    NestedSolver(const Scene& scene, const PhysicsDef& def, const FiniteVolumeDef& fv, const NestDef& nest);

    // The coarse step (the fine grid sub-cycles inside it) [s]: the coarse grid's own, or
    // a whole number of fine steps at their CFL limit when that costs fewer cell-updates
    // per simulated second (a ratio of 2.07 then gives two fine sub-steps at the limit,
    // not three at 69 % of it).
    double stable_dt() const;
    void step(double dt);

    double time() const { return time_; }
    void set_time(double t);
    const Grid& grid() const { return grid_; }  // the scene's grid (output, gauges)
    const PhysicsDef& def() const { return def_; }
    SolverStats stats() const;
    double volume() const { return coarse_.volume() + fine_.volume(); }
    // Cell updates done so far (coarse cells × coarse steps + fine cells × fine steps).
    double cell_updates() const { return cell_updates_; }
    // The scheme and the two grids in words (the flow file's `source`).
    std::string description() const;
    long fine_steps() const { return fine_steps_; }
    int interface_column() const { return i_nest_; }  // first fine column on the scene grid
    const Solver& coarse() const { return coarse_; }
    const Solver& fine() const { return fine_; }

    // The state on the scene's grid. West of the interface: the coarse cell's level over
    // the scene's own ground (depth ≥ 0) and the coarse cell's velocity.
    double depth(int i, int j) const;
    double bed(int i, int j) const { return z_[grid_.index(i, j)]; }
    double level(int i, int j) const { return depth(i, j) + bed(i, j); }
    double x_velocity(int i, int j) const;
    double y_velocity(int i, int j) const;
    // The three above for the cells i0 <= i < i1 of row j (as Solver::state_row).
    void state_row(int j, int i0, int i1, double* h, double* u, double* v) const;

    double pump_level_at_stop() const { return coarse_.pump_level_at_stop(); }
    void set_pump_level_at_stop(double v) { coarse_.set_pump_level_at_stop(v); }
    // The coarse then the fine grid's exact state (Solver::state_arrays), for checkpoints.
    std::vector<std::vector<double>*> state_arrays() {
        std::vector<std::vector<double>*> a = coarse_.state_arrays();
        for (std::vector<double>* v : fine_.state_arrays()) a.push_back(v);
        return a;
    }
    long reflux_clamps() const { return reflux_clamps_; }  // interface cells refluxed below h = 0

private:
    GhostState fine_ghosts_from_coarse() const;
    GhostState coarse_ghosts_from_fine() const;
    void reflux();

    Grid grid_;
    PhysicsDef def_;
    int rx_ = 1, ry_ = 1, i_nest_ = 0;  // coarse cells along x and y per scene cell; first fine column
    std::vector<double> z_;             // scene bed [m]
    Solver coarse_, fine_;
    double time_ = 0.0;
    double cell_updates_ = 0.0;
    long fine_steps_ = 0;
    long reflux_clamps_ = 0;
};

}  // namespace flotsam::hydro
