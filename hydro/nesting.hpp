// Grids of different spacing side by side for one scene: model no more than the scene needs.
//
// In the flume the water is 0.88 m deep, so the long-wave speed sqrt(g h) ≈ 2.9 m/s sets
// the time step of the whole grid, while the flow there is a smooth, nearly 1D wave that
// a coarse grid resolves. The city, a few centimetres deep, needs the fine grid but
// tolerates a step several times longer; and where no debris goes (open sea east of a
// port) a coarser grid serves again. So: north-south slabs, west to east, each with its
// own spacing (`ratio` × the scene's, the scene's cells averaged in blocks), and per step
// of the coarsest as many sub-steps of each finer slab as its own CFL asks.
//
// Coupling across each north-south interface between a coarse and a fine slab (two-way,
// with time sub-cycling), in the order coarsest slab first:
//   1. the coarse slab steps from t to t + Δt; its ghost cells at the interface hold the
//      block averages of the fine cells next to it at t;
//   2. the fine slab sub-steps to t + Δt; its ghost cells there take the coarse level and
//      velocity (linear in y, linear in time between t and t + Δt) over the fine ghost
//      cells' own ground, so a lake at rest stays at rest across the interface;
//   3. refluxing: the coarse cells along the interface get the volume the fine faces
//      actually passed instead of the coarse face's estimate, so the total volume is
//      conserved to round-off. (Momentum is not refluxed: the momentum mismatch is of
//      the size of the interface's truncation error.)
//
// Keep each interface in water that stays wet and smooth (the flume's slope at 0.1–0.3 m
// depth is a good place): the coupling is first order there in x, and where the flow wets
// and dries ground at an interface the two grids see different shores, refluxing can
// draw more water than a coarse cell holds, and a run that makes water so is stopped
// (docs/accuracy.md, "More than two grids": through the city it did).
#pragma once
#include <string>
#include <utility>
#include <vector>

#include "formats/scene.hpp"
#include "hydro/solver.hpp"

namespace flotsam::hydro {

// The slabs, west to east: ratio[k] × the scene's spacing between interfaces x[k - 1]
// and x[k] (the scene's edges at the ends). Ratios fall from the west to the finest slab
// and rise after it; neighbours differ, the larger a multiple of the smaller. One ratio
// fewer than slabs means the scene's own grid (1) east of the last interface: {x, ratio}
// = a coarse grid west of x, the scene's grid east of it.
struct NestDef {
    std::vector<double> x{-2.0};  // interfaces [m], west to east; each moved toward its coarser slab's edge of the scene to a whole number of that slab's cells
    std::vector<int> ratio{1};    // per slab: its spacing / the scene's (1, 2, 3, 4 ...); all 1: one uniform grid, no nesting
    NestDef() = default;
    NestDef(double x1, int ratio1) : x{x1}, ratio{ratio1} {}
    NestDef(std::vector<double> xs, std::vector<int> ratios) : x(std::move(xs)), ratio(std::move(ratios)) {}
    // More than one grid (some ratio above 1).
    bool nested() const;
};
// The coarse grid's ratio along y: `ratio`, or where the scene's rows are not a multiple
// of it, the largest number below it that divides them (50 rows, ratio 4: 2), so that
// nesting works at any resolution with the flume's exact width (the coarse cells are
// then ratio x that times the scene's; 1 for a prime number of rows).
int rows_ratio(int rows, int ratio);
NestDef default_nest_def();

// Real: the precision of every slab's state (BasicSolver<Real>).
template <class Real>
class BasicNestedSolver {
public:
    using real_type = Real;
    using SlabSolver = BasicSolver<Real>;
    // `def`'s west boundary applies to the west slab, its east one to the east slab, its
    // south and north ones to every slab. A slab's cells are ratio x rows_ratio(rows,
    // ratio) scene cells. Errors (naming the option) for ratios that do not nest and for
    // interfaces that leave a slab fewer than 2 of its own cells or 2 of a coarser
    // neighbour's.
    BasicNestedSolver(const Scene& scene, const PhysicsDef& def, const FiniteVolumeDef& fv, const NestDef& nest);

    // The step of the coarsest slabs (the finer ones sub-cycle inside it) [s]: their own,
    // or a whole number of a finer slab's steps at its CFL limit when that costs fewer
    // cell-updates per simulated second (a ratio of 2.07 then gives two fine sub-steps at
    // the limit, not three at 69 % of it).
    double stable_dt() const;
    void step(double dt);

    double time() const { return time_; }
    void set_time(double t);
    const Grid& grid() const { return grid_; }  // the scene's grid (output, gauges)
    const PhysicsDef& def() const { return def_; }
    SolverStats stats() const;
    double volume() const;
    // The scene's columns of row j outside which every slab's state is exactly zero.
    ColumnRange wet_columns(int j) const;
    // Cell updates done so far (each slab's cells × its steps).
    double cell_updates() const { return cell_updates_; }
    // The scheme and the slabs in words (the flow file's `source`).
    std::string description() const;
    long fine_steps() const { return fine_steps_; }  // steps of the finest slab
    int slabs() const { return int(slabs_.size()); }
    const SlabSolver& slab(int k) const { return slabs_[std::size_t(k)].solver; }  // west to east
    const SlabSolver& coarse() const { return slab(0); }

    // The state on the scene's grid. In a coarse slab: the coarse cell's level over the
    // scene's own ground (depth ≥ 0) and the coarse cell's velocity.
    double depth(int i, int j) const;
    double bed(int i, int j) const { return z_[grid_.index(i, j)]; }
    double level(int i, int j) const { return depth(i, j) + bed(i, j); }
    double x_velocity(int i, int j) const;
    double y_velocity(int i, int j) const;
    // The three above for the cells i0 <= i < i1 of row j (as Solver::state_row).
    void state_row(int j, int i0, int i1, double* h, double* u, double* v) const;

    double pump_level_at_stop() const { return slabs_.front().solver.pump_level_at_stop(); }
    void set_pump_level_at_stop(double v) { slabs_.front().solver.set_pump_level_at_stop(v); }
    // Each slab's exact state (BasicSolver::state_arrays), west to east, for checkpoints.
    std::vector<StateArray> state_arrays();
    long reflux_clamps() const { return reflux_clamps_; }  // interface cells refluxed below h = 0

private:
    struct Slab {
        int i0, i1;  // scene columns [i0, i1)
        int rx, ry;  // scene cells per cell along x and y
        SlabSolver solver;
    };
    // An interface between slabs `west` and `east` = west + 1; the coarse one's ghosts there
    // are the fine one's block averages, the fine one's the coarse level over their own
    // ground (layer by layer, as GhostState).
    struct Interface {
        int west = 0;
        // A time interface: both slabs have the same cells (the finest), and the one that
        // takes fewer sub-steps in a step is its "coarse" side, chosen every step
        // (NestedSolver::step); its ghosts are the other's cells, copied.
        bool same_grid = false;
        bool coarse_west = true;
        int rx = 1, ry = 1;  // coarse cells per fine cell
        std::vector<double> fine_bed, coarse_bed;  // ghost ground of each side
        GhostState before;  // the fine side's ghosts at the start of the step
        int coarse() const { return coarse_west ? west : west + 1; }
        int fine() const { return coarse_west ? west + 1 : west; }
        Side coarse_side() const { return coarse_west ? Side::east : Side::west; }
        Side fine_side() const { return coarse_west ? Side::west : Side::east; }
    };
    GhostState fine_ghosts_from_coarse(const Interface& f) const;
    // A time interface's ghosts: the cells of the slab west (from_west) or east of it.
    GhostState copied_ghosts(const Interface& f, bool from_west) const;
    // The stepping order and the time interfaces' coarse sides for a step of dt.
    void order_for_step(double dt);
    GhostState coarse_ghosts_from_fine(const Interface& f) const;
    void reflux(const Interface& f);
    const Slab& slab_of(int i) const;  // the slab holding scene column i

    Grid grid_;
    PhysicsDef def_;
    std::vector<double> z_;  // scene bed [m]
    std::vector<Slab> slabs_;
    std::vector<Interface> interfaces_;
    std::vector<int> order_;  // slabs by ratio, coarsest first (west first among equals; by sub-steps with time interfaces)
    bool time_interfaces_ = false;  // some neighbours have the same cells (order_for_step)
    int coarsest_ = 1, finest_ = 1;
    double time_ = 0.0;
    double cell_updates_ = 0.0;
    long fine_steps_ = 0;
    long reflux_clamps_ = 0;
    double reflux_made_ = 0.0;   // water made by clamping refluxed cells at 0 [m^3]
    double volume_start_ = 0.0;  // [m^3]
};

using NestedSolver = BasicNestedSolver<double>;
using NestedSolver32 = BasicNestedSolver<float>;

}  // namespace flotsam::hydro
