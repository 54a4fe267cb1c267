// The body's footprint: an oriented rectangle in the plane.
#pragma once
#include <array>
#include <cmath>

#include "debris/kernels.hpp"

namespace flotsam::debris {

struct Box {
    Vec2 centre;             // [m]
    Vec2 axis_long;          // unit vector along the length
    Vec2 axis_wide;          // unit vector along the width (axis_long turned +90°)
    double half_length = 0;  // [m]
    double half_width = 0;   // [m]

    static Box make(Vec2 centre, double theta, double length, double width) {
        const Vec2 a{std::cos(theta), std::sin(theta)};
        return Box{centre, a, Vec2{-a.y, a.x}, 0.5 * length, 0.5 * width};
    }
    // Counter-clockwise from the (+long, +wide) corner.
    std::array<Vec2, 4> corners() const {
        const Vec2 l = half_length * axis_long, w = half_width * axis_wide;
        return {centre + l + w, centre - l + w, centre - l - w, centre + l - w};
    }
    // Half extents of the axis-aligned bounding box [m].
    double extent_x() const { return half_length * std::fabs(axis_long.x) + half_width * std::fabs(axis_wide.x); }
    double extent_y() const { return half_length * std::fabs(axis_long.y) + half_width * std::fabs(axis_wide.y); }
    bool contains(Vec2 p, double eps = 0.0) const {
        const Vec2 r = p - centre;
        return std::fabs(dot(r, axis_long)) < half_length + eps && std::fabs(dot(r, axis_wide)) < half_width + eps;
    }
};

}  // namespace flotsam::debris
