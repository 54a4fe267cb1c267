#include "debris/body_collision.hpp"

#include <algorithm>
#include <cmath>

#include "debris/kernels.hpp"

namespace flotsam::debris {

namespace {

// Moving out by exactly the depth leaves the bodies touching; this much more leaves them
// clear of the next detection, far below anything the output resolves [m].
constexpr double separation_slop = 1e-9;
// Overlaps shallower than this are round-off, not contacts [m].
constexpr double contact_depth = 1e-10;

double radius_along(const Box& b, Vec2 n) {
    return b.half_length * std::fabs(dot(b.axis_long, n)) + b.half_width * std::fabs(dot(b.axis_wide, n));
}

Box pose_of(const BodyState& s, const BodyParams& p) { return Box::make({s.x, s.y}, s.theta, p.def.length, p.def.width); }

}  // namespace

bool box_overlap(const Box& A, const Box& B, double min_depth, BodyCollision& out) {
    const Vec2 d = B.centre - A.centre;
    const Vec2 axes[4] = {A.axis_long, A.axis_wide, B.axis_long, B.axis_wide};
    double best = 1e300;
    int k_best = 0;
    for (int k = 0; k < 4; ++k) {
        const double pen = radius_along(A, axes[k]) + radius_along(B, axes[k]) - std::fabs(dot(d, axes[k]));
        if (!(pen > min_depth)) return false;
        if (pen < best) {
            best = pen;
            k_best = k;
        }
    }
    // The reference box owns the axis; its face toward the other is the reference face.
    const bool a_refers = k_best < 2;
    const Box& ref = a_refers ? A : B;
    const Box& inc = a_refers ? B : A;
    Vec2 n = axes[k_best];  // oriented from the reference box toward the incident one
    if (dot(inc.centre - ref.centre, n) < 0.0) n = -1.0 * n;
    const bool along_long = (k_best % 2) == 0;
    const double ref_half = along_long ? ref.half_length : ref.half_width;
    const Vec2 t = along_long ? ref.axis_wide : ref.axis_long;
    const double t_half = along_long ? ref.half_width : ref.half_length;
    // The incident face: the other box's face whose outward normal is most against n.
    const Vec2 faces[4] = {inc.axis_long, -1.0 * inc.axis_long, inc.axis_wide, -1.0 * inc.axis_wide};
    int f = 0;
    for (int k = 1; k < 4; ++k)
        if (dot(faces[k], n) < dot(faces[f], n)) f = k;
    const bool f_long = f < 2;
    const Vec2 mid = inc.centre + (f_long ? inc.half_length : inc.half_width) * faces[f];
    const Vec2 along = f_long ? inc.axis_wide : inc.axis_long;
    const double along_half = f_long ? inc.half_width : inc.half_length;
    // The face as a segment in the reference face's tangent coordinate, clipped to its sides.
    const Vec2 p0 = mid - along_half * along, p1 = mid + along_half * along;
    const double s0 = dot(p0 - ref.centre, t), s1 = dot(p1 - ref.centre, t);
    double lo = std::max(std::min(s0, s1), -t_half), hi = std::min(std::max(s0, s1), t_half);
    // The ends of that part, each with its depth below the reference face (negative: the
    // gap above it); the impulse acts in the middle of those below it (of both, where the
    // boxes are only near).
    out.points = 0;
    Vec2 point;
    int below = 0;
    if (lo <= hi && s1 != s0) {
        const Vec2 q[2] = {p0 + ((lo - s0) / (s1 - s0)) * (p1 - p0), p0 + ((hi - s0) / (s1 - s0)) * (p1 - p0)};
        const Vec2 face_centre = ref.centre + ref_half * n;
        for (const Vec2& p : q) {
            out.at[out.points] = p;
            out.depth_at[out.points] = -dot(p - face_centre, n);
            if (out.depth_at[out.points] > 0.0) {
                point += p;
                ++below;
            }
            ++out.points;
        }
        point = below > 0 ? (1.0 / below) * point : 0.5 * (q[0] + q[1]);
    } else {  // the face lies beyond the other's sides (round-off at a corner's tip): the overlap as the axis gives it
        out.at[0] = point = 0.5 * (A.centre + B.centre);
        out.depth_at[0] = best;
        out.points = 1;
    }
    out.normal = a_refers ? -1.0 * n : n;  // from b into a
    out.depth = best;
    out.point = point;
    return true;
}

void candidate_pairs(const std::vector<Box>& boxes, double pad, std::vector<std::array<int, 2>>& out,
                     std::vector<std::array<long long, 2>>& cells) {
    out.clear();
    cells.clear();
    if (boxes.size() < 2) return;
    double widest = 0.0;
    for (const Box& b : boxes) widest = std::max({widest, b.extent_x(), b.extent_y()});
    const double h = 2.0 * (widest + pad);  // boxes whose bounding boxes overlap lie in neighbouring cells
    constexpr long long offset = 1LL << 30;
    const auto cell_of = [&](double v) { return (long long)std::floor(v / h) + offset; };
    const auto key = [](long long ix, long long iy) { return (ix << 31) | iy; };
    for (std::size_t k = 0; k < boxes.size(); ++k)
        cells.push_back({key(cell_of(boxes[k].centre.x), cell_of(boxes[k].centre.y)), (long long)k});
    std::sort(cells.begin(), cells.end());
    for (std::size_t a = 0; a < boxes.size(); ++a) {
        const Box& A = boxes[a];
        const long long ix = cell_of(A.centre.x), iy = cell_of(A.centre.y);
        for (long long dx = -1; dx <= 1; ++dx)
            for (long long dy = -1; dy <= 1; ++dy) {
                const long long k = key(ix + dx, iy + dy);
                auto it = std::lower_bound(cells.begin(), cells.end(), std::array<long long, 2>{k, -1});
                for (; it != cells.end() && (*it)[0] == k; ++it) {
                    const std::size_t b = std::size_t((*it)[1]);
                    if (b <= a) continue;
                    const Box& B = boxes[b];
                    if (std::fabs(A.centre.x - B.centre.x) <= A.extent_x() + B.extent_x() + 2.0 * pad &&
                        std::fabs(A.centre.y - B.centre.y) <= A.extent_y() + B.extent_y() + 2.0 * pad)
                        out.push_back({int(a), int(b)});
                }
            }
    }
    std::sort(out.begin(), out.end());
}

double deepest_body_overlap(const std::vector<Box>& boxes) {
    std::vector<std::array<int, 2>> pairs;
    std::vector<std::array<long long, 2>> cells;
    candidate_pairs(boxes, 0.0, pairs, cells);
    double deepest = 0.0;
    BodyCollision c;
    for (const auto& p : pairs)
        if (box_overlap(boxes[std::size_t(p[0])], boxes[std::size_t(p[1])], 0.0, c)) deepest = std::max(deepest, c.depth);
    return deepest;
}

namespace {

// The pairs of the group that overlap now (sorted by pair); with a margin, those within it
// too (depth down to −margin: the gap), into `out`.
void detect_pairs(const std::vector<GroupBody>& group, BodyCollisionScratch& s, double margin, std::vector<BodyCollision>& out) {
    s.boxes.resize(group.size());
    for (std::size_t k = 0; k < group.size(); ++k) s.boxes[k] = pose_of(*group[k].state, *group[k].body);
    candidate_pairs(s.boxes, margin, s.pairs, s.cells);
    out.clear();
    BodyCollision c;
    for (const auto& p : s.pairs)
        if (box_overlap(s.boxes[std::size_t(p[0])], s.boxes[std::size_t(p[1])], margin > 0.0 ? -margin : contact_depth, c)) {
            c.a = p[0];
            c.b = p[1];
            out.push_back(c);
        }
}

// The walls of the bodies taking part: overlaps, or with a margin the cells near them too.
void detect_walls(const ObstacleMap& obstacles, const std::vector<GroupBody>& group, BodyCollisionScratch& s, double margin) {
    s.wall_contacts.clear();
    for (std::size_t k = 0; k < group.size(); ++k) {
        if (!s.involved[k]) continue;
        s.walls.clear();
        obstacles.find_contacts(s.boxes[k], group[k].blocking, s.walls, margin > 0.0 ? -margin : contact_depth, margin);
        for (const ObstacleCollision& c : s.walls) s.wall_contacts.push_back({int(k), c});
    }
}

// Velocity of body g's point p.
Vec2 point_velocity(const BodyState& s, Vec2 p) { return Vec2{s.vx, s.vy} + spin(s.omega, p - Vec2{s.x, s.y}); }

void push(GroupBody& g, Vec2 impulse, Vec2 at) {
    BodyState& s = *g.state;
    s.vx += impulse.x / g.mass;
    s.vy += impulse.y / g.mass;
    s.omega += cross(at - Vec2{s.x, s.y}, impulse) / g.inertia;
}

// The impulses of one pass: sweeps over the contacts, deepest first, an impulse at each
// that approaches, until none approaches (a row of bodies against a wall passes an
// impact on from body to body: one sweep per link) or the sweeps run out.
void apply_impulses(std::vector<GroupBody>& group, BodyCollisionScratch& s) {
    struct Item {
        double depth;
        int kind;  // 0 pair, 1 wall
        int index;
    };
    std::vector<Item> order;
    order.reserve(s.contacts.size() + s.wall_contacts.size());
    for (std::size_t k = 0; k < s.contacts.size(); ++k) order.push_back({s.contacts[k].depth, 0, int(k)});
    for (std::size_t k = 0; k < s.wall_contacts.size(); ++k) order.push_back({s.wall_contacts[k].c.depth, 1, int(k)});
    std::stable_sort(order.begin(), order.end(), [](const Item& x, const Item& y) { return x.depth > y.depth; });
    constexpr int max_sweeps = 100;
    for (int sweep = 0; sweep < max_sweeps; ++sweep) {
        bool any = false;
        for (const Item& it : order) {
            if (it.kind == 0) {
                const BodyCollision& c = s.contacts[std::size_t(it.index)];
                GroupBody &A = group[std::size_t(c.a)], &B = group[std::size_t(c.b)];
                const double vn = dot(point_velocity(*A.state, c.point) - point_velocity(*B.state, c.point), c.normal);
                if (vn >= 0.0) continue;
                const double ra = cross(c.point - Vec2{A.state->x, A.state->y}, c.normal);
                const double rb = cross(c.point - Vec2{B.state->x, B.state->y}, c.normal);
                const double e = 0.5 * (A.body->def.restitution + B.body->def.restitution);
                const double j = -(1.0 + e) * vn / (1.0 / A.mass + 1.0 / B.mass + ra * ra / A.inertia + rb * rb / B.inertia);
                push(A, j * c.normal, c.point);
                push(B, -j * c.normal, c.point);
                any = true;
            } else {
                const BodyCollisionScratch::Wall& w = s.wall_contacts[std::size_t(it.index)];
                GroupBody& A = group[std::size_t(w.body)];
                const Vec2 r = w.c.point - Vec2{A.state->x, A.state->y};
                const double vn = dot(point_velocity(*A.state, w.c.point), w.c.normal);
                if (vn >= 0.0) continue;
                const double j = collision_impulse(vn, A.body->def.restitution, A.mass, A.inertia, r, w.c.normal);
                push(A, j * w.c.normal, w.c.point);
                any = true;
            }
        }
        if (!any) break;
    }
}

// One row of the moves out: a point where a body taking part overlaps, or nears, another
// body or a wall, linearised at the present poses.
struct OverlapRow {
    int a, b;       // the bodies that move (taking part); −1: a wall, or a body not taking part, held
    Vec2 n;         // from b (or what holds) into a
    double ra, rb;  // (p − x) × n of each body [m]
    double depth0;  // at the present poses [m]
};

// The rows of the bodies taking part: both ends of each face across another (so the turn
// is held too), and the walls. No move out is longer than all the overlaps together: a
// gap wider than that cannot be closed, and its row is left out.
std::vector<OverlapRow> overlap_rows(const std::vector<GroupBody>& group, const BodyCollisionScratch& s) {
    std::vector<OverlapRow> rows;
    rows.reserve(2 * s.near.size() + s.wall_contacts.size());
    const auto moving = [&](int k) { return s.involved[std::size_t(k)] ? k : -1; };
    for (const BodyCollision& c : s.near) {
        const int a = moving(c.a), b = moving(c.b);
        if (a < 0 && b < 0) continue;
        const BodyState &A = *group[std::size_t(c.a)].state, &B = *group[std::size_t(c.b)].state;
        for (int k = 0; k < c.points; ++k) {
            const double ra = cross(c.at[k] - Vec2{A.x, A.y}, c.normal), rb = cross(c.at[k] - Vec2{B.x, B.y}, c.normal);
            if (a >= 0)
                rows.push_back({a, b, c.normal, ra, rb, c.depth_at[k]});
            else  // seen from b: the normal turned round
                rows.push_back({b, -1, -1.0 * c.normal, rb, 0.0, c.depth_at[k]});
        }
    }
    for (const BodyCollisionScratch::Wall& w : s.wall_contacts) {
        const BodyState& A = *group[std::size_t(w.body)].state;
        rows.push_back({w.body, -1, w.c.normal, cross(w.c.point - Vec2{A.x, A.y}, w.c.normal), 0.0, w.c.depth});
    }
    double total = 0.0;
    for (const OverlapRow& r : rows) total += std::max(0.0, r.depth0);
    std::erase_if(rows, [&](const OverlapRow& r) { return r.depth0 < -2.0 * total - separation_slop; });
    return rows;
}

// Gauss-Seidel over the rows, adding each body's move dx [m] and turn dth [rad], until no
// row is deeper than `settled` or the sweeps run out. Sweeps forth and back in turn: a row
// of bodies pressed on a wall is cleared from whichever end it starts, in as many sweeps
// as it has bodies at most.
void relax_rows(const std::vector<GroupBody>& group, const std::vector<OverlapRow>& rows, double settled, std::vector<Vec2>& dx,
                std::vector<double>& dth) {
    const auto depth_now = [&](const OverlapRow& r) {
        double moved = dot(r.n, dx[std::size_t(r.a)]) + r.ra * dth[std::size_t(r.a)];
        if (r.b >= 0) moved -= dot(r.n, dx[std::size_t(r.b)]) + r.rb * dth[std::size_t(r.b)];
        return r.depth0 - moved;
    };
    std::vector<double> k_row(rows.size());
    for (std::size_t q = 0; q < rows.size(); ++q) {
        const OverlapRow& r = rows[q];
        const GroupBody& A = group[std::size_t(r.a)];
        k_row[q] = 1.0 / A.mass + r.ra * r.ra / A.inertia;
        if (r.b >= 0) {
            const GroupBody& B = group[std::size_t(r.b)];
            k_row[q] += 1.0 / B.mass + r.rb * r.rb / B.inertia;
        }
    }
    const auto relax = [&](std::size_t q) {
        const OverlapRow& r = rows[q];
        const double d = depth_now(r);
        if (!(d > -separation_slop)) return 0.0;
        const double p = (d + separation_slop) / k_row[q];
        const GroupBody& A = group[std::size_t(r.a)];
        dx[std::size_t(r.a)] += (p / A.mass) * r.n;
        dth[std::size_t(r.a)] += p * r.ra / A.inertia;
        if (r.b >= 0) {
            const GroupBody& B = group[std::size_t(r.b)];
            dx[std::size_t(r.b)] += (-p / B.mass) * r.n;
            dth[std::size_t(r.b)] -= p * r.rb / B.inertia;
        }
        return d;
    };
    for (int sweep = 0; sweep < 1000; ++sweep) {
        double deepest = 0.0;
        if (sweep % 2 == 0)
            for (std::size_t q = 0; q < rows.size(); ++q) deepest = std::max(deepest, relax(q));
        else
            for (std::size_t q = rows.size(); q-- > 0;) deepest = std::max(deepest, relax(q));
        if (deepest <= settled) break;
    }
}

// The bodies' share of the moves out of what overlaps (pairs, walls; the walls within the
// margin as gaps not to close): the rows relaxed at the present poses, then each body's
// move added to its own.
void move_out(std::vector<GroupBody>& group, BodyCollisionScratch& s, double settled, double margin) {
    const std::vector<OverlapRow> rows = overlap_rows(group, s);
    const std::size_t n = group.size();
    std::vector<Vec2> dx(n);
    std::vector<double> dth(n, 0.0);
    relax_rows(group, rows, settled, dx, dth);
    // No corner moves beyond the margin in one pass: the walls held as gaps are those within
    // it, and where the rows contradict each other (a body pressed into a corner by others
    // that cannot give way) their moves must not carry it through a wall.
    for (std::size_t k = 0; k < n; ++k) {
        const double scale = share_within(dx[k], dth[k], group[k].body->half_diagonal, margin);
        s.moved[k] += scale * dx[k];
        s.turned[k] += scale * dth[k];
    }
}

}  // namespace

namespace {

// A body joins the bodies that move when it first meets another: its rotation about a
// contact centroid is handed to its centre first, and the pose it reached is where its
// moves start from.
void join(std::vector<GroupBody>& group, BodyCollisionScratch& s) {
    for (const BodyCollision& c : s.contacts)
        for (const int k : {c.a, c.b})
            if (!s.involved[std::size_t(k)]) {
                s.involved[std::size_t(k)] = 1;
                group[std::size_t(k)].met = true;
                hand_pivot_to_centre(*group[std::size_t(k)].state);
                s.reached[std::size_t(k)] = *group[std::size_t(k)].state;
            }
}

// The bodies that move put where their step, the advance with the corrected velocities
// and the moves out take them; then what they touch found again.
void place(const ObstacleMap& obstacles, std::vector<GroupBody>& group, BodyCollisionScratch& s) {
    for (std::size_t k = 0; k < group.size(); ++k) {
        if (!s.involved[k]) continue;
        BodyState& st = *group[k].state;
        const BodyState& r = s.reached[k];
        st.x = r.x + s.advanced[k].x + s.moved[k].x;
        st.y = r.y + s.advanced[k].y + s.moved[k].y;
        st.theta = r.theta + s.advanced_turn[k] + s.turned[k];
    }
    detect_pairs(group, s, 0.0, s.contacts);
    join(group, s);
    detect_walls(obstacles, group, s, 0.0);
}

// The buildings the bodies' wall contacts touch, each with its fastest approach.
void note_buildings(std::vector<GroupBody>& group, const BodyCollisionScratch& s) {
    for (const auto& wc : s.wall_contacts) {
        if (wc.c.building <= 0) continue;
        GroupBody& g = group[std::size_t(wc.body)];
        const double approach = -dot(point_velocity(*g.state, wc.c.point), wc.c.normal);
        auto it =
            std::find_if(g.touches.begin(), g.touches.end(), [&](const BuildingTouch& t) { return t.building == wc.c.building; });
        if (it == g.touches.end())
            g.touches.push_back({wc.c.building, approach, wc.c.point});
        else if (approach > it->speed)
            *it = {wc.c.building, approach, wc.c.point};
    }
}

double deepest_left(const BodyCollisionScratch& s) {
    double d = 0.0;
    for (const BodyCollision& c : s.contacts) d = std::max(d, c.depth);
    for (const auto& wc : s.wall_contacts) d = std::max(d, wc.c.depth);
    return d;
}

}  // namespace

bool resolve_body_collisions(const ObstacleMap& obstacles, std::vector<GroupBody>& group, const BodyCollisionDef& def,
                             BodyCollisionScratch& s) {
    for (GroupBody& g : group) {
        g.met = false;
        g.body_overlap = g.wall_overlap = 0.0;
    }
    detect_pairs(group, s, 0.0, s.contacts);
    if (s.contacts.empty()) return false;
    const std::size_t n = group.size();
    s.involved.assign(n, 0);
    s.reached.resize(n);
    s.advanced.assign(n, Vec2{});
    s.advanced_turn.assign(n, 0.0);
    s.moved.assign(n, Vec2{});
    s.turned.assign(n, 0.0);
    join(group, s);
    detect_walls(obstacles, group, s, 0.0);
    if (def.note_buildings) note_buildings(group, s);
    // The impulses, then the poses advanced again from the start of the step with the
    // corrected momenta, once: a body's move from then on is only what clears overlaps.
    apply_impulses(group, s);
    const double w = def.move.new_weight * def.move.dt;
    for (std::size_t k = 0; k < n; ++k)
        if (s.involved[k]) {
            const BodyState &st = *group[k].state, &r = s.reached[k];
            s.advanced[k] = Vec2{w * (st.vx - r.vx), w * (st.vy - r.vy)};
            s.advanced_turn[k] = w * (st.omega - r.omega);
        }
    place(obstacles, group, s);
    // Passes until nothing overlaps deeper than a tenth of the tolerance: bodies pressed
    // together by the flow touch again at every step, and clearing them to round-off each
    // time would cost passes for nothing the output resolves.
    const double settled = 0.1 * def.move.tolerance;
    const double margin = clearing_margin_cells * std::min(obstacles.grid().dx, obstacles.grid().dy);
    for (int pass = 0; pass < def.max_passes && deepest_left(s) > settled; ++pass) {
        if (pass > 0) {  // contacts the moves made: impulses where they approach
            if (def.note_buildings) note_buildings(group, s);
            apply_impulses(group, s);
        }
        detect_walls(obstacles, group, s, margin);  // and the cells and bodies within the margin, as gaps
        detect_pairs(group, s, margin, s.near);
        move_out(group, s, settled, margin);
        place(obstacles, group, s);
    }
    for (const BodyCollision& c : s.contacts)
        for (const int k : {c.a, c.b}) group[std::size_t(k)].body_overlap = std::max(group[std::size_t(k)].body_overlap, c.depth);
    for (const auto& wc : s.wall_contacts)
        group[std::size_t(wc.body)].wall_overlap = std::max(group[std::size_t(wc.body)].wall_overlap, wc.c.depth);
    return true;
}

}  // namespace flotsam::debris
