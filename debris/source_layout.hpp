// Bodies laid out in a yard: a container yard or a car park given as a polygon, filled
// with rows of identical bodies. The rows run along the stacks' heading; neighbours stand
// a clear gap apart along and across it; a body is placed only where its whole footprint
// lies inside the polygon (holes excluded), so no two bodies overlap and none crosses the
// yard's outline. Pure geometry, no GDAL (app/ reads the polygons, data/source_features).
#pragma once
#include <array>
#include <cmath>
#include <optional>
#include <vector>

namespace flotsam::debris {

using Ring = std::vector<std::array<double, 2>>;  // polygon ring, (x, y) [m]; closing point optional

struct Yard {
    std::vector<Ring> rings;         // the outline first, then its holes [m]
    double heading_deg = std::nan("");  // stacks' long axis from +x, counter-clockwise [degree]; NaN: the outline's longest edge
    double gap = std::nan("");          // clear distance between neighbours, along and across [m]; NaN: the widest that fits `count`
    int count = 0;                      // bodies wanted; 0: every place at `gap`
};

struct Pose {
    double x = 0.0, y = 0.0;  // centre [m]
    double heading = 0.0;     // long axis from +x, counter-clockwise [rad]
};

struct YardLayout {
    std::vector<Pose> poses;  // in rows: across the heading outermost, along it fastest
    double gap = 0.0;         // the gap used [m]
    double heading_deg = 0.0; // the heading used [degree]
    int capacity = 0;         // places at gap 0: the most bodies the yard holds
};

// The places for bodies of `length` × `width` [m] in the yard. With a gap, every place the
// lattice at that gap has inside the outline (the first `count`-spread of them when a
// count is also given); with a count only, the widest gap whose lattice holds that many,
// the count spread evenly over the places. The lattice is centred on the outline's extent
// along and across the heading. Fewer places than `count` is not an error here: the caller
// compares poses.size() with the count and names the feature.
YardLayout lay_out_yard(const Yard& yard, double length, double width);

// The places the layout tests for bodies of `length` × `width` [m] at gap 0 (the most it
// tests at any gap), from the outline's extent along and across the heading it uses:
// what laying out the yard costs, known before any place is made. 0 for no outline.
double yard_lattice_places(const Yard& yard, double length, double width);

// Two edges of the polygon (outline and holes) that cross each other, as (start of one,
// start of the other); none when the polygon is simple. A self-intersecting outline (a
// bow tie) has no inside to fill.
std::optional<std::array<std::array<double, 2>, 2>> polygon_crossing(const std::vector<Ring>& rings);

// True when the rectangle (centre, heading, length × width) lies inside the polygon
// (outline minus holes), touching excepted.
bool rectangle_inside(const std::vector<Ring>& rings, const Pose& centre, double length, double width);

// The direction of the ring's longest edge [degree], in [0, 180).
double longest_edge_heading_deg(const Ring& ring);

// Area of the polygon (outline minus holes) [m²].
double polygon_area(const std::vector<Ring>& rings);

}  // namespace flotsam::debris
