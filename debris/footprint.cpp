#include "debris/footprint.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace flotsam::debris {

namespace {

// Overlaps below this fraction of a cell are round-off, not contact [-].
constexpr double sliver_fraction = 1e-9;

using Poly = FootprintPoly;

// The vertex after k of a polygon of n vertices (k + 1) % n, without an integer division.
int next_vertex(int k, int n) { return k + 1 < n ? k + 1 : 0; }

// Keeps the part of `in` where s * (coord - c) ≤ 0, coord = x (axis 0) or y (axis 1).
Poly clip(const Poly& in, int axis, double c, double s) {
    Poly out;
    for (int k = 0; k < in.n; ++k) {
        const Vec2 a = in.p[k], b = in.p[next_vertex(k, in.n)];
        const double da = s * ((axis == 0 ? a.x : a.y) - c), db = s * ((axis == 0 ? b.x : b.y) - c);
        if (da <= 0.0) out.p[out.n++] = a;
        if ((da < 0.0 && db > 0.0) || (da > 0.0 && db < 0.0)) {
            const double f = da / (da - db);
            out.p[out.n++] = a + f * (b - a);
        }
    }
    return out;
}

// Area and centroid of a convex polygon (shoelace), its vertices taken from `origin`, a
// point near it: in map coordinates (metres from the world's origin) the sums' round-off
// put a thin clip's centroid a cell or more away (a triangle of 1e-13 m² at x = 4.3 m:
// 1.5 cm); from the cell's centre it is some 1e-12 m.
void area_centroid(const Poly& q, Vec2 origin, double& area, Vec2& centroid) {
    double a2 = 0.0, cx = 0.0, cy = 0.0;
    for (int k = 0; k < q.n; ++k) {
        const Vec2 p0 = q.p[k] - origin, p1 = q.p[next_vertex(k, q.n)] - origin;
        const double c = cross(p0, p1);
        a2 += c;
        cx += (p0.x + p1.x) * c;
        cy += (p0.y + p1.y) * c;
    }
    area = 0.5 * a2;
    centroid = std::fabs(a2) > 0.0 ? origin + Vec2{cx / (3.0 * a2), cy / (3.0 * a2)} : (q.n ? q.p[0] : Vec2{});
}

// The x interval [x0, x1] of the line y = `y` that lies inside the box shrunk by `inset`
// on every side (empty: x0 > x1).
struct Span {
    double x0, x1;
};
Span inner_span(const Box& box, double y, double inset) {
    Span span{-std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
    const Vec2 axes[2] = {box.axis_long, box.axis_wide};
    const double halves[2] = {box.half_length - inset, box.half_width - inset};
    for (int k = 0; k < 2; ++k) {
        // Inside the slab: |(x − cx) a.x + (y − cy) a.y| ≤ half.
        const Vec2 a = axes[k];
        const double along_y = (y - box.centre.y) * a.y;
        if (a.x == 0.0) {
            if (!(std::fabs(along_y) <= halves[k])) return Span{1.0, 0.0};
            continue;
        }
        double lo = box.centre.x + (-halves[k] - along_y) / a.x, hi = box.centre.x + (halves[k] - along_y) / a.x;
        if (lo > hi) std::swap(lo, hi);
        span.x0 = std::max(span.x0, lo);
        span.x1 = std::min(span.x1, hi);
    }
    return span;
}

}  // namespace

void FootprintCache::set_box(const Box& box, const Grid& grid) {
    box_ = box;
    grid_ = grid;
    valid_ = true;
    row_count_ = 0;
    const auto corners = box.corners();
    Poly body;
    for (const Vec2& c : corners) body.p[body.n++] = c;
    const double hy = 0.5 * grid.dy;
    // A cell inside the footprint shrunk by this much passes the four corner tests below
    // whatever the round-off (some 1e-15 m), so it needs none of them [m].
    const double inset = 1e-6 * std::min(grid.dx, grid.dy);
    const int j0 = std::max(0, int(std::floor((box.centre.y - box.extent_y() - grid.y0) / grid.dy + 0.5)));
    const int j1 = std::min(grid.ny - 1, int(std::floor((box.centre.y + box.extent_y() - grid.y0) / grid.dy + 0.5)));
    for (int j = j0; j <= j1; ++j) {
        const double yc = grid.y(j);
        // The footprint cut to this row of cells, then (clip_row) to each cell of the row.
        const Poly part = clip(clip(body, 1, yc - hy, -1.0), 1, yc + hy, 1.0);
        if (part.n < 3) continue;
        if (row_count_ == rows_.size()) rows_.emplace_back();
        Row& row = rows_[row_count_++];
        row.j = j;
        row.part = part;
        row.clipped = false;
        row.patches.clear();
        // A cell wholly beside the row's part of the footprint clips to nothing: skipped
        // before clipping (strictly beside: a cell touching it still goes through the clip).
        row.x0 = row.x1 = part.p[0].x;
        for (int k = 1; k < part.n; ++k) {
            row.x0 = std::min(row.x0, part.p[k].x);
            row.x1 = std::max(row.x1, part.p[k].x);
        }
        // Where both of the row's edges lie inside the shrunk footprint, so do whole cells
        // (the footprint is convex).
        const Span lower = inner_span(box, yc - hy, inset), upper = inner_span(box, yc + hy, inset);
        row.inner_x0 = std::max(lower.x0, upper.x0);
        row.inner_x1 = std::min(lower.x1, upper.x1);
    }
}

void FootprintCache::clip_row(Row& row) const {
    const Grid& grid = grid_;
    const Box& box = box_;
    const double hx = 0.5 * grid.dx, hy = 0.5 * grid.dy;
    const int i0 = std::max(0, int(std::floor((box.centre.x - box.extent_x() - grid.x0) / grid.dx + 0.5)));
    const int i1 = std::min(grid.nx - 1, int(std::floor((box.centre.x + box.extent_x() - grid.x0) / grid.dx + 0.5)));
    const double yc = grid.y(row.j);
    for (int i = i0; i <= i1; ++i) {
        const double xc = grid.x(i);
        if (xc + hx < row.x0 || xc - hx > row.x1) continue;
        const Vec2 cc{xc, yc};
        FootprintPatch patch;
        // Fast path: a cell whose four corners are inside the footprint is covered whole.
        const bool whole = (xc - hx >= row.inner_x0 && xc + hx <= row.inner_x1) ||
                           (box.contains(cc + Vec2{hx, hy}) && box.contains(cc + Vec2{-hx, hy}) &&
                            box.contains(cc + Vec2{hx, -hy}) && box.contains(cc + Vec2{-hx, -hy}));
        if (whole) {
            patch.area = grid.dx * grid.dy;
            patch.centroid = cc;
        } else {
            const Poly cell = clip(clip(row.part, 0, xc - hx, -1.0), 0, xc + hx, 1.0);
            if (cell.n < 3) continue;
            area_centroid(cell, cc, patch.area, patch.centroid);
            // A clip this thin is round-off where an edge of the body lies on a cell
            // edge (a grid-aligned start); its centroid, area / area, is noise that
            // can land anywhere. It holds no ground: left out.
            if (!(patch.area > sliver_fraction * grid.dx * grid.dy)) continue;
        }
        row.patches.push_back(patch);
    }
}

const std::vector<FootprintPatch>& FootprintCache::patches(const Box& box, const Grid& grid, RowFilter wanted,
                                                           const void* context) {
    const auto same = [](const auto& a, const auto& b) { return std::memcmp(&a, &b, sizeof a) == 0; };
    const bool same_grid = grid.nx == grid_.nx && grid.ny == grid_.ny && same(grid.dx, grid_.dx) && same(grid.dy, grid_.dy) &&
                           same(grid.x0, grid_.x0) && same(grid.y0, grid_.y0);
    bool changed = !(valid_ && same_grid && same(box, box_));
    if (changed) set_box(box, grid);
    if (taken_.size() != row_count_) {
        taken_.assign(row_count_, 0);
        changed = true;
    }
    const double hy = 0.5 * grid.dy;
    for (std::size_t r = 0; r < row_count_; ++r) {
        Row& row = rows_[r];
        const double yc = grid.y(row.j);
        const char take = !wanted || wanted(context, row.x0, row.x1, yc - hy, yc + hy);
        rows_left_out_ += !take;
        if (take && !row.clipped) {
            clip_row(row);
            row.clipped = true;
        }
        changed = changed || take != taken_[r];
        taken_[r] = take;
    }
    if (changed) {
        patches_.clear();
        for (std::size_t r = 0; r < row_count_; ++r)
            if (taken_[r]) patches_.insert(patches_.end(), rows_[r].patches.begin(), rows_[r].patches.end());
    }
    return patches_;
}

void footprint_patches(const Box& box, const Grid& grid, std::vector<FootprintPatch>& out) {
    FootprintCache every_row;
    const std::vector<FootprintPatch>& p = every_row.patches(box, grid);
    out.insert(out.end(), p.begin(), p.end());
}

}  // namespace flotsam::debris
