// `flotsam hydro --boundary-output FILE --boundary-box x0,x1,y0,y1`: the level, depth and
// velocity on the outline of a box, so that this run can drive a finer run over the box
// alone (its sides forced by the file: hydro/forced_side.hpp, data/boundary_forcing.hpp).
//
// Stations lie on the box's four edges from corner to corner, spaced by the grid's cells
// along each edge (a corner belongs to both of its edges); each is read as the gauges are
// (hydro/point_samples.hpp) and recorded at every `interval` of simulated time, linear
// between the steps around it, or at the end of every step with interval 0. The file
// (formats/boundary_file.hpp) is written as <FILE>.part and renamed at the end.
#pragma once
#include <array>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "common/atomic_file.hpp"
#include "common/cf.hpp"
#include "common/grid.hpp"
#include "formats/boundary_file.hpp"
#include "hydro/point_samples.hpp"

namespace flotsam::hydro {

struct BoundaryOutputDef {
    std::string file;              // "": no boundary output
    std::array<double, 4> box{};   // x_min, x_max, y_min, y_max [m], inside the grid
    double interval = 0.05;        // [s] of simulated time between samples; 0: every step
};

class BoundaryOutput {
public:
    // Places the stations and creates the file. Errors name --boundary-box.
    BoundaryOutput(const BoundaryOutputDef& def, const Grid& grid, const cf::GridMapping& crs,
                   const std::map<std::string, std::string>& attributes);
    std::size_t stations() const { return stencils_.size(); }

    template <class S>
    std::vector<PointSample> read(const S& s) const {
        std::vector<PointSample> out;
        for (const PointStencil& p : stencils_) out.push_back(sample_point(s, p));
        return out;
    }
    // Records the sample times in (t0, t1] (t1 alone with interval 0), linear in time
    // between the states at t0 and t1; t0 = t1 records the initial state.
    void record(double t0, const std::vector<PointSample>& a, double t1, const std::vector<PointSample>& b);
    void flush();   // writes what was recorded since the last flush
    void commit();  // flush, close and rename to the final name

private:
    BoundaryOutputDef def_;
    std::vector<PointStencil> stencils_;
    std::unique_ptr<AtomicOutput> file_;
    std::optional<BoundaryWriter> writer_;
    std::size_t next_ = 0, flushed_ = 0;  // sample index to record next; samples in the file
    std::vector<double> time_, eta_, depth_, u_, v_;
};

}  // namespace flotsam::hydro
