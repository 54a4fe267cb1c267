#include "hydro/boundary.hpp"

#include <cmath>

#include "common/error.hpp"

namespace flotsam::hydro {

BoundaryKind parse_boundary_kind(const std::string& s, const std::string& option) {
    if (s == "wall") return BoundaryKind::wall;
    if (s == "transmissive" || s == "open") return BoundaryKind::transmissive;
    if (s == "level") return BoundaryKind::level;
    if (s == "discharge") return BoundaryKind::discharge;
    if (s == "pump") return BoundaryKind::pump;
    fail("", option, "unknown boundary '" + s + "' (wall, transmissive, level, discharge, pump)");
}

LevelMode parse_level_mode(const std::string& s, const std::string& option) {
    if (s == "incident") return LevelMode::incident;
    if (s == "total") return LevelMode::total;
    fail("", option, "unknown level mode '" + s + "' (incident, total)");
}

const char* to_string(BoundaryKind k) {
    switch (k) {
        case BoundaryKind::wall: return "wall";
        case BoundaryKind::transmissive: return "transmissive";
        case BoundaryKind::level: return "level";
        case BoundaryKind::discharge: return "discharge";
        case BoundaryKind::pump: return "pump";
        case BoundaryKind::nested: return "nested";
    }
    return "?";
}

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
        if (std::abs(next - h) < 1e-12 * h) { h = next; break; }
        h = next;
    }
    h_out = std::max(h, critical);  // stay subcritical at the inflow
    un_out = q_in / h_out;
}

}  // namespace flotsam::hydro
