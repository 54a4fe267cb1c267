// Boundary conditions, one per side of the grid (TUM SWE style scenario data): they
// fill two layers of ghost cells before each flux evaluation.
#pragma once
#include <array>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "common/enum_names.hpp"
#include "common/grid.hpp"
#include "common/timeseries.hpp"
#include "formats/boundary_file.hpp"
#include "hydro/forced_side.hpp"

namespace flotsam::hydro {

enum class Side { west, east, south, north };
inline const char* side_name(Side s) {
    constexpr const char* names[4] = {"west", "east", "south", "north"};
    return names[int(s)];
}

enum class BoundaryKind {
    wall,           // slip wall: normal velocity mirrored, tangential kept
    transmissive,   // free transmission: waves leave into still water of the side's
                    // initial depth (outgoing Riemann invariant from inside, incoming
                    // one of that still water), so no inflow feeds itself
    zero_gradient,  // study only (finite volumes): ghosts copy the edge cell; an inflow
                    // there keeps its own incoming invariant and can grow without bound
    level,          // water level from a series (see LevelMode)
    discharge,      // inflow discharge from a series [m^3/s over the whole side]
    pump,           // the public benchmark forcing: a wall with a mass source in the
                    // first cells until pump_stop, then a level relaxing to still water
    nested,         // ghost cells given by the other grid of a nested pair (hydro/nesting.hpp)
    forced,         // level (and velocity) along the side from another run's output (forced_side.hpp)
};
// The kinds a user may give a side (`nested` is set by the nesting driver only).
inline constexpr EnumNames<BoundaryKind, 8> boundary_kind_names{"boundary",
                                                                {{{BoundaryKind::wall, "wall"},
                                                                  {BoundaryKind::transmissive, "transmissive"},
                                                                  {BoundaryKind::level, "level"},
                                                                  {BoundaryKind::discharge, "discharge"},
                                                                  {BoundaryKind::pump, "pump"},
                                                                  {BoundaryKind::transmissive, "open"},
                                                                  {BoundaryKind::zero_gradient, "zero-gradient"},
                                                                  {BoundaryKind::forced, "forced"}}}};
constexpr const auto& enum_names(BoundaryKind) { return boundary_kind_names; }

// A measured record (WG1) is the total level: the wave going in plus what the city sent
// back. Read as the incoming wave alone, that reflection is counted twice (generated
// scene, 4 cm, record r00: WG2 peaks at 0.117 m as `incident`, 0.0615 m as `total`;
// the paper measured 0.063 m). Hence `total` is the default; `incident` is for a series
// that really is the incoming wave only (an offshore model's, a wave maker's target).
enum class LevelMode {
    total,     // the series is the total level at the side: the level is imposed, the
               // velocity follows from the outgoing Riemann invariant taken from inside
    incident,  // the series is the incoming long wave: the incoming Riemann invariant is
               // imposed, the outgoing one comes from inside, so reflections leave
};
inline constexpr EnumNames<LevelMode, 2> level_mode_names{"level mode",
                                                          {{{LevelMode::total, "total"}, {LevelMode::incident, "incident"}}}};
constexpr const auto& enum_names(LevelMode) { return level_mode_names; }

// What a level or discharge side becomes after its series ends.
enum class SeriesEnd {
    error,         // nothing: the series must cover the whole run (checked before it starts)
    transmissive,  // a transmissive side (no incoming wave): what is still in the domain
                   // leaves instead of reflecting off a level held at its last value
};
inline constexpr EnumNames<SeriesEnd, 2> series_end_names{
    "end of series", {{{SeriesEnd::error, "error"}, {SeriesEnd::transmissive, "transmissive"}}}};
constexpr const auto& enum_names(SeriesEnd) { return series_end_names; }

struct BoundaryDef {
    BoundaryKind kind = BoundaryKind::wall;
    std::string series_file;   // CSV time,value for level / discharge
    std::string forcing_file;  // CF NetCDF of a forced side (another run's values; data/boundary_forcing.hpp)
    LevelMode level_mode = LevelMode::total;
    SeriesEnd series_end = SeriesEnd::error;
    // A forced side's values along the side, placed in the scene's frame
    // (data/boundary_forcing.hpp reads them from forcing_file), and how they are read in time.
    std::shared_ptr<const SideRecord> record;
    ForcingTime forcing_time = ForcingTime::linear;
};

// The public benchmark's forcing on the west side (BoundaryKind::pump): a mass source in
// a strip of cells along the wall until `stop`, then a total level relaxing to still
// water from its value at the stop.
struct PumpDef {
    double discharge = 0.0175;  // [m^3/s] mass source while pumping (half the flume pump)
    double stop = 300.0;        // [s] end of pumping
    double relax_time = 50.0;   // [s] e-folding time of the level after pumping
    double length = 0.2;        // [m] width of the strip of source cells along the side
};

// Ghost values handed to a `nested` side: layer 1 (next to the edge) then layer 2, each
// n_along values (south to north on an x side). Conserved variables h [m], hu, hv [m^2/s].
struct GhostState {
    std::vector<double> h, hu, hv;
};

// Ghost state for an open side from Riemann invariants. `un` is the velocity into the
// domain, c = sqrt(g h). Inputs: interior depth and inward velocity, still-water depth
// h0 at the side. Outputs through h_out, un_out.
void level_ghost(double h_in, double un_in, double h0, double eta_given, LevelMode mode, double g, double& h_out, double& un_out);
void discharge_ghost(double h_in, double un_in, double q_in, double g, double dry_depth, double& h_out, double& un_out);

// What one side imposes at one time: the pump resolved (a wall while it pumps, then a
// total level relaxing to still water), a series read at that time.
struct SideForcing {
    BoundaryKind kind = BoundaryKind::wall;  // never pump
    LevelMode mode = LevelMode::incident;
    double given = 0.0;  // level [m], or discharge per unit length of the side [m^2/s]
    // A forced side: per edge cell (south to north, or west to east) the level [m] and,
    // where the record has them, u and v [m s-1] (null otherwise). They point into
    // Forcing's buffers: valid until the next Forcing::at for the same side.
    const std::vector<double>* level = nullptr;
    const std::vector<double>* u = nullptr;
    const std::vector<double>* v = nullptr;
    const std::vector<double>* depth = nullptr;  // [m] where the record has it
};

// The state (depth h_out, inward velocity un_out) at an open side of kind level or
// discharge from the interior cell (h_in, un_in, still-water depth h0); any other kind
// is taken as no incoming wave (a level side with incident level 0).
void open_side_state(const SideForcing& f, double h_in, double un_in, double h0, double g, double dry_depth, double& h_out,
                     double& un_out);

// The time-dependent inputs of the four sides, shared by the solvers: the boundary
// series, the pump's strip of source cells, and the level the pump side relaxes from
// after the stop (part of a run's restart state).
class Forcing {
public:
    // `sides` in the order of Side; `bed` [m] on `grid`, row-major. Reads the series and
    // checks the sides (errors name the boundary); places the pump's strip on the cells
    // below still water in the first pump.length along the west side.
    Forcing(const std::array<BoundaryDef, 4>& sides, const PumpDef& pump, const Grid& grid, const std::vector<double>& bed);

    const BoundaryDef& def(Side s) const { return sides_[int(s)]; }
    const PumpDef& pump() const { return pump_; }
    // Largest value of side s's series (level [m] or discharge [m^3/s]) or record (level
    // [m]); 0 without one.
    double series_max(Side s) const;
    // Forcing of side s at time t. `strip_level()` is the mean level [m] over the pump's
    // strip now; it is called once, the first time past the pump's stop, to fix the level
    // the side relaxes from.
    template <class StripLevel>
    SideForcing at(Side s, double t, StripLevel&& strip_level);

    // The pump's strip: interior cells (i, j), and its source as a depth rate [m/s] at t.
    const std::vector<std::array<int, 2>>& pump_cells() const { return pump_cells_; }
    double pump_rate(double t) const;
    double pump_level_at_stop() const { return pump_level_at_stop_; }
    void set_pump_level_at_stop(double v) {
        pump_level_at_stop_ = v;
        pump_stopped_ = true;
    }

private:
    std::array<BoundaryDef, 4> sides_;
    PumpDef pump_;
    std::array<TimeSeries, 4> series_;  // level [m] or discharge [m^3/s], where used
    std::array<std::shared_ptr<const ForcedSide>, 4> forced_;        // forced sides
    std::array<std::vector<double>, 4> level_now_, u_now_, v_now_, depth_now_;  // a forced side's values at the last at()
    std::array<double, 4> length_{};    // [m] of each side
    std::vector<std::array<int, 2>> pump_cells_;
    double pump_area_ = 0.0;           // [m^2]
    double pump_level_at_stop_ = 0.0;  // [m]
    bool pump_stopped_ = false;
};

template <class StripLevel>
SideForcing Forcing::at(Side s, double t, StripLevel&& strip_level) {
    const BoundaryDef& b = def(s);
    SideForcing f{b.kind, b.level_mode, 0.0};
    if (b.kind == BoundaryKind::pump) {
        if (t < pump_.stop) {
            f.kind = BoundaryKind::wall;
        } else {
            if (!pump_stopped_) set_pump_level_at_stop(strip_level());
            f.kind = BoundaryKind::level;
            f.mode = LevelMode::total;
            f.given = pump_level_at_stop_ * std::exp(-(t - pump_.stop) / pump_.relax_time);
        }
    } else if (b.kind == BoundaryKind::forced) {
        const ForcedSide& fs = *forced_[int(s)];
        if (t < fs.start() || t > fs.end()) {
            f.kind = BoundaryKind::transmissive;  // outside the record's times
        } else {
            fs.sample(t, level_now_[int(s)], u_now_[int(s)], v_now_[int(s)], depth_now_[int(s)]);
            f.level = &level_now_[int(s)];
            if (fs.has_depth()) f.depth = &depth_now_[int(s)];
            if (fs.has_velocity()) {
                f.u = &u_now_[int(s)];
                f.v = &v_now_[int(s)];
            }
        }
    } else if ((b.kind == BoundaryKind::level || b.kind == BoundaryKind::discharge) && b.series_end == SeriesEnd::transmissive &&
               t > series_[int(s)].end()) {
        f.kind = BoundaryKind::transmissive;
    } else if (b.kind == BoundaryKind::level) {
        f.given = series_[int(s)].at(t);
    } else if (b.kind == BoundaryKind::discharge) {
        f.given = series_[int(s)].at(t) / length_[int(s)];
    }
    return f;
}

}  // namespace flotsam::hydro
