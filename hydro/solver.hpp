// The finite-volume shallow-water solver (equations and scheme: swe_kernels.hpp; the
// split step, the default: split_rows.hpp).
//
// The split step: an x sweep and a y sweep of MUSCL-Hancock, their order alternating
// (split_step.cpp). Heun's step (`--time-stepping heun`): two stages, each computing all
// face fluxes and sources into a rate of change, then updating (SSP-RK2: each stage a
// convex combination of forward-Euler steps, so the positivity of the first-order step
// carries over; heun_stage.cpp).
//
// Storage: h, hu, hv, z with two ghost layers on every side, row-major, x fastest:
// the interior cell (i, j) sits at (j + 2) * (nx + 4) + (i + 2). The state and the
// arithmetic of the row kernels are of type Real: BasicSolver<float> (`--precision
// float32`) or BasicSolver<double> (Solver); time, steps, boundary values and the sums a
// run reports are double in both.
//
// Speed (docs/hydro.md, "Cost"): a stage or sweep passes over the rows once, keeping the
// primitive values, slopes and y-face fluxes of the few rows in flight in per-thread
// row buffers, and updates each row as soon as its rates are known; cells whose whole
// stencil is exactly zero (dry land the water has not reached) are skipped, which
// gives the same bits as computing them.
#pragma once
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
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

// The type of the state and of the row kernels' arithmetic. float32 halves the bytes of
// the state and doubles the cells per vector instruction; its round-off (1e-7 of the
// depth) is far below what a grid resolves (docs/studies/hydro_speed_levers.md).
enum class Precision { float32, float64 };
inline constexpr EnumNames<Precision, 2> precision_names{
    "precision", {{{Precision::float32, "float32"}, {Precision::float64, "float64"}}}};
constexpr const auto& enum_names(Precision) { return precision_names; }

// The settings only the finite-volume scheme has (the physics: PhysicsDef).
struct FiniteVolumeDef {
    double cfl = 0.8;            // split: dt * max(a_x/dx, a_y/dy); Heun: dt * max(a_x/dx + a_y/dy) (a = |u| + c);
                                 // <= 0.5 keeps h >= 0 by itself; up to 1:
                                 // a step that would clamp a negative depth is redone (BasicSolver::step)
    double limiter_theta = 1.3;  // 1 = minmod ... 2 = monotonised central
    int order = 2;               // 1: first order in space and time; 2: MUSCL + Heun
    // Skip cells whose whole stencil is exactly dry (h = hu = hv = 0): the same result,
    // faster. false computes every cell (the tests check that skipping changes no bit).
    bool skip_dry_land = true;
    Friction friction = Friction::implicit;  // explicit: stability study only
    FrontTreatment fronts = FrontTreatment::plain;
    TimeStepping stepping = TimeStepping::split;  // heun for the tracked fronts
    // The state's type in a run: run_hydro builds BasicSolver<float> or <double> by it (a
    // BasicSolver's precision is its Real; tracked fronts need float64). float32 moves
    // nothing a user reads beyond the grid's own error (docs/studies/hydro_speed_levers.md).
    Precision precision = Precision::float32;
};

// The conserved state of a grid (padded arrays: two ghost layers, row-major, x fastest)
// and what is known of it.
template <class Real>
struct GridState {
    std::vector<Real> h, hu, hv;     // depth [m], discharges [m^2/s]
    std::vector<Real> wet_fraction;  // 0..1, the tracked fronts' (front.hpp); empty with plain fronts
    std::vector<ColumnRange> bound;  // per interior row: the columns outside which h, hu, hv are exactly zero
    void swap(GridState& o) noexcept {
        h.swap(o.h);
        hu.swap(o.hu);
        hv.swap(o.hv);
        wet_fraction.swap(o.wet_fraction);
        bound.swap(o.bound);
    }
};

namespace rows {
template <class Real>
struct Sweep;
template <class Real>
class RowBuffers;
}  // namespace rows

template <class Real>
class BasicSolver {
public:
    using real_type = Real;
    static constexpr Precision precision = std::is_same_v<Real, float> ? Precision::float32 : Precision::float64;

    BasicSolver(const Scene& scene, const PhysicsDef& def, const FiniteVolumeDef& fv = {});

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
    double depth(int i, int j) const { return now_.h[at(i, j)]; }
    double x_discharge(int i, int j) const { return now_.hu[at(i, j)]; }
    double y_discharge(int i, int j) const { return now_.hv[at(i, j)]; }
    double bed(int i, int j) const { return z_[at(i, j)]; }
    double level(int i, int j) const { return double(now_.h[at(i, j)]) + double(z_[at(i, j)]); }
    double x_velocity(int i, int j) const { return velocity(now_.h[at(i, j)], now_.hu[at(i, j)], Real(def_.dry_depth)); }
    double y_velocity(int i, int j) const { return velocity(now_.h[at(i, j)], now_.hv[at(i, j)], Real(def_.dry_depth)); }
    // The part of the cell the water covers, 0..1 (front.hpp; 1 or 0 away from fronts).
    double wet_fraction(int i, int j) const {
        return now_.wet_fraction.empty() ? (now_.h[at(i, j)] > 0 ? 1.0 : 0.0) : now_.wet_fraction[at(i, j)];
    }
    // depth(i, j), x_velocity(i, j), y_velocity(i, j) of the cells i0 <= i < i1 of row j,
    // into h[i - i0], u[i - i0], v[i - i0] (for output and statistics over whole rows).
    void state_row(int j, int i0, int i1, double* h, double* u, double* v) const;
    // Total water volume [m^3].
    double volume() const;
    // The columns of row j outside which h, hu and hv are exactly zero (dry land the water
    // has not reached): where the last step computed, or the whole row.
    ColumnRange wet_columns(int j) const { return state_changed_outside_ ? ColumnRange{0, grid_.nx} : now_.bound[std::size_t(j)]; }
    // Interior cells x steps since construction.
    double cell_updates() const { return double(stats_.steps) * double(grid_.size()); }
    // The scheme in words (the flow file's `source`).
    std::string description() const;

    // Padded state, for checkpoints and output (size (nx+4)*(ny+4)). The non-const
    // accessors tell the solver that the state may change outside step(): write through
    // the reference before the next step() or stable_dt(), not after.
    std::vector<Real>& depth_data() { return changed_outside(now_.h); }
    std::vector<Real>& x_discharge_data() { return changed_outside(now_.hu); }
    std::vector<Real>& y_discharge_data() { return changed_outside(now_.hv); }
    const std::vector<Real>& depth_data() const { return now_.h; }
    const std::vector<Real>& x_discharge_data() const { return now_.hu; }
    const std::vector<Real>& y_discharge_data() const { return now_.hv; }
    std::size_t stride() const { return stride_; }
    // h, hu, hv (padded), and the tracked fronts' wet fraction or the split step's sweep
    // order: the exact state for checkpoints.
    std::vector<StateArray> state_arrays() {
        std::vector<StateArray> a{&depth_data(), &x_discharge_data(), &y_discharge_data()};
        if (front_)
            a.push_back(&changed_outside(now_.wet_fraction));
        else
            a.push_back(&sweep_order_);
        return a;
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
    const std::vector<double>& side_transfer(Side side) const { return transfer_[side == Side::west ? 0 : 1]; }
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
    using State = GridState<Real>;
    using Array = std::vector<Real>;
    // The tracked fronts (front.hpp) work on double arrays: float32 refuses them.
    static constexpr bool kFronts = std::is_same_v<Real, double>;

    // Construction, in order: the definition checked, the arrays sized, the scene's
    // initial state and ground, the ghosts' ground, the sides' still water, the pump's cells.
    void check_definition() const;
    void allocate();
    void set_initial_state(const Scene& scene);
    void fill_ghost_bed();
    void record_rest_depths();
    void place_pump_cells();

    enum class Stage { predictor, corrector };
    // Ghost cells of (h, hu, hv) at time t.
    void fill_ghosts(Array& h, Array& hu, Array& hv, double t);
    void fill_side(Side side, Array& h, Array& hu, Array& hv, double t);
    // The side's forcing at t (a pump past its stop takes its level once, from the step's
    // start); then the ghosts of its cells k0 <= k < k1 along it (rows for west and
    // east), thread-safe.
    SideForcing side_forcing(Side side, double t);
    void fill_side_cells(Side side, const SideForcing& forcing, Array& h, Array& hu, Array& hv, double t, int k0, int k1) const;
    // The ghosts of a nested side's cells k0 <= k < k1, interpolated in time.
    void fill_nested_cells(Side side, Array& h, Array& hu, Array& hv, double t, int k0, int k1) const;
    // One Heun stage at time t: predictor U1 = E(U), corrector U = (U + E(U1)) / 2, with
    // E(U) = friction(U + dt L(U)). Fused: one pass over the rows (heun_stage.cpp).
    void stage(Stage which, double dt, double t);
    // What a stage reads and writes, worked out before its rows.
    struct StagePlan {
        bool corrector = false, last = false, fronts = false;
        double dt = 0.0, t_out = 0.0, pump_rate = 0.0;  // [s], [s], [m/s]
        State* in = nullptr;                            // now_ (predictor) or mid_ (corrector)
        State* out = nullptr;                           // mid_ or next_
        std::array<SideForcing, 4> out_forcing{};       // the sides at t_out (tracked fronts)
    };
    StagePlan prepare_stage(Stage which, double dt, double t);
    // The tracked fronts' work before a stage's rows (tips of its input; the grown wet fraction).
    void prepare_fronts(Stage which, StagePlan& p, double dt);
    // Rows j0 <= j < j1 of a stage, with this thread's row buffers `mem`.
    void stage_strip(const StagePlan& plan, Array& mem, int j0, int j1, long& fixes, Real& worst, Real& amax);
    void update_stage_row(const StagePlan& plan, const rows::Sweep<Real>& s, const rows::RowBuffers<Real>& w, int j,
                          ColumnRange cols, long& fixes, Real& worst, Real& amax);
    // The tracked fronts' wet fraction of a strip's first and last rows and then of the
    // whole output, once every strip is done (Heun stages with tracked fronts).
    void fix_strip_edges(const StagePlan& plan, int j0, int j1);
    // Columns of each row whose rate may be nonzero in this stage, into active_.
    void find_active_columns(Stage which, const Array& h, const Array& hu, const Array& hv, bool pumping);
    // The same for an input known to be zero outside `bound` (whole rows with `whole_rows`).
    void find_active_columns(const std::vector<ColumnRange>& bound, bool whole_rows, const Array& h, const Array& hu,
                             const Array& hv, bool pumping);
    // Shares the rows among threads by the columns active_ computes (and sizes work_);
    // then the rows [first, last) of a thread.
    void balance_strips();
    std::pair<int, int> strip_rows(int thread, int threads) const;
    // The split step (split_rows.hpp): two sweeps, now_ -> mid_ -> next_, then next_ swapped in.
    enum class Axis { x, y };
    void split_step(double dt);
    // One sweep along `axis` over dt from `in` (nonzero within its bound, or anywhere with
    // `whole_rows`) into `out`; ghosts at time t; `last`: the step's second sweep (friction,
    // CFL rate).
    void sweep(Axis axis, bool last, double dt, double t, State& in, bool whole_rows, State& out);
    struct SweepPlan {
        State* in = nullptr;
        State* out = nullptr;
        bool last = false;
        double dt = 0.0, pump_depth = 0.0;  // [s], [m] added to the pump's cells (x sweep)
    };
    void x_sweep_strip(const SweepPlan& plan, Array& mem, int j0, int j1, long& fixes, Real& worst, Real& amax);
    void y_sweep_strip(const SweepPlan& plan, Array& mem, int j0, int j1, long& fixes, Real& worst, Real& amax);
    // The constants of a stage or sweep.
    rows::Sweep<Real> sweep_constants() const;
    // The CFL rate of one cell for the stepping in use [1/s].
    double cell_rate(Real h, Real hu, Real hv) const;
    template <class V>
    V& changed_outside(V& v) {
        state_changed_outside_ = true;
        max_wave_rate_ = -1.0;
        return v;
    }
    const BoundaryDef& boundary(Side s) const;
    // Adds the boundary faces' mass flux of the last x pass times `weight` [s] to transfer_.
    void add_transfer(double weight);

    Grid grid_;
    PhysicsDef def_;
    FiniteVolumeDef fv_;
    std::size_t stride_ = 0, rows_ = 0;
    double time_ = 0.0;
    SolverStats stats_;
    // Hot state: U^n; Heun's predictor or the split step's first sweep; the step's output,
    // which becomes U^n by a swap, after which it keeps the step's start (for a step redone
    // for positivity).
    State now_, mid_, next_;
    std::optional<FrontTracker> front_;     // the tracked fronts' (front.hpp); none with plain fronts
    std::vector<Array> work_;               // per thread: the row buffers of a stage or sweep
    std::vector<double> cumulative_columns_;  // columns to compute below each row (splits rows over threads)
    // Skipping dry land (active_columns.cpp). Per interior row: the columns of the stage's
    // input (and base) with a nonzero h, hu or hv; the columns to compute. Per padded row:
    // the columns of the input with a nonzero depth.
    std::vector<ColumnRange> state_nonzero_, base_nonzero_, active_;
    std::vector<ColumnRange> depth_nonzero_;
    bool state_changed_outside_ = true;    // now_.bound unknown: scan whole rows
    mutable double max_wave_rate_ = -1.0;  // max(a_x/dx + a_y/dy) of the state [1/s]; < 0: not known
    // Cold data.
    Array z_;                                  // bed [m], ghosts filled once
    Array g_n2_;                               // g * manning_n^2 per cell
    Forcing forcing_;                          // boundary series and the pump
    std::vector<std::size_t> pump_cells_;      // padded indices of the pump's source strip (forcing_'s), row by row
    std::vector<std::size_t> pump_row_start_;  // the pump cells of interior row j: [start[j], start[j+1])
    // Steps above the positivity bound (cfl > 0.5): the boundary transfers before the
    // step (the state before it is in next_ after it), restored and stepped again at cfl
    // 0.45 when the step clamped a negative depth.
    std::array<std::vector<double>, 2> saved_transfer_;  // west, east
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
    std::array<NestedGhosts, 2> nested_;  // west, east
    bool track_transfer_ = false;
    // Per x side (0 west, 1 east), per row: the mass flux through the boundary face of the
    // current stage [m^2/s], Heun's first stage's, and the volume per unit length since the
    // last reset [m^2].
    std::array<std::vector<double>, 2> face_mass_, stage1_mass_, transfer_;
};

// The solver in double precision (tests, studies and the leap-frog's comparisons), and in float.
using Solver = BasicSolver<double>;
using Solver32 = BasicSolver<float>;

}  // namespace flotsam::hydro
