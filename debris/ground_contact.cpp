#include "debris/ground_contact.hpp"

#include <algorithm>
#include <cmath>

#include "debris/kernels.hpp"

namespace flotsam::debris {

namespace {

// A velocity below this has no direction (a point that does not slide) [m/s].
constexpr double sliding_epsilon = 1e-12;

}  // namespace

void ground_patches(const FlowSampler& flow, const Grid& grid, const BodyParams& b, const Box& box, double centre_depth, double t,
                     double rho, double g, FootprintCache& footprint_cache, std::vector<GroundPatch>& out, bool depth_bound) {
    const BodyDef& def = b.def;
    const Vec2 xg = box.centre;
    out.clear();
    if (def.contact == ContactModel::center) {
        if (centre_depth < b.draft)
            out.push_back({Vec2{}, b.plan_area, friction_capacity(def.mu, 1.0, b.mass, rho, b.plan_area, centre_depth, g)});
        return;
    }
    if (depth_bound) {
        const CellWindow cells =
            flow.cells_for(xg.x - box.extent_x(), xg.x + box.extent_x(), xg.y - box.extent_y(), xg.y + box.extent_y());
        if (!(flow.min_depth(cells) < b.draft)) return;  // no point under the body can be shallower than the draft
    }
    // Likewise row by row: a row of cells none of whose points can be shallower than the
    // draft gives no patch, so it is neither clipped nor sampled. Every patch centroid of
    // a row lies in the footprint's part in it (to some 1e-12 m: footprint.cpp), whose
    // band is widened here by a thousandth of a cell; the draft is raised by 1e-9 of
    // itself (the interpolated depth may lie round-off below its nodes' smallest). The
    // bound then holds whatever the rounding, and the patches are the same bits.
    struct RowBound {
        const FlowSampler& flow;
        double pad, draft;
    };
    const RowBound bound{flow, 1e-3 * std::min(grid.dx, grid.dy), b.draft * (1.0 + 1e-9)};
    const FootprintCache::RowFilter shallow_somewhere = [](const void* c, double x0, double x1, double y0, double y1) {
        const RowBound& r = *static_cast<const RowBound*>(c);
        return r.flow.min_depth(r.flow.cells_for(x0 - r.pad, x1 + r.pad, y0 - r.pad, y1 + r.pad)) < r.draft;
    };
    const std::vector<FootprintPatch>& footprint =
        depth_bound ? footprint_cache.patches(box, grid, shallow_somewhere, &bound) : footprint_cache.patches(box, grid);
    const FlowSampler::TimeStencil at_t = flow.at_time(t);
    // The depths at the patches' centroids, sampled a block of patches at a time.
    constexpr int block = 64;
    Vec2 at[block];
    double h[block];
    for (std::size_t k0 = 0; k0 < footprint.size(); k0 += block) {
        const int n = int(std::min<std::size_t>(block, footprint.size() - k0));
        for (int k = 0; k < n; ++k) at[k] = footprint[k0 + k].centroid;
        flow.depth(at, n, at_t, h);
        for (int k = 0; k < n; ++k) {
            const FootprintPatch& fp = footprint[k0 + k];
            if (h[k] < b.draft)
                out.push_back({fp.centroid - xg, fp.area,
                               friction_capacity(def.mu, fp.area / b.plan_area, b.mass, rho, b.plan_area, h[k], g)});
        }
    }
}

Friction apply_friction(const std::vector<GroundPatch>& patches, const Velocities& trial, const Inertia& eff, double dt) {
    Friction f;
    f.after = trial;
    if (patches.empty()) return f;
    // Each patch resists the sliding of its own point. Translation first, with the sliding
    // at the trial velocities; then the torque, with the sliding at the new translation,
    // so that a body friction has stopped is not turned by it (a static corner does not
    // drive a rotation; a dragging one does). Neither reverses the motion within the
    // step: a component that would change sign stops instead, which is also the static
    // case (at rest with the driving force below the capacity, the trial velocity is
    // reversed, so the body stays).
    Vec2 Ff;
    for (const auto& p : patches) {
        f.capacity += p.capacity;
        Ff += (-p.capacity) * unit_or_zero(trial.V + spin(trial.omega, p.r), sliding_epsilon);
    }
    f.after.V = trial.V + (dt / eff.mass) * Ff;
    if (dot(f.after.V, trial.V) <= 0.0) f.after.V = Vec2{};
    double Tf = 0.0;
    for (const auto& p : patches)
        Tf += cross(p.r, (-p.capacity) * unit_or_zero(f.after.V + spin(trial.omega, p.r), sliding_epsilon));
    f.after.omega = trial.omega + dt / eff.inertia * Tf;
    if (f.after.omega * trial.omega <= 0.0) f.after.omega = 0.0;
    return f;
}

// T' in the condition T'^n T'^(n+1) ≥ 0 is taken about the axis in use: the centre, or
// the contact centroid while the axis is shifted (choice: about the centre, T' of a body
// held at one corner in a uniform current is near zero and flips sign with round-off,
// which would end every pivot after a few steps).
AxisShift axis_shift(const BodyParams& b, const BodyState& s, const std::vector<GroundPatch>& patches, const FluidLoad& load,
                     double omega_after, double capacity, const Inertia& eff, double dt) {
    AxisShift a;
    a.torque_ref = load.torque;
    if (b.def.contact != ContactModel::local || !b.def.axis_shift || patches.empty()) return a;
    Vec2 r_sub;  // contact-area centroid relative to the centre
    double area = 0.0;
    for (const auto& p : patches) {
        r_sub += p.area * p.r;
        area += p.area;
    }
    r_sub = (1.0 / area) * r_sub;
    const Vec2 arm = -1.0 * r_sub;                                         // centre relative to the axis
    const double torque_sub = torque_about(load.torque, load.force, arm);  // T_sub: no friction term (Eq. 6's T')
    const double torque_now = (s.flags & flag_pivoting) ? torque_sub : load.torque;
    if (!(norm(arm) > 1e-9 && s.omega * omega_after <= 0.0 && s.torque_prev * torque_now >= 0.0 && norm(load.force) <= capacity))
        return a;
    a.shifted = true;
    a.torque_ref = torque_sub;
    const double inertia_sub = parallel_axis_inertia(eff.inertia, eff.mass, arm);
    double w = pivot_rate_step(b.def.pivot_rate == PivotRate::restarted ? 0.0 : s.pivot_rate, torque_sub, inertia_sub, dt);
    if (b.def.pivot_rate == PivotRate::braked) {
        double friction_torque = 0.0;
        for (const auto& p : patches) friction_torque += p.capacity * norm(p.r - r_sub);
        const double brake = dt / inertia_sub * friction_torque;  // never reverses the pivot
        w = std::fabs(w) <= brake ? 0.0 : w - std::copysign(brake, w);
    }
    a.pivot_rate = w;
    a.turn = w * dt;
    a.shift = pivot_shift(arm, a.turn);   // Eqs. 7-9: x_g* − x_g^n
    a.pivot_arm = rotate(r_sub, a.turn);  // the axis stays put; seen from the moved centre
    return a;
}

}  // namespace flotsam::debris
