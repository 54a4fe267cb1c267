// The finite-volume shallow-water solver (equations and scheme: swe_kernels.hpp).
//
// Two-phase step as in TUM SWE: compute all face fluxes and sources into a rate of
// change, then update. Heun's method (SSP-RK2) gives second order in time; each stage
// is a convex combination of forward-Euler steps, so the positivity of the first-order
// step carries over.
//
// Storage: h, hu, hv, z with two ghost layers on every side, row-major, x fastest:
// the interior cell (i, j) sits at (j + 2) * (nx + 4) + (i + 2).
//
// Speed (docs/hydro.md, "Performance notes"): a stage sweeps the rows once, keeping the
// primitive values, slopes and y-face fluxes of the few rows in flight in per-thread
// row buffers, and updates each row as soon as its rates are known; cells whose whole
// stencil is exactly zero (dry land the water has not reached) are skipped, which
// gives the same bits as computing them.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "common/timeseries.hpp"
#include "formats/scene.hpp"
#include "hydro/boundary.hpp"
#include "hydro/front.hpp"
#include "hydro/physics.hpp"
#include "hydro/swe_kernels.hpp"

namespace flotsam::hydro {

// Manning friction: implicit (the scheme's) or explicit, forward Euler on the old state,
// kept only for the stability study (it reverses and blows up thin films).
enum class Friction { implicit, explicit_ };
inline constexpr EnumNames<Friction, 2> friction_names{"friction treatment",
                                                       {{{Friction::implicit, "implicit"}, {Friction::explicit_, "explicit"}}}};
constexpr const auto& enum_names(Friction) { return friction_names; }

// Dry-bed fronts: plain cell averages, or tracked (the wet fraction of the cells a front
// moves into and the invariant correction, front.hpp; Heun's stepping only): these keep a
// dry-bed front within two cells at 100-400 cells but blow up on Thacker's bowl and the
// parabola and run a film ahead of Ritter's tip on fine grids (docs/hydro.md).
enum class FrontTreatment { tracked, plain };
inline constexpr EnumNames<FrontTreatment, 2> front_treatment_names{
    "front treatment", {{{FrontTreatment::tracked, "tracked"}, {FrontTreatment::plain, "plain"}}}};
constexpr const auto& enum_names(FrontTreatment) { return front_treatment_names; }

// Time stepping: dimensionally split MUSCL-Hancock (an x sweep and a y sweep per step,
// their order alternating; split_rows.hpp) or the unsplit MUSCL scheme with Heun's
// method (swe_rows.hpp). The split step takes about twice the step for the same cfl:
// each sweep is limited by its own direction's speed.
enum class TimeStepping { split, heun };
inline constexpr EnumNames<TimeStepping, 2> time_stepping_names{
    "time stepping", {{{TimeStepping::split, "split"}, {TimeStepping::heun, "heun"}}}};
constexpr const auto& enum_names(TimeStepping) { return time_stepping_names; }

// The settings only the finite-volume scheme has (the physics: PhysicsDef).
struct FiniteVolumeDef {
    double cfl = 0.8;            // split: dt * max(a_x/dx, a_y/dy); Heun: dt * max(a_x/dx + a_y/dy) (a = |u| + c);
                                 // <= 0.5 keeps h >= 0 by itself; up to 1:
                                 // a step that would clamp a negative depth is redone (Solver::step)
    double limiter_theta = 1.3;  // 1 = minmod ... 2 = monotonised central
    int order = 2;               // 1: first order in space and time; 2: MUSCL + Heun
    // Skip cells whose whole stencil is exactly dry (h = hu = hv = 0): the same result,
    // faster. false computes every cell (the tests check that skipping changes no bit).
    bool skip_dry_land = true;
    Friction friction = Friction::implicit;  // explicit: stability study only
    FrontTreatment fronts = FrontTreatment::plain;
    TimeStepping stepping = TimeStepping::split;  // heun for the tracked fronts
};

class Solver {
public:
    Solver(const Scene& scene, const PhysicsDef& def, const FiniteVolumeDef& fv = {});

    // Largest stable step for the current state [s] (CFL and max_dt).
    double stable_dt() const;
    // Advances the state by dt [s].
    void step(double dt);

    double time() const { return time_; }
    void set_time(double t) { time_ = t; }
    const Grid& grid() const { return grid_; }
    const PhysicsDef& def() const { return def_; }
    const FiniteVolumeDef& finite_volume_def() const { return fv_; }
    const SolverStats& stats() const { return stats_; }

    // Interior cell accessors.
    std::size_t at(int i, int j) const { return std::size_t(j + 2) * stride_ + std::size_t(i + 2); }
    double depth(int i, int j) const { return h_[at(i, j)]; }
    double x_discharge(int i, int j) const { return hu_[at(i, j)]; }
    double y_discharge(int i, int j) const { return hv_[at(i, j)]; }
    double bed(int i, int j) const { return z_[at(i, j)]; }
    double level(int i, int j) const { return h_[at(i, j)] + z_[at(i, j)]; }
    double x_velocity(int i, int j) const { return velocity(h_[at(i, j)], hu_[at(i, j)], def_.dry_depth); }
    double y_velocity(int i, int j) const { return velocity(h_[at(i, j)], hv_[at(i, j)], def_.dry_depth); }
    // The part of the cell the water covers, 0..1 (front.hpp; 1 or 0 away from fronts).
    double wet_fraction(int i, int j) const { return alpha_[at(i, j)]; }
    // depth(i, j), x_velocity(i, j), y_velocity(i, j) of the cells i0 <= i < i1 of row j,
    // into h[i - i0], u[i - i0], v[i - i0] (for output and statistics over whole rows).
    void state_row(int j, int i0, int i1, double* h, double* u, double* v) const;
    // Total water volume [m^3].
    double volume() const;
    // The columns of row j outside which h, hu and hv are exactly zero (dry land the water
    // has not reached): where the last step computed, or the whole row.
    ColumnRange wet_columns(int j) const { return state_changed_outside_ ? ColumnRange{0, grid_.nx} : bound_[std::size_t(j)]; }
    // Interior cells x steps since construction.
    double cell_updates() const { return double(stats_.steps) * double(grid_.size()); }
    // The scheme in words (the flow file's `source`).
    std::string description() const;

    // Padded state, for checkpoints and output (size (nx+4)*(ny+4)). The non-const
    // accessors tell the solver that the state may change outside step(): write through
    // the reference before the next step() or stable_dt(), not after.
    std::vector<double>& depth_data() { return changed_outside(h_); }
    std::vector<double>& x_discharge_data() { return changed_outside(hu_); }
    std::vector<double>& y_discharge_data() { return changed_outside(hv_); }
    const std::vector<double>& depth_data() const { return h_; }
    const std::vector<double>& x_discharge_data() const { return hu_; }
    const std::vector<double>& y_discharge_data() const { return hv_; }
    std::size_t stride() const { return stride_; }
    std::vector<double>& wet_fraction_data() { return changed_outside(alpha_); }
    // h, hu, hv and the wet fraction (padded), the exact state for checkpoints.
    std::vector<std::vector<double>*> state_arrays() {
        return {&depth_data(), &x_discharge_data(), &y_discharge_data(), &wet_fraction_data(), &sweep_order_};
    }

    // Nesting (hydro/nesting.hpp), west and east sides only. Ghost values of a `nested`
    // side: the state `a` at time t0 and `b` at t1, interpolated linearly in time
    // (held outside [t0, t1]).
    void set_nested_ghosts(Side side, double t0, const GhostState& a, double t1, const GhostState& b);
    // Bed [m] in the ghost cells of a side, layout as GhostState (replaces the copy of
    // the edge cells, so that a nested side sees the other grid's ground).
    void set_ghost_bed(Side side, const std::vector<double>& z);
    // Volume per unit length that crossed each face of a west/east side since the last
    // reset, positive toward +x, per cell row [m^2]: the time integral of the mass flux
    // with the weights of the time stepper (for refluxing between nested grids).
    const std::vector<double>& side_transfer(Side side) const { return side == Side::west ? west_transfer_ : east_transfer_; }
    void reset_side_transfer();
    // Adds dh[j] [m] to the depth of row j's cell at a west or east side (refluxing a time
    // interface, nesting.hpp), setting a depth below 0 to 0; returns the water that made
    // [m^3]. Unlike a change through depth_data(), it updates what the solver knows of its
    // state (wet columns, wet fractions, CFL rate) for that column only, so a large slab
    // refluxed every step is not scanned whole at its next step.
    double add_side_depth(Side side, const std::vector<double>& dh, long& clamps);

    // Level at the pump side when pumping stopped (restart state of the pump boundary).
    double pump_level_at_stop() const { return forcing_.pump_level_at_stop(); }
    void set_pump_level_at_stop(double v) { forcing_.set_pump_level_at_stop(v); }

private:
    enum class Stage { predictor, corrector };
    // Ghost cells of (h, hu, hv) at time t.
    void fill_ghosts(std::vector<double>& h, std::vector<double>& hu, std::vector<double>& hv, double t);
    void fill_side(Side side, std::vector<double>& h, std::vector<double>& hu, std::vector<double>& hv, double t);
    // The side's forcing at t (a pump past its stop takes its level once, from the step's
    // start h_); then the ghosts of its cells k0 <= k < k1 along it (rows for west and
    // east), thread-safe.
    SideForcing side_forcing(Side side, double t);
    void fill_side_cells(Side side, const SideForcing& forcing, std::vector<double>& h, std::vector<double>& hu,
                         std::vector<double>& hv, double t, int k0, int k1) const;
    // One Heun stage at time t: predictor U1 = E(U), corrector U = (U + E(U1)) / 2, with
    // E(U) = friction(U + dt L(U)). Fused: one sweep over the rows (see solver.cpp).
    void stage(Stage which, double dt, double t);
    // Columns of each row whose rate may be nonzero in this stage, into active_.
    void find_active_columns(Stage which, const std::vector<double>& h, const std::vector<double>& hu,
                             const std::vector<double>& hv, bool pumping);
    // The same for an input known to be zero outside `bound` (whole rows with `whole_rows`).
    void find_active_columns(const std::vector<ColumnRange>& bound, bool whole_rows, const std::vector<double>& h,
                             const std::vector<double>& hu, const std::vector<double>& hv, bool pumping);
    // The split step (split_rows.hpp): two sweeps, h_ -> h1_ -> h2_, then h2_ swapped in.
    enum class Axis { x, y };
    void split_step(double dt);
    // One sweep along `axis` over dt from (h, hu, hv), nonzero within `in_bound`, into the
    // outputs; ghosts at time t; `last`: the step's second sweep (friction, CFL rate).
    void sweep(Axis axis, bool last, double dt, double t, std::vector<double>& h, std::vector<double>& hu,
               std::vector<double>& hv, const std::vector<ColumnRange>& in_bound, bool whole_rows, std::vector<double>& h_out,
               std::vector<double>& hu_out, std::vector<double>& hv_out, std::vector<ColumnRange>& out_bound);
    // The CFL rate of one cell for the stepping in use [1/s].
    double cell_rate(double h, double hu, double hv) const;
    std::vector<double>& changed_outside(std::vector<double>& v) {
        state_changed_outside_ = true;
        max_wave_rate_ = -1.0;
        return v;
    }
    const BoundaryDef& boundary(Side s) const;

    Grid grid_;
    PhysicsDef def_;
    FiniteVolumeDef fv_;
    std::size_t stride_ = 0, rows_ = 0;
    double time_ = 0.0;
    SolverStats stats_;
    // Hot state.
    std::vector<double> h_, hu_, hv_;
    std::vector<double> h1_, hu1_, hv1_;  // Heun's intermediate stage
    std::vector<double> h2_, hu2_, hv2_;  // the corrector's output, swapped with h_ after it
    // Wet fraction (front.hpp) of h_, h1_ and h2_; the tracker and the columns it looks at.
    std::vector<double> alpha_, alpha1_, alpha2_;
    FrontTracker front_;
    std::vector<std::vector<double>> work_;   // per thread: the row buffers of stage()
    std::vector<double> cumulative_columns_;  // columns to compute below each row (splits rows over threads)
    // Skipping dry land (solver.cpp). Per interior row: the columns outside which h_
    // (bound_), h1_ (bound1_) and h2_ (bound2_) are exactly zero; those of the stage's
    // input (and base) with a nonzero h, hu or hv; the columns to compute. Per padded
    // row: the columns of the input with a nonzero depth.
    std::vector<ColumnRange> bound_, bound1_, bound2_, state_nonzero_, base_nonzero_, active_;
    std::vector<ColumnRange> depth_nonzero_;
    bool state_changed_outside_ = true;    // bound_ unknown: scan whole rows
    mutable double max_wave_rate_ = -1.0;  // max(a_x/dx + a_y/dy) of the state [1/s]; < 0: not known
    // Cold data.
    std::vector<double> z_;                    // bed [m], ghosts filled once
    std::vector<double> g_n2_;                 // g * manning_n^2 per cell
    Forcing forcing_;                          // boundary series and the pump
    std::vector<std::size_t> pump_cells_;      // padded indices of the pump's source strip (forcing_'s), row by row
    std::vector<std::size_t> pump_row_start_;  // the pump cells of interior row j: [start[j], start[j+1])
    // Steps above the positivity bound (cfl > 0.5): the boundary transfers before the
    // step (the state before it is in h2_ after it), restored and stepped again at cfl
    // 0.45 when the step clamped a negative depth.
    std::vector<double> saved_west_transfer_, saved_east_transfer_;
    void step_once(double dt);
    // The split step's order: 0, x then y; 1, y then x (alternating; part of the state).
    std::vector<double> sweep_order_ = {0.0};
    std::array<bool, 4> mirrored_{};  // per side (west, east, south, north): ghosts mirror the edge (walls, the pump)
    std::array<std::vector<double>, 4> rest_depth_;  // initial depth of each side's edge cells [m] (transmissive sides)
    // Nesting: ghost frames per x side (0 west, 1 east) and the boundary face fluxes.
    struct NestedGhosts {
        double t0 = 0.0, t1 = 0.0;
        GhostState a, b;
    };
    NestedGhosts nested_[2];
    bool track_transfer_ = false;
    std::vector<double> west_face_mass_, east_face_mass_;  // mass flux of the current stage [m^2/s]
    std::vector<double> west_stage1_, east_stage1_;        // Heun's first-stage fluxes [m^2/s]
    std::vector<double> west_transfer_, east_transfer_;    // [m^2]
};

}  // namespace flotsam::hydro
