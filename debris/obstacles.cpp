#include "debris/obstacles.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "formats/scene.hpp"

namespace flotsam::debris {

ObstacleMap::ObstacleMap(const Grid& grid, std::vector<float> bed, std::vector<std::uint8_t> building)
    : grid_(grid), bed_(std::move(bed)), open_ground_(bed_) {
    if (std::find(building.begin(), building.end(), 1) != building.end() && building.size() == bed_.size())
        building_id_ = building_components(grid_.nx, grid_.ny, building);
    constexpr float inf = std::numeric_limits<float>::infinity();
    const auto is_building = [&](std::size_t c) { return c < building.size() && building[c]; };
    for (std::size_t c = 0; c < bed_.size(); ++c)
        if (is_building(c)) open_ground_[c] = -inf;
    for (const BlockingGround rule : {BlockingGround::land, BlockingGround::any, BlockingGround::none}) {
        Walls& w = walls_[std::size_t(rule)];
        w.open_top.resize(bed_.size());
        for (std::size_t c = 0; c < bed_.size(); ++c) {
            // Land: ground above still water (z = 0 in every scene and flow file).
            const bool can_block = rule == BlockingGround::any || (rule == BlockingGround::land && bed_[c] > 0.0f);
            w.open_top[c] = !is_building(c) && can_block ? bed_[c] : -inf;
        }
        w.top = w.open_top;
        for (std::size_t c = 0; c < bed_.size(); ++c)
            if (is_building(c)) w.top[c] = inf;
        wall_top_blocks_[std::size_t(rule)] = BlockMax(grid_, w.top);
        open_top_blocks_[std::size_t(rule)] = BlockMax(grid_, w.open_top);
    }
}

ObstacleMap::BlockMax::BlockMax(const Grid& grid, const std::vector<float>& cells)
    : nbx((grid.nx + block_cells - 1) / block_cells),
      nby((grid.ny + block_cells - 1) / block_cells),
      max(std::size_t(nbx) * std::size_t(nby), -std::numeric_limits<float>::infinity()) {
    for (int j = 0; j < grid.ny; ++j)
        for (int i = 0; i < grid.nx; ++i) {
            float& m = max[std::size_t(j / block_cells) * std::size_t(nbx) + std::size_t(i / block_cells)];
            m = std::max(m, cells[grid.index(i, j)]);
        }
}

float ObstacleMap::BlockMax::bound(int i0, int i1, int j0, int j1) const {
    float m = -std::numeric_limits<float>::infinity();
    for (int bj = j0 / block_cells; bj <= j1 / block_cells; ++bj)
        for (int bi = i0 / block_cells; bi <= i1 / block_cells; ++bi)
            m = std::max(m, max[std::size_t(bj) * std::size_t(nbx) + std::size_t(bi)]);
    return m;
}

bool ObstacleMap::blocked(int i, int j, double bottom, double step_height, BlockingGround rule) const {
    if (i < 0 || j < 0 || i >= grid_.nx || j >= grid_.ny) return true;
    return double(walls(rule).top[grid_.index(i, j)]) > bottom + step_height;
}

bool ObstacleMap::blocked(int i, int j, const Blocking& by) const {
    if (!blocked(i, j, by.bottom, by.step_height, by.rule)) return false;
    // Ground (not a building, not the edge) that the body would float over does not block.
    if (by.water && i >= 0 && j >= 0 && i < grid_.nx && j < grid_.ny && std::isfinite(open_ground_[grid_.index(i, j)]))
        return !(by.water->depth(i, j) >= by.draft);
    return true;
}

namespace {

// Largest of row[i0 .. i1] (vectorised; exact: a max does not depend on the order).
float row_max(const float* row, int i0, int i1) {
    float m = -std::numeric_limits<float>::infinity();
#pragma omp simd reduction(max : m)
    for (int i = i0; i <= i1; ++i) m = std::max(m, row[i]);
    return m;
}

// The separating-axis test of a body against the square cell of half sizes hx, hy at c.
// For each direction n, "pen" is how far the body must move along +n to clear the cell:
// x and y of the cell (px along +x, mx along −x, ...), then the body's long and wide
// axes (p along +axis, m along −axis). They overlap where every pen is positive.
struct Penetration {
    double px, mx, py, my;
    double p[2], m[2];
    bool overlap() const { return depth() > 0.0; }
    double depth() const { return std::min({px, mx, py, my, p[0], m[0], p[1], m[1]}); }
};

Penetration penetration(const Box& box, Vec2 c, double hx, double hy) {
    const double ex = box.extent_x(), ey = box.extent_y();
    Penetration pen;
    pen.px = (c.x + hx) - (box.centre.x - ex);
    pen.mx = (box.centre.x + ex) - (c.x - hx);
    pen.py = (c.y + hy) - (box.centre.y - ey);
    pen.my = (box.centre.y + ey) - (c.y - hy);
    const Vec2 axes[2] = {box.axis_long, box.axis_wide};
    const double halves[2] = {box.half_length, box.half_width};
    for (int k = 0; k < 2; ++k) {
        const double rc = hx * std::fabs(axes[k].x) + hy * std::fabs(axes[k].y);
        const double cb = dot(box.centre, axes[k]), cc = dot(c, axes[k]);
        pen.p[k] = (cc + rc) - (cb - halves[k]);
        pen.m[k] = (cb + halves[k]) - (cc - rc);
    }
    return pen;
}

// The body's outline for the row scans: each edge from corner k to corner k + 1, with
// its run in x per unit of y (0 along x).
struct Outline {
    Vec2 from[4];
    double to_y[4];
    double x_per_y[4];
    explicit Outline(const Box& box) {
        const auto c = box.corners();
        for (int k = 0; k < 4; ++k) {
            const Vec2 a = c[k], b = c[(k + 1) & 3];
            from[k] = a;
            to_y[k] = b.y;
            x_per_y[k] = b.y != a.y ? (b.x - a.x) / (b.y - a.y) : 0.0;
        }
    }
};

// The x range of the part of the body within the band y0 ≤ y ≤ y1: the corners in the
// band and the edges' crossings of its two lines (empty, x0 > x1, where none). Good to
// round-off (some 1e-15 m): the scans widen it or ask for more overlap than that.
struct XRange {
    double x0, x1;
};
XRange x_range_in_band(const Outline& body, double y0, double y1) {
    XRange r{std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
    const auto include = [&r](double x) {
        r.x0 = std::min(r.x0, x);
        r.x1 = std::max(r.x1, x);
    };
    for (int k = 0; k < 4; ++k) {
        const Vec2 a = body.from[k];
        if (a.y >= y0 && a.y <= y1) include(a.x);
        for (const double y : {y0, y1})
            if ((a.y - y) * (body.to_y[k] - y) < 0.0) include(a.x + (y - a.y) * body.x_per_y[k]);
    }
    return r;
}

}  // namespace

ObstacleMap::CellRange ObstacleMap::cells_touching(const Box& box, int pad) const {
    const double ex = box.extent_x(), ey = box.extent_y();
    const Double4 f = Double4{box.centre.x - ex - grid_.x0, box.centre.x + ex - grid_.x0, box.centre.y - ey - grid_.y0,
                              box.centre.y + ey - grid_.y0} /
                      Double4{grid_.dx, grid_.dx, grid_.dy, grid_.dy};  // one packed division
    return CellRange{int(std::floor(f[0] + 0.5)) - pad, int(std::floor(f[1] + 0.5)) + pad, int(std::floor(f[2] + 0.5)) - pad,
                     int(std::floor(f[3] + 0.5)) + pad};
}

double ObstacleMap::highest_ground(const Box& box, double min_overlap) const {
    const CellRange r = cells_touching(box, 0);
    const Outline outline(box);
    const double hy = 0.5 * grid_.dy;
    double top = -std::numeric_limits<double>::infinity();
    for (int j = std::max(r.j0, 0); j <= std::min(r.j1, grid_.ny - 1); ++j) {
        // Only the cells that meet the body's part within the row's band can be under it
        // by more than min_overlap (> 0); those beside it are not tested.
        const double yc = grid_.y0 + j * grid_.dy;
        const XRange part = x_range_in_band(outline, yc - hy, yc + hy);
        if (!(part.x0 <= part.x1)) continue;
        const int i0 = std::max({r.i0, 0, int(std::floor((part.x0 - grid_.x0) / grid_.dx + 0.5))});
        const int i1 = std::min({r.i1, grid_.nx - 1, int(std::floor((part.x1 - grid_.x0) / grid_.dx + 0.5))});
        for (int i = i0; i <= i1; ++i) {
            const std::size_t c = grid_.index(i, j);
            if (double(open_ground_[c]) <= top) continue;  // a building (-inf) or no higher
            const Vec2 centre{grid_.x0 + i * grid_.dx, grid_.y0 + j * grid_.dy};
            if (penetration(box, centre, 0.5 * grid_.dx, 0.5 * grid_.dy).depth() > min_overlap) top = double(bed_[c]);
        }
    }
    return top;
}

bool ObstacleMap::ground_above(const Box& box, double level, BlockingGround rule) const {
    const CellRange r = cells_touching(box, 1);
    const int i0 = std::max(r.i0, 0), i1 = std::min(r.i1, grid_.nx - 1);
    const int j0 = std::max(r.j0, 0), j1 = std::min(r.j1, grid_.ny - 1);
    if (i0 > i1 || j0 > j1 || !(double(open_top_blocks_[std::size_t(rule)].bound(i0, i1, j0, j1)) > level)) return false;
    const std::vector<float>& open_top = walls(rule).open_top;
    for (int j = j0; j <= j1; ++j)
        if (i0 <= i1 && double(row_max(open_top.data() + grid_.index(0, j), i0, i1)) > level) return true;
    return false;
}

namespace {

// Where the impulse of a contact with normal n acts when the body only nears the cell (no
// overlap): the body's point nearest the cell along n, on the body. Its supporting
// feature toward the cell (a corner, or a face lying across n) cut to the cell's extent
// across n, and its middle taken: for a face, the part of it facing the cell. The lever
// arm's moment (r × n) does not depend on where along n the point lies.
Vec2 nearest_point_toward(const Box& box, Vec2 cell, double hx, double hy, Vec2 n) {
    const auto corners = box.corners();
    const Vec2 t{-n.y, n.x};
    double low = 1e300;
    for (const Vec2& p : corners) low = std::min(low, dot(p, n));
    const double flat = 1e-9 * (box.half_length + box.half_width);  // corners level to round-off
    double a = 1e300, b = -1e300;                                   // the feature's extent along t
    for (const Vec2& p : corners)
        if (dot(p, n) <= low + flat) {
            a = std::min(a, dot(p, t));
            b = std::max(b, dot(p, t));
        }
    const double reach = hx * std::fabs(t.x) + hy * std::fabs(t.y);  // the cell's half extent along t
    const double c = dot(cell, t);
    double s0 = std::max(a, c - reach), s1 = std::min(b, c + reach);
    if (s0 > s1) s0 = s1 = s1 < a ? a : b;  // no common part: the feature's end nearest the cell
    return low * n + 0.5 * (s0 + s1) * t;
}

// The gap between a cell and the body's part across from it, along a face normal n of the
// cell (into the body): the body's point lowest along n within the cell's slab across n
// (its corners there and its edges' crossings of the slab's sides), and how far that point
// lies beyond the cell's face [m]. False where no part of the body lies across the cell.
bool gap_across(const Box& box, Vec2 cell, double hx, double hy, Vec2 n, Vec2& point, double& gap) {
    const Vec2 t{-n.y, n.x};
    const double reach = hx * std::fabs(t.x) + hy * std::fabs(t.y), c = dot(cell, t);
    const auto corners = box.corners();
    double low = 1e300;
    const auto take = [&](Vec2 p) {
        if (const double h = dot(p, n); h < low) {
            low = h;
            point = p;
        }
    };
    for (int k = 0; k < 4; ++k) {
        const Vec2 p = corners[k], q = corners[(k + 1) & 3];
        const double sp = dot(p, t), sq = dot(q, t);
        if (std::fabs(sp - c) <= reach) take(p);
        for (const double side : {c - reach, c + reach})
            if ((sp - side) * (sq - side) < 0.0) take(p + ((side - sp) / (sq - sp)) * (q - p));
    }
    if (!(low < 1e300)) return false;
    gap = low - (dot(cell, n) + hx * std::fabs(n.x) + hy * std::fabs(n.y));
    return true;
}

// The push-out direction of a body from the blocked cell at c and the depth along it: the
// least of the candidate normals' penetrations; depth 1e300 where every side of the cell
// lies inside the wall. A cell face shared with another blocked cell is inside a wall and
// is never a push-out direction (no snagging on internal edges); a body axis is used only
// in the direction pointing from the cell toward the body. And how far the body reaches
// into the cell through the faces it shares with other blocked cells (the least; 1e300
// where none is shared).
struct PushOut {
    ObstacleCollision best;
    double through_wall = 1e300;  // [m]
};

// shut: the cell's neighbours across its faces +x, −x, +y, −y are blocked.
PushOut push_out(const Box& box, Vec2 c, const Penetration& pen, const std::array<bool, 4>& shut) {
    PushOut out;
    ObstacleCollision& best = out.best;
    best.depth = 1e300;
    auto consider = [&](Vec2 n, double depth) {
        if (depth < best.depth) {
            best.depth = depth;
            best.normal = n;
        }
    };
    const Vec2 faces[4] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
    const double through[4] = {pen.px, pen.mx, pen.py, pen.my};
    for (int f = 0; f < 4; ++f) {
        if (shut[f])
            out.through_wall = std::min(out.through_wall, through[f]);
        else
            consider(faces[f], through[f]);
    }
    // A body axis n pushes the body off the cell's corner that points along n (the
    // cell's vertex in its face): only where that corner is one of the obstacle's
    // own, its two cells beside it along n open. Inside a straight wall the next cell
    // goes on where the corner is, and the push would be along the wall.
    const auto corner_exposed = [&](Vec2 n) {
        const bool x_open = n.x > 0.0 ? !shut[0] : (n.x < 0.0 ? !shut[1] : true);
        const bool y_open = n.y > 0.0 ? !shut[2] : (n.y < 0.0 ? !shut[3] : true);
        return x_open && y_open;
    };
    const Vec2 axes[2] = {box.axis_long, box.axis_wide};
    const Vec2 rel = box.centre - c;
    for (int k = 0; k < 2; ++k) {
        const double side = dot(rel, axes[k]);
        if (side >= 0 && corner_exposed(axes[k])) consider(axes[k], pen.p[k]);
        if (side <= 0 && corner_exposed(-1.0 * axes[k])) consider(-1.0 * axes[k], pen.m[k]);
    }
    return out;
}

// Where the impulse of an overlap with the cell at c acts: the mean of the body corners
// inside the cell and the cell corners inside the body (both in the body); where there
// are none, nearest_point_toward along n.
Vec2 overlap_point(const Box& box, Vec2 c, double hx, double hy, Vec2 n) {
    Vec2 sum;
    int count = 0;
    for (const Vec2& p : box.corners())
        if (std::fabs(p.x - c.x) <= hx && std::fabs(p.y - c.y) <= hy) {
            sum += p;
            ++count;
        }
    for (const Vec2 d : {Vec2{hx, hy}, Vec2{-hx, hy}, Vec2{-hx, -hy}, Vec2{hx, -hy}})
        if (box.contains(c + d)) {
            sum += c + d;
            ++count;
        }
    return count ? (1.0 / count) * sum : nearest_point_toward(box, c, hx, hy, n);
}

// With a margin (the moves out), beside an overlap `contact` along a face of the cell at
// c: the body's corners across from that face but not in the cell, within the margin,
// are gaps the move may not close, so that turning one end of a body's side out of a cell
// larger than it does not turn the other in. Appends them.
void corner_gaps(const Box& box, Vec2 c, double hx, double hy, const ObstacleCollision& contact, double margin,
                 std::int32_t building, std::vector<ObstacleCollision>& out) {
    const Vec2 n = contact.normal, t{-n.y, n.x};
    const double face = dot(c, n) + hx * std::fabs(n.x) + hy * std::fabs(n.y);
    const double across = hx * std::fabs(t.x) + hy * std::fabs(t.y);
    for (const Vec2& p : box.corners())
        if (std::fabs(dot(p - c, t)) <= across && !(std::fabs(p.x - c.x) <= hx && std::fabs(p.y - c.y) <= hy))
            if (const double depth = face - dot(p, n); depth > -margin && depth <= 0.0) {
                ObstacleCollision gap = contact;
                gap.depth = depth;
                gap.point = p + depth * n;
                gap.building = building;
                out.push_back(gap);
            }
}

}  // namespace

bool ObstacleMap::cell_contact(const Box& box, int i, int j, const Blocking& by, double min_depth, double margin,
                               std::vector<ObstacleCollision>& out) const {
    const double hx = 0.5 * grid_.dx, hy = 0.5 * grid_.dy;
    const Vec2 c{grid_.x0 + i * grid_.dx, grid_.y0 + j * grid_.dy};
    const Penetration pen = penetration(box, c, hx, hy);
    const double separation = pen.depth();  // > 0: overlap; ≤ 0: minus a lower bound of the gap
    // Without a margin, only a cell the body reaches into by more than min_depth
    // along every axis: one it only grazes (an edge on the cell's line, to round-off)
    // is no contact, whatever its depth along the normals that are left.
    if (!(separation > -margin) || (margin == 0.0 && !(separation > min_depth))) return false;
    const std::array<bool, 4> shut{blocked(i + 1, j, by), blocked(i - 1, j, by), blocked(i, j + 1, by), blocked(i, j - 1, by)};
    const PushOut push = push_out(box, c, pen, shut);
    ObstacleCollision best = push.best;
    if (best.depth == 1e300) return false;  // every side of it lies inside the wall
    if (best.depth <= min_depth) return false;
    // Reached through a face it shares with another blocked cell (a wall's inside corner):
    // where the body is less than half the cell past that face and more than half the cell
    // from the open one, it came in from the neighbour's side, which holds it. Out through
    // the far face would carry the body through the cell (a car's corner in an L-shaped
    // building's inside corner on 10 m cells: 11.8 m deep, into the building).
    const double half = std::min(hx, hy);
    if (separation > 0.0 && push.through_wall < half && best.depth > half) return false;
    // Apart from the body along an axis that lies inside a wall: a nearer blocked
    // neighbour holds that side, and this cell is no contact.
    if (separation <= 0.0 && best.depth > 0.0) return false;
    const bool along_face = best.normal.x == 0.0 || best.normal.y == 0.0;
    if (separation > 0.0) {
        best.point = overlap_point(box, c, hx, hy, best.normal);
        if (margin > 0.0 && along_face) corner_gaps(box, c, hx, hy, best, margin, building_id(i, j), out);
    } else if (along_face) {
        // Apart along one of the cell's faces: the gap to the body's part across
        // from this cell (the separating axis bounds the gap of the whole body).
        double gap = 0.0;
        if (!gap_across(box, c, hx, hy, best.normal, best.point, gap) || !(-gap > min_depth)) return false;
        best.depth = -gap;
    } else {
        best.point = nearest_point_toward(box, c, hx, hy, best.normal);
    }
    best.building = building_id(i, j);
    out.push_back(best);
    return true;
}

void ObstacleMap::find_contacts(const Box& box, const Blocking& by, std::vector<ObstacleCollision>& out, double min_depth,
                                double margin) const {
    const std::vector<float>& wall_top = walls(by.rule).top;
    const double reach = by.bottom + by.step_height;
    const double hy = 0.5 * grid_.dy;
    Box wide = box;  // chooses the cells looked at: those within the margin
    wide.half_length += margin;
    wide.half_width += margin;
    const CellRange r = cells_touching(wide, 0);
    const bool inside_x = r.i0 >= 0 && r.i1 < grid_.nx;
    // Nothing within the grid that rises above the bottom's reach: no contact at all.
    if (inside_x && r.j0 >= 0 && r.j1 < grid_.ny &&
        !(double(wall_top_blocks_[std::size_t(by.rule)].bound(r.i0, r.i1, r.j0, r.j1)) > reach))
        return;
    // A cell that the body misses by more than this cannot overlap it whatever the
    // round-off (some 1e-15 m) of the separating-axis test [m].
    const double clear = 1e-6 * std::min(grid_.dx, grid_.dy);
    const Outline outline(wide);
    for (int j = r.j0; j <= r.j1; ++j) {
        // A row inside the grid with nothing above the bottom's reach under the whole
        // bounding box holds no contact: ruled out before the body's part in it is found.
        if (inside_x && j >= 0 && j < grid_.ny && !(double(row_max(wall_top.data() + grid_.index(0, j), r.i0, r.i1)) > reach))
            continue;
        // Only the row's cells that meet the (widened) body's part within the row's band,
        // widened by `clear`, can be found: the cells beside it are not tested.
        const double yc = grid_.y0 + j * grid_.dy;
        const XRange part = x_range_in_band(outline, yc - hy - clear, yc + hy + clear);
        if (!(part.x0 <= part.x1)) continue;
        const int i0 = std::max(r.i0, int(std::floor((part.x0 - clear - grid_.x0) / grid_.dx + 0.5)));
        const int i1 = std::min(r.i1, int(std::floor((part.x1 + clear - grid_.x0) / grid_.dx + 0.5)));
        // A row inside the grid with nothing above the bottom's reach holds no contact.
        if (i0 > i1 || (i0 >= 0 && i1 < grid_.nx && j >= 0 && j < grid_.ny &&
                        !(double(row_max(wall_top.data() + grid_.index(0, j), i0, i1)) > reach)))
            continue;
        for (int i = i0; i <= i1; ++i) {
            if (!blocked(i, j, by)) continue;
            cell_contact(box, i, j, by, min_depth, margin, out);
        }
    }
}

}  // namespace flotsam::debris
