// The staggered leap-frog shallow-water solver (`--scheme leapfrog`): the scheme family
// of the paper's STOC-ML and of the classic tsunami codes (TUNAMI, COMCOT), beside the
// finite-volume one (solver.hpp). Same equations (docs/hydro.md, "Equations"), with h depth, z bed,
// eta = h + z, (u, v) velocity:
//
//   h_t + (hu)_x + (hv)_y = 0
//   (hu)_t + (hu u)_x + (hv u)_y + g h eta_x = -g n^2 u |u| / h^(1/3)
//   (hv)_t + (hu v)_x + (hv v)_y + g h eta_y = -g n^2 v |u| / h^(1/3)
//
// (g h z_x + (g h^2/2)_x = g h eta_x: pressure and bed slope in one term.)
//
// Space: a C-grid. h and z at cell centres (i, j); u and the discharge M = h* u on the
// x-faces (i-1/2, j); v and N = h* v on the y-faces (i, j-1/2). Each face has a
// momentum cell reaching from centre to centre. Time: leap-frog, the velocities half a
// step behind the depth (forward-backward). One step from t^n:
//
//   1. momentum, on every open face (face_open: the side with the higher level is wet
//      and that level stands above the higher ground), from h^n, u^(n-1/2) and the
//      discharges M, N of the previous step:
//        hb (u' - u) / dt = -g hb (eta_R - eta_L) / dx + sum over the 4 sides of q_in (u_beyond - u) / spacing
//        u^(n+1/2) = u' / (1 + dt g n^2 |u| / hb^(4/3))
//      hb = (h_L + h_R) / 2 is the face's depth; on a flat bed g hb (eta_R - eta_L) is
//      exactly the difference of g h^2/2. The advection is the momentum-conservative
//      first-order upwind form of Stelling & Duinmeijer (2003, Int. J. Numer. Meth.
//      Fluids 43:1329): at each side of the momentum cell the mean of the two
//      discharges there, where it flows in (q_in), brings the velocity of the face
//      beyond; with d(hb)/dt from continuity this conserves hb u, so bores run at the
//      right speed. Friction is semi-implicit as in the classic codes (old speed, v
//      averaged onto the x-face): a factor in (0, 1] that never reverses a face.
//   2. discharges M = h* u^(n+1/2): h* (upstream_depth) is the level of the upstream
//      cell above the higher ground, the classic codes' wet/dry rule ("the level of the
//      wet side above the higher ground") used on every face. Upwinding the depth is
//      what damps the mass equation: a variant that stepped M itself with the mean
//      depth, TUNAMI's form, leaves oscillations of half the jump behind the wet dam
//      break's bore and a stalled dry front.
//   3. outflow limiter: a cell whose outgoing discharges would take more water than it
//      holds has them (and their velocities) scaled down to take exactly what it holds.
//      Classic codes clamp h at 0 after the fact, which creates water; this keeps
//      h >= 0 and conserves mass. Limited cell-steps are counted in
//      SolverStats::outflow_limits.
//   4. continuity with the new discharges:
//        h^(n+1) = h^n - dt [(M_(i+1/2) - M_(i-1/2)) / dx + (N_(j+1/2) - N_(j-1/2)) / dy]
//
// Linear stability (the forward-backward C-grid at rest): c dt sqrt(1/dx^2 + 1/dy^2) <= 1
// with c = sqrt(g h). The step is fixed: from `courant` and the initial state's largest
// Courant rate (the deepest water, and |u| + c per direction where the scene starts
// moving), shortened to divide the output interval so frames land on steps. Every step
// checks the Courant number of the new state, which adds the flow speed to c per
// direction (leapfrog_kernels.hpp: courant_number), and fails naming --courant if it
// passes 1: a changing step would break the leap-frog's half-step stagger.
//
// Stagger in the stored state: after a step to t, h is at t and u, v, M, N at t - dt/2.
// The velocities reported at cell centres (the mean of the two faces') lag the depth by
// half a step (e.g. 3.4 ms at 4 cm): far below anything stage two resolves.
//
// Boundaries (the same BoundaryDef kinds as the finite-volume solver): a wall closes
// its faces; a level, discharge or transmissive side gives its boundary faces the
// velocity u_b and discharge h_b u_b of the characteristic state at the side
// (boundary.hpp: open_side_state), transmissive being "no incoming wave" on the side's
// initial depth. On a C-grid a zero-gradient ghost would freeze the boundary face and
// reflect waves, so transmissive here is the classic codes' radiation condition
// (M = c eta) in its nonlinear form. The pump is the same source strip and level.
//
// The one dry tolerance is PhysicsDef::dry_depth: a cell with h <= dry_depth sends no
// flux, a face opens only where the higher level stands more than dry_depth above the
// higher ground, and a face whose mean depth is below it has no velocity.
#pragma once
#include <array>
#include <string>
#include <vector>

#include "formats/scene.hpp"
#include "hydro/boundary.hpp"
#include "hydro/column_range.hpp"
#include "hydro/physics.hpp"

namespace flotsam::hydro {

struct LeapfrogDef {
    // Courant number of the fixed step: dt sqrt(g h_max) sqrt(1/dx^2 + 1/dy^2), with h_max
    // the deepest water at the start (and of a level boundary), or where the scene starts
    // moving, dt sqrt(((|u| + c)/dx)^2 + ((|v| + c)/dy)^2) if larger. Linear limit: 1.
    double courant = 0.7;       // [-]
    double step_divides = 0.0;  // [s] shorten the step to divide this (the output interval); 0: no
};
LeapfrogDef default_leapfrog_def();

class LeapfrogSolver {
public:
    // Nested boundaries are refused.
    LeapfrogSolver(const Scene& scene, const PhysicsDef& def, const LeapfrogDef& leapfrog);

    // The fixed step [s].
    double stable_dt() const { return dt_; }
    // Advances by dt [s] (the fixed step, or a shorter one to land on a time).
    void step(double dt);

    double time() const { return time_; }
    void set_time(double t) { time_ = t; }
    const Grid& grid() const { return grid_; }
    const PhysicsDef& def() const { return def_; }
    const LeapfrogDef& leapfrog_def() const { return lf_; }
    const SolverStats& stats() const { return stats_; }
    // Largest Courant number (courant_number) of any cell after any step so far.
    double max_courant_seen() const { return max_courant_; }

    std::size_t at(int i, int j) const { return std::size_t(j + 1) * stride_ + std::size_t(i + 1); }
    double depth(int i, int j) const { return h_[at(i, j)]; }
    double bed(int i, int j) const { return z_[at(i, j)]; }
    double level(int i, int j) const { return h_[at(i, j)] + z_[at(i, j)]; }
    // Discharge through the west x-face of cell (i, j), i = 0 .. nx, over the last step [m^2/s].
    double x_face_discharge(int i, int j) const { return m_[at(i, j)]; }
    // Discharge through the south y-face of cell (i, j), j = 0 .. ny [m^2/s].
    double y_face_discharge(int i, int j) const { return n_[at(i, j)]; }
    // Cell-centre velocities [m/s]: the mean of the two faces', half a step behind the depth; 0 where dry.
    double x_velocity(int i, int j) const { return h_[at(i, j)] > def_.dry_depth ? 0.5 * (u_[at(i, j)] + u_[at(i + 1, j)]) : 0.0; }
    double y_velocity(int i, int j) const { return h_[at(i, j)] > def_.dry_depth ? 0.5 * (v_[at(i, j)] + v_[at(i, j + 1)]) : 0.0; }
    // depth(i, j), x_velocity(i, j), y_velocity(i, j) of the cells i0 <= i < i1 of row j (as Solver::state_row).
    void state_row(int j, int i0, int i1, double* h, double* u, double* v) const {
        for (int i = i0; i < i1; ++i) {
            h[i - i0] = depth(i, j);
            u[i - i0] = x_velocity(i, j);
            v[i - i0] = y_velocity(i, j);
        }
    }
    double volume() const;  // [m^3]
    // The columns of row j outside which the state is exactly zero: here, the whole row.
    ColumnRange wet_columns(int) const { return {0, grid_.nx}; }
    // Interior cells x steps since construction.
    double cell_updates() const { return double(stats_.steps) * double(grid_.size()); }
    // The scheme in words, with its fixed step (the flow file's `source`).
    std::string description() const;

    double pump_level_at_stop() const { return forcing_.pump_level_at_stop(); }
    void set_pump_level_at_stop(double v) { forcing_.set_pump_level_at_stop(v); }
    // h, u, v, M, N (padded, one ghost layer), for checkpoints.
    std::vector<StateArray> state_arrays() { return {&h_, &u_, &v_, &m_, &n_}; }

private:
    std::size_t edge_cell(Side s, int k) const;  // padded index of the k-th cell along side s
    // The start, in the order the constructor takes it: bed, friction and initial depths of
    // every cell (ghosts copy the edge), returning the deepest water [m]; the scene's u0,
    // v0 on the open interior faces (the mean of the two cells); each side's edge depths,
    // returning `deepest` raised to the deepest water a level side brings (its highest
    // level over its deepest edge cell); the fixed step [s].
    double initial_cells(const Scene& scene);
    void initial_face_velocities(const Scene& scene);
    double record_rest_depths(double deepest);
    double initial_step(const Scene& scene, double deepest) const;
    void boundary_faces(double t);
    void momentum(double dt);
    void limit_outflow(double dt);
    void continuity(double dt);

    Grid grid_;
    PhysicsDef def_;
    LeapfrogDef lf_;
    Forcing forcing_;
    std::size_t stride_ = 0;
    double dt_ = 0.0;
    double time_ = 0.0;
    double max_courant_ = 0.0;
    SolverStats stats_;
    // Hot state: depth at centres; velocities and discharges on the faces (x-faces
    // i = 0..nx, y-faces j = 0..ny of the padded arrays). Ghost rows of u_ and ghost
    // columns of v_ copy the edge (tangential zero gradient, a slip wall).
    std::vector<double> h_, u_, v_, m_, n_;
    std::vector<double> u_new_, v_new_, m_new_, n_new_;  // the step's new values
    std::vector<double> factor_;                         // outflow factor per cell (1 in ghosts)
    // Cold data.
    std::vector<double> z_;                          // bed [m]; ghosts copy the edge
    std::vector<double> g_n2_;                       // g n^2 per cell
    std::array<std::vector<double>, 4> rest_depth_;  // initial depth of each side's edge cells [m] (transmissive sides)
};

}  // namespace flotsam::hydro
