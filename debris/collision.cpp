#include "debris/collision.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "debris/kernels.hpp"

namespace flotsam::debris {

namespace {

// Moving out by exactly the depth leaves the body touching; this much more leaves it
// clear of the next detection, far below anything the output resolves [m].
constexpr double separation_slop = 1e-9;

Box pose(const BodyState& s, const BodyParams& b) { return Box::make({s.x, s.y}, s.theta, b.def.length, b.def.width); }

// The impulse at one contact (zero unless it approaches).
void apply_impulse(const ObstacleCollision& c, const BodyParams& b, double mass, double inertia, BodyState& s) {
    const Vec2 r = c.point - Vec2{s.x, s.y};
    const Vec2 vp = Vec2{s.vx, s.vy} + spin(s.omega, r);
    const double j = collision_impulse(dot(vp, c.normal), b.def.restitution, mass, inertia, r, c.normal);
    s.vx += j / mass * c.normal.x;
    s.vy += j / mass * c.normal.y;
    s.omega += j * cross(r, c.normal) / inertia;
}

// The buildings among `contacts` not yet in `touches`, each with its fastest approach
// (before any impulse of this pass) and that contact's point.
void note_buildings(const std::vector<ObstacleCollision>& contacts, const BodyState& s, std::vector<BuildingTouch>& touches) {
    const std::size_t seen_before = touches.size();
    for (const auto& c : contacts) {
        if (c.building <= 0) continue;
        const Vec2 r = c.point - Vec2{s.x, s.y};
        const double approach = -dot(Vec2{s.vx, s.vy} + spin(s.omega, r), c.normal);
        std::size_t k = 0;
        while (k < touches.size() && touches[k].building != c.building) ++k;
        if (k < seen_before) continue;  // seen at an earlier pass
        if (k == touches.size())
            touches.push_back({c.building, approach, c.point});
        else if (approach > touches[k].speed)
            touches[k] = {c.building, approach, c.point};
    }
}

double deepest(const std::vector<ObstacleCollision>& cs) {
    double d = 0.0;
    for (const auto& c : cs) d = std::max(d, c.depth);
    return d;
}

// The least move out of every contact at once (`clearing_move` below): the contacts'
// rows in the inertia-scaled coordinates u = (√M Δx, √M Δy, √I Δθ), where that move is
// the shortest u.
struct ClearingRow {
    double a[3];  // (n / √M, (r × n) / √I)
    double b;     // depth to clear [m]
};

// Solves the k × k system G λ = b (k ≤ 3) by Gaussian elimination with partial
// pivoting; false where G is (nearly) singular: the rows are dependent.
bool solve_small(int k, double G[3][3], double b[3], double lambda[3]) {
    for (int c = 0; c < k; ++c) {
        int p = c;
        for (int r = c + 1; r < k; ++r)
            if (std::fabs(G[r][c]) > std::fabs(G[p][c])) p = r;
        if (!(std::fabs(G[p][c]) > 1e-12 * (std::fabs(G[0][0]) + std::fabs(G[k - 1][k - 1])))) return false;
        std::swap(G[p], G[c]);
        std::swap(b[p], b[c]);
        for (int r = c + 1; r < k; ++r) {
            const double f = G[r][c] / G[c][c];
            for (int q = c; q < k; ++q) G[r][q] -= f * G[c][q];
            b[r] -= f * b[c];
        }
    }
    for (int c = k - 1; c >= 0; --c) {
        double v = b[c];
        for (int q = c + 1; q < k; ++q) v -= G[c][q] * lambda[q];
        lambda[c] = v / G[c][c];
    }
    return true;
}

// The shortest u with a_i · u ≥ b_i for every row: the nearest point to the origin of a
// polyhedron in three dimensions, where at most three constraints are active. Every set
// of one to three of the first `n_try` rows is tried as the active set (u = Σ λ_k a_k,
// a_k · u = b_k on the set, λ ≥ 0), kept where it meets every row; the shortest kept is
// the optimum whenever its active set lies among the rows tried. False where no set does.
bool shortest_clearing(const std::vector<ClearingRow>& rows, std::size_t n_try, double u[3]) {
    const double tol = 1e-12;
    double best = -1.0;
    int set[3];
    const auto try_set = [&](int k) {
        double G[3][3], b[3], lambda[3] = {0, 0, 0};
        for (int i = 0; i < k; ++i) {
            b[i] = rows[set[i]].b;
            for (int j = 0; j < k; ++j) {
                const ClearingRow &ri = rows[set[i]], &rj = rows[set[j]];
                G[i][j] = ri.a[0] * rj.a[0] + ri.a[1] * rj.a[1] + ri.a[2] * rj.a[2];
            }
        }
        if (!solve_small(k, G, b, lambda)) return;
        double v[3] = {0, 0, 0};
        for (int i = 0; i < k; ++i) {
            if (lambda[i] < 0.0) return;
            for (int d = 0; d < 3; ++d) v[d] += lambda[i] * rows[set[i]].a[d];
        }
        const double len = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
        if (best >= 0.0 && len >= best) return;
        for (const ClearingRow& r : rows)
            if (r.a[0] * v[0] + r.a[1] * v[1] + r.a[2] * v[2] < r.b - tol * std::fabs(r.b)) return;
        best = len;
        for (int d = 0; d < 3; ++d) u[d] = v[d];
    };
    const int n = int(n_try);
    for (set[0] = 0; set[0] < n; ++set[0]) {
        try_set(1);
        for (set[1] = set[0] + 1; set[1] < n; ++set[1]) {
            try_set(2);
            for (set[2] = set[1] + 1; set[2] < n; ++set[2]) try_set(3);
        }
    }
    return best >= 0.0;
}

// The move that takes the body out of every contact (sorted deepest first) to first
// order, with the least M |Δx|² + I Δθ²: translation and rotation shared as impulses
// share them. Where the rows tried admit none (more contacts than the linearisation can
// clear together), out of each contact in turn by what is left of its depth.
SeparatingMove clearing_move(const std::vector<ObstacleCollision>& contacts, Vec2 centre, double mass, double inertia) {
    constexpr std::size_t max_tried = 6;  // the deepest distinct contacts tried as active sets: at most 41 solves
    const double sm = std::sqrt(mass), si = std::sqrt(inertia);
    std::vector<ClearingRow> rows;
    rows.reserve(contacts.size());
    std::size_t tried = 0;
    for (const ObstacleCollision& c : contacts) {
        const Vec2 r = c.point - centre;
        // b: the depth to clear, or (negative) the gap the move may close [m].
        const ClearingRow row{{c.normal.x / sm, c.normal.y / sm, cross(r, c.normal) / si}, c.depth + separation_slop};
        // Tried as an active set only where its direction differs from those of the deeper
        // rows tried (the cells of one straight wall give nearly the same row).
        bool distinct = tried < max_tried;
        for (std::size_t k = 0; distinct && k < tried; ++k) {
            const ClearingRow& q = rows[k];
            const double dot3 = row.a[0] * q.a[0] + row.a[1] * q.a[1] + row.a[2] * q.a[2];
            const double n1 = row.a[0] * row.a[0] + row.a[1] * row.a[1] + row.a[2] * row.a[2];
            const double n2 = q.a[0] * q.a[0] + q.a[1] * q.a[1] + q.a[2] * q.a[2];
            if (dot3 > 0.9999 * std::sqrt(n1 * n2)) distinct = false;
        }
        if (distinct) {
            rows.insert(rows.begin() + std::ptrdiff_t(tried), row);
            ++tried;
        } else {
            rows.push_back(row);
        }
    }
    double u[3];
    if (shortest_clearing(rows, tried, u)) return {Vec2{u[0] / sm, u[1] / sm}, u[2] / si};
    SeparatingMove total;
    for (const ObstacleCollision& c : contacts) {
        const Vec2 r = c.point - centre;
        const double left = c.depth - (dot(total.shift, c.normal) + total.turn * cross(r, c.normal));
        if (!(left > 0.0)) continue;
        const SeparatingMove m = separating_move(left + separation_slop, mass, inertia, r, c.normal);
        total.shift += m.shift;
        total.turn += m.turn;
    }
    return total;
}

}  // namespace

void hand_pivot_to_centre(BodyState& s) {
    if (s.pivot_rate == 0.0) return;
    const Vec2 arm{-s.pivot_ax, -s.pivot_ay};  // the centre relative to the axis
    const Vec2 v = spin(s.pivot_rate, arm);
    s.vx += v.x;
    s.vy += v.y;
    s.omega += s.pivot_rate;
    s.pivot_rate = 0.0;
    s.pivot_ax = s.pivot_ay = 0.0;
}

double deepest_overlap(const ObstacleMap& obstacles, const Blocking& blocking, const Box& box,
                       std::vector<ObstacleCollision>& scratch) {
    scratch.clear();
    obstacles.find_contacts(box, blocking, scratch);
    return deepest(scratch);
}

CollisionOutcome resolve_collisions(const CollisionSetup& setup, BodyState& state, const Box& footprint,
                                    std::vector<ObstacleCollision>& contacts, std::vector<BuildingTouch>* touches) {
    const ObstacleMap& obstacles = setup.obstacles;
    const BodyParams& body = setup.body;
    const double mass = setup.mass, inertia = setup.inertia;
    const auto detect = [&](const Box& box) {
        contacts.clear();
        obstacles.find_contacts(box, setup.blocking, contacts);
    };
    // The contacts of `box` and the cells within `margin` of it (depth > −margin: the gap).
    const double margin = clearing_margin_cells * std::min(obstacles.grid().dx, obstacles.grid().dy);
    const auto detect_near = [&](const Box& box) {
        contacts.clear();
        obstacles.find_contacts(box, setup.blocking, contacts, -margin, margin);
    };
    CollisionOutcome out;
    detect(footprint);
    if (contacts.empty()) return out;
    out.touched = true;
    hand_pivot_to_centre(state);
    auto by_depth = [](const ObstacleCollision& a, const ObstacleCollision& b) { return a.depth > b.depth; };

    if (body.def.collision == CollisionModel::single) {
        if (touches) note_buildings(contacts, state, *touches);
        const auto& c = *std::min_element(contacts.begin(), contacts.end(), by_depth);
        apply_impulse(c, body, mass, inertia, state);
        state.x += (c.depth + separation_slop) * c.normal.x;
        state.y += (c.depth + separation_slop) * c.normal.y;
        detect(pose(state, body));
        out.residual = deepest(contacts);
        return out;
    }

    // The pose the step reached and the velocities it reached it with: the pose is that
    // one plus the step's share of what the impulses changed (Euler: x^n + Δt V, the
    // corrected V; the axis shift's turn, done before, stays), plus the moves out.
    const BodyState reached = state;
    Vec2 moved_out;
    double turned_out = 0.0;
    const double w = setup.move.new_weight * setup.move.dt;
    const auto place = [&] {
        state.x = reached.x + w * (state.vx - reached.vx) + moved_out.x;
        state.y = reached.y + w * (state.vy - reached.vy) + moved_out.y;
        state.theta = reached.theta + w * (state.omega - reached.omega) + turned_out;
        detect(pose(state, body));
    };
    for (; out.passes < setup.max_passes && !contacts.empty(); ++out.passes) {
        std::sort(contacts.begin(), contacts.end(), by_depth);
        if (touches) note_buildings(contacts, state, *touches);
        for (const auto& c : contacts) apply_impulse(c, body, mass, inertia, state);
        place();  // advanced again from the start of the step with the corrected momentum
        if (contacts.empty()) break;
        // What that leaves (an overlap the step began with, a turning body's arc against
        // the straight re-advance, contacts whose impulses undo each other in a wedge):
        // the least move out of all of it at once, translation and rotation, that also
        // closes no gap to the cells within the margin (so that it does not push the body
        // from one wall into the other).
        detect_near(pose(state, body));
        std::sort(contacts.begin(), contacts.end(), by_depth);
        const SeparatingMove m = clearing_move(contacts, Vec2{state.x, state.y}, mass, inertia);
        const double most = largest_move_cells * std::min(obstacles.grid().dx, obstacles.grid().dy);
        const double scale = share_within(m.shift, m.turn, body.half_diagonal, most);
        moved_out += scale * m.shift;
        turned_out += scale * m.turn;
        place();
    }
    out.residual = deepest(contacts);
    out.unresolved = out.residual > setup.move.tolerance;
    return out;
}

}  // namespace flotsam::debris
