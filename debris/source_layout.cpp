#include "debris/source_layout.hpp"

#include <algorithm>
#include <numbers>

namespace flotsam::debris {

namespace {

using P = std::array<double, 2>;

double cross(const P& o, const P& a, const P& b) { return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]); }

// Segments ab and cd cross at a point inside both (touching and collinear overlap excepted).
bool segments_cross(const P& a, const P& b, const P& c, const P& d) {
    const double d1 = cross(c, d, a), d2 = cross(c, d, b), d3 = cross(a, b, c), d4 = cross(a, b, d);
    return ((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0));
}

// Even-odd rule over all rings: inside the outline and outside every hole.
bool point_inside(const std::vector<Ring>& rings, const P& p) {
    bool inside = false;
    for (const Ring& r : rings)
        for (std::size_t i = 0, n = r.size(), j = n - 1; i < n; j = i++)
            if ((r[i][1] > p[1]) != (r[j][1] > p[1]) &&
                p[0] < (r[j][0] - r[i][0]) * (p[1] - r[i][1]) / (r[j][1] - r[i][1]) + r[i][0])
                inside = !inside;
    return inside;
}

std::array<P, 4> corners(const Pose& c, double length, double width) {
    const double cs = std::cos(c.heading), sn = std::sin(c.heading), hl = 0.5 * length, hw = 0.5 * width;
    return {P{c.x + cs * hl - sn * hw, c.y + sn * hl + cs * hw}, P{c.x - cs * hl - sn * hw, c.y - sn * hl + cs * hw},
            P{c.x - cs * hl + sn * hw, c.y - sn * hl - cs * hw}, P{c.x + cs * hl + sn * hw, c.y + sn * hl - cs * hw}};
}

// The outline's extent along the heading (u) and across it (v), from its first vertex:
// about the CRS origin, UTM's 4e6 m would turn a 1e-9 rad heading error into millimetres.
struct Extent {
    double u0 = INFINITY, u1 = -INFINITY, v0 = INFINITY, v1 = -INFINITY;
};
Extent extent_along(const Ring& outline, double cs, double sn) {
    Extent e;
    const P o = outline.front();
    for (const P& p : outline) {
        const double u = (p[0] - o[0]) * cs + (p[1] - o[1]) * sn, v = -(p[0] - o[0]) * sn + (p[1] - o[1]) * cs;
        e.u0 = std::min(e.u0, u), e.u1 = std::max(e.u1, u), e.v0 = std::min(e.v0, v), e.v1 = std::max(e.v1, v);
    }
    return e;
}

// Every lattice place at `gap` whose footprint lies inside the yard.
std::vector<Pose> places(const std::vector<Ring>& rings, double length, double width, double heading, double gap) {
    const double cs = std::cos(heading), sn = std::sin(heading);
    const P o = rings.front().front();
    const auto [u0, u1, v0, v1] = extent_along(rings.front(), cs, sn);
    const double pu = length + gap, pv = width + gap;
    const long nu = long(std::floor((u1 - u0 + gap) / pu)), nv = long(std::floor((v1 - v0 + gap) / pv));
    std::vector<Pose> out;
    if (nu <= 0 || nv <= 0) return out;
    // Centred: the lattice's spare length split evenly at both ends.
    const double su = u0 + 0.5 * (u1 - u0 - (double(nu) * pu - gap)) + 0.5 * length;
    const double sv = v0 + 0.5 * (v1 - v0 - (double(nv) * pv - gap)) + 0.5 * width;
    // Footprints tested a hair smaller (1e-9 of the body), so a body flush with the outline counts as inside.
    const double shrink = 1.0 - 1e-9;
    for (long b = 0; b < nv; ++b)
        for (long a = 0; a < nu; ++a) {
            const double u = su + double(a) * pu, v = sv + double(b) * pv;
            const Pose c{o[0] + u * cs - v * sn, o[1] + u * sn + v * cs, heading};
            if (rectangle_inside(rings, c, length * shrink, width * shrink)) out.push_back(c);
        }
    return out;
}

// `count` of `all`, spread evenly over it (all of them when there are no more).
std::vector<Pose> spread(const std::vector<Pose>& all, int count) {
    if (count <= 0 || std::size_t(count) >= all.size()) return all;
    std::vector<Pose> out;
    for (int k = 0; k < count; ++k) out.push_back(all[std::size_t((double(k) + 0.5) * double(all.size()) / double(count))]);
    return out;
}

}  // namespace

bool rectangle_inside(const std::vector<Ring>& rings, const Pose& centre, double length, double width) {
    const std::array<P, 4> c = corners(centre, length, width);
    for (const P& p : c)
        if (!point_inside(rings, p)) return false;
    // No edge of the yard crosses the footprint's, and no vertex of it (a hole) lies inside.
    const std::vector<Ring> footprint = {Ring(c.begin(), c.end())};
    for (const Ring& r : rings)
        for (std::size_t i = 0, n = r.size(), j = n - 1; i < n; j = i++) {
            if (point_inside(footprint, r[i])) return false;
            for (int k = 0; k < 4; ++k)
                if (segments_cross(r[j], r[i], c[std::size_t(k)], c[std::size_t((k + 1) % 4)])) return false;
        }
    return true;
}

std::optional<std::array<P, 2>> polygon_crossing(const std::vector<Ring>& rings) {
    std::vector<std::array<P, 2>> edges;
    for (const Ring& r : rings)
        for (std::size_t i = 0, n = r.size(), j = n - 1; i < n; j = i++) edges.push_back({r[j], r[i]});
    for (std::size_t a = 0; a < edges.size(); ++a)
        for (std::size_t b = a + 1; b < edges.size(); ++b)
            if (segments_cross(edges[a][0], edges[a][1], edges[b][0], edges[b][1])) return std::array<P, 2>{edges[a][0], edges[b][0]};
    return std::nullopt;
}

double yard_lattice_places(const Yard& yard, double length, double width) {
    if (yard.rings.empty() || yard.rings.front().size() < 3 || !(length > 0) || !(width > 0)) return 0.0;
    const double heading_deg = std::isnan(yard.heading_deg) ? longest_edge_heading_deg(yard.rings.front()) : yard.heading_deg;
    const double heading = heading_deg * std::numbers::pi / 180.0;
    const Extent e = extent_along(yard.rings.front(), std::cos(heading), std::sin(heading));
    return std::floor((e.u1 - e.u0) / length) * std::floor((e.v1 - e.v0) / width);
}

double longest_edge_heading_deg(const Ring& ring) {
    double best = -1.0, angle = 0.0;
    for (std::size_t i = 0, n = ring.size(), j = n - 1; i < n; j = i++) {
        const double dx = ring[i][0] - ring[j][0], dy = ring[i][1] - ring[j][1], len = std::hypot(dx, dy);
        if (len > best * (1.0 + 1e-12)) best = len, angle = std::atan2(dy, dx) * 180.0 / std::numbers::pi;
    }
    angle = std::fmod(angle + 360.0, 180.0);
    return angle >= 180.0 ? 0.0 : angle;
}

double polygon_area(const std::vector<Ring>& rings) {
    double area = 0.0;
    for (std::size_t k = 0; k < rings.size(); ++k) {
        double a = 0.0;
        const Ring& r = rings[k];
        for (std::size_t i = 0, n = r.size(), j = n - 1; i < n; j = i++) a += r[j][0] * r[i][1] - r[i][0] * r[j][1];
        area += (k == 0 ? 1.0 : -1.0) * std::fabs(0.5 * a);
    }
    return area;
}

YardLayout lay_out_yard(const Yard& yard, double length, double width) {
    YardLayout out;
    if (yard.rings.empty() || yard.rings.front().size() < 3 || !(length > 0) || !(width > 0)) return out;
    out.heading_deg = std::isnan(yard.heading_deg) ? longest_edge_heading_deg(yard.rings.front()) : yard.heading_deg;
    const double heading = out.heading_deg * std::numbers::pi / 180.0;
    out.capacity = int(places(yard.rings, length, width, heading, 0.0).size());
    if (!std::isnan(yard.gap)) {
        out.gap = yard.gap;
        out.poses = spread(places(yard.rings, length, width, heading, yard.gap), yard.count);
        return out;
    }
    if (yard.count > out.capacity || yard.count <= 0) {  // the caller names the shortfall
        out.poses = places(yard.rings, length, width, heading, 0.0);
        return out;
    }
    // The widest gap whose lattice still holds `count` (bisection; lo always holds it).
    double lo = 0.0, hi = 0.0;
    for (const P& p : yard.rings.front())
        for (const P& q : yard.rings.front()) hi = std::max(hi, std::hypot(p[0] - q[0], p[1] - q[1]));
    for (int it = 0; it < 48 && hi - lo > 1e-6 * length; ++it) {
        const double mid = 0.5 * (lo + hi);
        (int(places(yard.rings, length, width, heading, mid).size()) >= yard.count ? lo : hi) = mid;
    }
    out.gap = lo;
    out.poses = spread(places(yard.rings, length, width, heading, lo), yard.count);
    return out;
}

}  // namespace flotsam::debris
