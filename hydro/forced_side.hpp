// A side driven by another run's output (formats/boundary_file.hpp, SideRecord): the
// water level, and where the record has it the velocity, at points along the side, read
// at each edge cell and step.
//
// In space: linear along the side between the record's points (a cell beyond the first or
// last point by less than half a cell takes that point's values; farther is an error).
// In time: linear between the record's samples, or a cubic Hermite curve whose slope at a
// sample is that of the parabola through it and its two neighbours (one-sided secants at
// the ends): both are exact for a level linear in time, the cubic also for a quadratic one.
//
// The ghost state. Normal to the side the 1-D shallow-water equations carry two Riemann
// invariants, R+ = u_n + 2c into the domain and R- = u_n - 2c out of it (c = sqrt(g h),
// u_n the velocity into the domain). With the level alone the side is a level side
// (boundary.hpp, level_ghost, with its LevelMode). With level and velocity R+ is the
// record's, u_n,f + 2 sqrt(g h_f) with h_f = max(0, eta_f - z) over the edge cell's bed
// (0 where the record's own depth, where it has one, is below the dry tolerance: a dry
// point of the source, whose level is its ground, sends no water over a lower edge cell),
// and R- the edge cell's:
//     c_b = max(0, (R+ - R-) / 4),   h_b = c_b^2 / g,   u_n,b = (R+ + R-) / 2,
// the tangential velocity the record's where water flows in and the edge cell's where it
// flows out. Where the inside agrees with the record the ghost is the record's state; what
// the inside sends toward the side leaves through it instead of reflecting. With the level
// alone, a point the record has dry gives a dry ghost.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "common/enum_names.hpp"
#include "formats/boundary_file.hpp"

namespace flotsam::hydro {

enum class ForcingTime { linear, cubic };
inline constexpr EnumNames<ForcingTime, 2> forcing_time_names{
    "forcing time interpolation", {{{ForcingTime::linear, "linear"}, {ForcingTime::cubic, "cubic"}}}};
constexpr const auto& enum_names(ForcingTime) { return forcing_time_names; }

class ForcedSide {
public:
    // `cell_along` [m]: the along-side coordinate of each edge cell, increasing; `cell_size`
    // [m] the cells' size along the side; `side` names the side in errors.
    ForcedSide(std::shared_ptr<const SideRecord> record, const std::vector<double>& cell_along, double cell_size,
               ForcingTime time, const std::string& side);
    double start() const { return record_->time.front(); }  // [s]
    double end() const { return record_->time.back(); }     // [s]
    bool has_velocity() const { return record_->has_velocity(); }
    bool has_depth() const { return record_->has_depth(); }
    double max_level() const;  // [m] over the whole record
    // Values at each edge cell at t (clamped to [start, end]): level [m], u and v [m s-1]
    // along the grid's x and y, depth [m] (each left empty where the record has none).
    void sample(double t, std::vector<double>& level, std::vector<double>& u, std::vector<double>& v,
                std::vector<double>& depth) const;

private:
    std::shared_ptr<const SideRecord> record_;
    std::vector<std::size_t> point_;  // per cell: the record point at or before it
    std::vector<double> weight_;      // per cell: the weight of the point after it
    ForcingTime time_;
    mutable std::vector<double> points_now_;  // scratch: the record's points at the time sampled
};

// The ghost state of a side forced with level and velocity (above). Inputs: the edge
// cell's depth, inward and tangential velocity; the record's depth over the edge cell's
// bed, inward and tangential velocity. Outputs: the ghost's depth and velocities.
void forced_ghost(double h_in, double un_in, double ut_in, double h_given, double un_given, double ut_given, double g,
                  double& h_out, double& un_out, double& ut_out);

}  // namespace flotsam::hydro
