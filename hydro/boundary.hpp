// Boundary conditions, one per side of the grid (TUM SWE style scenario data): they
// fill two layers of ghost cells before each flux evaluation.
#pragma once
#include <string>
#include <vector>

#include "common/timeseries.hpp"

namespace flotsam::hydro {

enum class Side { west, east, south, north };

enum class BoundaryKind {
    wall,          // slip wall: normal velocity mirrored, tangential kept
    transmissive,  // free transmission: zero gradient, waves leave
    level,         // water level from a series (see LevelMode)
    discharge,     // inflow discharge from a series [m^3/s over the whole side]
    pump,          // the public benchmark forcing: a wall with a mass source in the
                   // first cells until pump_stop, then a level relaxing to still water
    nested,        // ghost cells given by the other grid of a nested pair (hydro/nesting.hpp)
};

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

struct BoundaryDef {
    BoundaryKind kind = BoundaryKind::wall;
    std::string series_file;                  // CSV time,value for level / discharge
    LevelMode level_mode = LevelMode::total;
    double pump_discharge = 0.0175;           // [m^3/s] mass source while pumping (half the flume pump)
    double pump_stop = 300.0;                 // [s] end of pumping
    double pump_relax_time = 50.0;            // [s] e-folding time of the level after pumping
    double pump_length = 0.2;                 // [m] width of the strip of source cells along the side
};

// Ghost values handed to a `nested` side: layer 1 (next to the edge) then layer 2, each
// n_along values (south to north on an x side). Conserved variables h [m], hu, hv [m^2/s].
struct GhostState {
    std::vector<double> h, hu, hv;
};

BoundaryKind parse_boundary_kind(const std::string& s, const std::string& option);
LevelMode parse_level_mode(const std::string& s, const std::string& option);
const char* to_string(BoundaryKind k);

// Ghost state for an open side from Riemann invariants. `un` is the velocity into the
// domain, c = sqrt(g h). Inputs: interior depth and inward velocity, still-water depth
// h0 at the side. Outputs through h_out, un_out.
void level_ghost(double h_in, double un_in, double h0, double eta_given, LevelMode mode, double g, double& h_out, double& un_out);
void discharge_ghost(double h_in, double un_in, double q_in, double g, double dry_depth, double& h_out, double& un_out);

}  // namespace flotsam::hydro
