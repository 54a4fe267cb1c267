#include "hydro/boundary.hpp"

#include <algorithm>
#include <cmath>

#include "common/error.hpp"

namespace flotsam::hydro {

// Characteristics of the 1-D shallow-water equations normal to the side: un + 2c travels
// into the domain (set from outside), un - 2c travels out (taken from the interior cell).
void level_ghost(double h_in, double un_in, double h0, double eta_given, LevelMode mode, double g, double& h_out, double& un_out) {
    const double c_in = std::sqrt(g * std::max(h_in, 0.0));
    const double outgoing = un_in - 2.0 * c_in;
    if (mode == LevelMode::total) {
        h_out = std::max(0.0, h0 + eta_given);
        un_out = outgoing + 2.0 * std::sqrt(g * h_out);
        return;
    }
    // Incident simple wave entering still water of depth h0: un = 2 (c - c0).
    const double c0 = std::sqrt(g * h0);
    const double c_wave = std::sqrt(g * std::max(0.0, h0 + eta_given));
    const double incoming = 2.0 * (c_wave - c0) + 2.0 * c_wave;
    const double c_b = std::max(0.0, 0.25 * (incoming - outgoing));
    h_out = c_b * c_b / g;
    un_out = 0.5 * (incoming + outgoing);
}

// Inflow q [m^2/s] with the outgoing invariant from inside: solve
// q / h - 2 sqrt(g h) = un_in - 2 c_in for h by Newton (the left side decreases in h).
void discharge_ghost(double h_in, double un_in, double q_in, double g, double dry_depth, double& h_out, double& un_out) {
    const double critical = std::cbrt(q_in * q_in / g);  // depth of critical flow for q
    if (h_in <= dry_depth) {
        h_out = std::max(critical, dry_depth);
        un_out = q_in / h_out;
        return;
    }
    const double target = un_in - 2.0 * std::sqrt(g * h_in);
    double h = std::max(h_in, critical);
    for (int it = 0; it < 30; ++it) {
        const double f = q_in / h - 2.0 * std::sqrt(g * h) - target;
        const double df = -q_in / (h * h) - std::sqrt(g / h);
        const double next = std::max(0.5 * h, h - f / df);
        if (std::abs(next - h) < 1e-12 * h) {
            h = next;
            break;
        }
        h = next;
    }
    h_out = std::max(h, critical);  // stay subcritical at the inflow
    un_out = q_in / h_out;
}

void open_side_state(const SideForcing& f, double h_in, double un_in, double h0, double g, double dry_depth, double& h_out,
                     double& un_out) {
    if (f.kind == BoundaryKind::discharge)
        discharge_ghost(h_in, un_in, f.given, g, dry_depth, h_out, un_out);
    else if (f.kind == BoundaryKind::level)
        level_ghost(h_in, un_in, h0, f.given, f.mode, g, h_out, un_out);
    else
        level_ghost(h_in, un_in, h0, 0.0, LevelMode::incident, g, h_out, un_out);
}

Forcing::Forcing(const std::array<BoundaryDef, 4>& sides, const PumpDef& pump, const Grid& grid, const std::vector<double>& bed)
    : sides_(sides), pump_(pump) {
    length_ = {grid.ny * grid.dy, grid.ny * grid.dy, grid.nx * grid.dx, grid.nx * grid.dx};
    for (Side s : {Side::west, Side::east, Side::south, Side::north}) {
        const BoundaryDef& b = def(s);
        if (b.kind == BoundaryKind::level || b.kind == BoundaryKind::discharge) {
            if (b.series_file.empty())
                fail("", std::string("boundary ") + enum_name(b.kind), "needs a series file (time,value CSV)");
            series_[int(s)] = read_time_series_csv(b.series_file);
        }
        if (b.kind == BoundaryKind::forced) {
            if (!b.record)
                fail("", std::string("boundary ") + side_name(s), "is forced but has no record (--<side>-forcing FILE)");
            const bool x_side = s == Side::west || s == Side::east;
            std::vector<double> along;
            for (int k = 0; k < (x_side ? grid.ny : grid.nx); ++k) along.push_back(x_side ? grid.y(k) : grid.x(k));
            forced_[int(s)] = std::make_shared<const ForcedSide>(b.record, along, x_side ? grid.dy : grid.dx, b.forcing_time,
                                                                 side_name(s));
        }
        if (b.kind == BoundaryKind::pump && s != Side::west) fail("", "boundary pump", "is only available on the west side");
        if (b.kind == BoundaryKind::nested && s != Side::west && s != Side::east)
            fail("", "boundary nested", "is only available on the west and east sides");
    }
    const BoundaryDef& w = def(Side::west);
    if (w.kind == BoundaryKind::pump) {
        const int ncol = std::max(1, int(std::lround(pump_.length / grid.dx)));
        for (int j = 0; j < grid.ny; ++j)
            for (int i = 0; i < std::min(ncol, grid.nx); ++i)
                if (bed[grid.index(i, j)] < 0.0) {
                    pump_cells_.push_back({i, j});
                    pump_area_ += grid.dx * grid.dy;
                }
        if (pump_area_ <= 0.0) fail("", "boundary pump", "no wet cells along the west side to put the pump's mass source in");
    }
}

double Forcing::series_max(Side s) const {
    if (forced_[int(s)]) return forced_[int(s)]->max_level();
    const auto& v = series_[int(s)].value;
    return v.empty() ? 0.0 : *std::max_element(v.begin(), v.end());
}

double Forcing::pump_rate(double t) const {
    const BoundaryDef& w = def(Side::west);
    return w.kind == BoundaryKind::pump && t < pump_.stop ? pump_.discharge / pump_area_ : 0.0;
}

}  // namespace flotsam::hydro
