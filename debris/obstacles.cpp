#include "debris/obstacles.hpp"

#include <algorithm>
#include <cmath>

namespace flotsam::debris {

ObstacleMap::ObstacleMap(const Grid& grid, std::vector<float> bed, std::vector<std::uint8_t> building)
    : grid_(grid), bed_(std::move(bed)), building_(std::move(building)) {}

bool ObstacleMap::blocked(int i, int j, double bottom, double step_height) const {
    if (i < 0 || j < 0 || i >= grid_.nx || j >= grid_.ny) return true;
    const std::size_t c = grid_.index(i, j);
    if (!building_.empty() && building_[c]) return true;
    return double(bed_[c]) > bottom + step_height;
}

void ObstacleMap::find_contacts(const Box& box, double bottom, double step_height, std::vector<ObstacleContact>& out,
                                double min_depth) const {
    const double hx = 0.5 * grid_.dx, hy = 0.5 * grid_.dy;
    const double ex = box.extent_x(), ey = box.extent_y();
    const int i0 = int(std::floor((box.centre.x - ex - grid_.x0) / grid_.dx + 0.5));
    const int i1 = int(std::floor((box.centre.x + ex - grid_.x0) / grid_.dx + 0.5));
    const int j0 = int(std::floor((box.centre.y - ey - grid_.y0) / grid_.dy + 0.5));
    const int j1 = int(std::floor((box.centre.y + ey - grid_.y0) / grid_.dy + 0.5));
    const auto corners = box.corners();
    const Vec2 axes[2] = {box.axis_long, box.axis_wide};
    const double halves[2] = {box.half_length, box.half_width};
    for (int j = j0; j <= j1; ++j) {
        for (int i = i0; i <= i1; ++i) {
            if (!blocked(i, j, bottom, step_height)) continue;
            const Vec2 c{grid_.x0 + i * grid_.dx, grid_.y0 + j * grid_.dy};
            // Separating axes: x and y of the cell, long and wide of the body. For each
            // direction n, "pen" is how far the body must move along +n to clear the cell.
            const double pen_px = (c.x + hx) - (box.centre.x - ex), pen_mx = (box.centre.x + ex) - (c.x - hx);
            const double pen_py = (c.y + hy) - (box.centre.y - ey), pen_my = (box.centre.y + ey) - (c.y - hy);
            if (pen_px <= 0 || pen_mx <= 0 || pen_py <= 0 || pen_my <= 0) continue;
            double pen_p[2], pen_m[2];
            bool separated = false;
            for (int k = 0; k < 2; ++k) {
                const double rc = hx * std::fabs(axes[k].x) + hy * std::fabs(axes[k].y);
                const double cb = dot(box.centre, axes[k]), cc = dot(c, axes[k]);
                pen_p[k] = (cc + rc) - (cb - halves[k]);
                pen_m[k] = (cb + halves[k]) - (cc - rc);
                if (pen_p[k] <= 0 || pen_m[k] <= 0) separated = true;
            }
            if (separated) continue;
            // Candidate normals. A cell face shared with another blocked cell is inside a
            // wall and is never a push-out direction (no snagging on internal edges); a body
            // axis is used only in the direction pointing from the cell toward the body.
            ObstacleContact best;
            best.depth = 1e300;
            auto consider = [&](Vec2 n, double pen) {
                if (pen < best.depth) {
                    best.depth = pen;
                    best.normal = n;
                }
            };
            if (!blocked(i + 1, j, bottom, step_height)) consider({1, 0}, pen_px);
            if (!blocked(i - 1, j, bottom, step_height)) consider({-1, 0}, pen_mx);
            if (!blocked(i, j + 1, bottom, step_height)) consider({0, 1}, pen_py);
            if (!blocked(i, j - 1, bottom, step_height)) consider({0, -1}, pen_my);
            const Vec2 rel = box.centre - c;
            for (int k = 0; k < 2; ++k) {
                const double side = dot(rel, axes[k]);
                if (side >= 0) consider(axes[k], pen_p[k]);
                if (side <= 0) consider(-1.0 * axes[k], pen_m[k]);
            }
            if (best.depth <= min_depth) continue;
            // The contact point: the mean of the body corners inside the cell and the cell
            // corners inside the body.
            Vec2 sum;
            int count = 0;
            for (const Vec2& p : corners)
                if (std::fabs(p.x - c.x) <= hx && std::fabs(p.y - c.y) <= hy) {
                    sum += p;
                    ++count;
                }
            for (const Vec2 d : {Vec2{hx, hy}, Vec2{-hx, hy}, Vec2{-hx, -hy}, Vec2{hx, -hy}})
                if (box.contains(c + d)) {
                    sum += c + d;
                    ++count;
                }
            best.point = count ? (1.0 / count) * sum : 0.5 * (box.centre + c);
            out.push_back(best);
        }
    }
}

}  // namespace flotsam::debris
