#include "debris/scene_match.hpp"

#include <cmath>
#include <cstdio>

#include "common/error.hpp"
#include "common/sha256.hpp"

namespace flotsam::debris {

namespace {
std::string fmt(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", v);
    return buf;
}
// A coordinate to the millimetre: map coordinates (UTM northings) have seven digits before the point.
std::string coordinate(double v) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.3f", v);
    std::string s = buf;
    while (s.back() == '0') s.pop_back();
    if (s.back() == '.') s.pop_back();
    return s;
}
}  // namespace

void check_flow_matches_scene(const FlowReader& flow, const Scene& scene) {
    const Grid& f = flow.grid();
    const Grid& s = scene.grid;
    auto other_scene = [&](const std::string& what) {
        std::string sums;
        if (const auto sha = flow.scene_sha256(); !sha.empty() && !scene.path.empty())
            sums = " (the flow was computed on a scene with sha256 " + sha + ", " + scene.path + " has " + sha256_file(scene.path) +
                   ")";
        fail(flow.path(), "",
             "was not computed on scene " + scene.path + ": " + what + sums + "; replay a flow with the scene it was computed on");
    };
    if (std::fabs(f.dx - s.dx) > 1e-6 * s.dx || std::fabs(f.dy - s.dy) > 1e-6 * s.dy)
        other_scene("its cells are " + fmt(f.dx) + " x " + fmt(f.dy) + " m, the scene's " + fmt(s.dx) + " x " + fmt(s.dy) + " m");
    const double oi = (f.x0 - s.x0) / s.dx, oj = (f.y0 - s.y0) / s.dy;
    const long i0 = std::lround(oi), j0 = std::lround(oj);
    if (std::fabs(oi - double(i0)) > 1e-3 || std::fabs(oj - double(j0)) > 1e-3 || i0 < 0 || j0 < 0 || i0 + f.nx > s.nx ||
        j0 + f.ny > s.ny)
        other_scene("its grid (x " + fmt(f.x_min_edge()) + " to " + fmt(f.x_max_edge()) + ", y " + fmt(f.y_min_edge()) + " to " +
                    fmt(f.y_max_edge()) + " m) is not a window of the scene's (x " + fmt(s.x_min_edge()) + " to " +
                    fmt(s.x_max_edge()) + ", y " + fmt(s.y_min_edge()) + " to " + fmt(s.y_max_edge()) + " m)");
    const auto& bed = flow.bed();
    for (int j = 0; j < f.ny; ++j)
        for (int i = 0; i < f.nx; ++i) {
            const double zf = bed[f.index(i, j)], zs = float(scene.z[s.index(int(i0) + i, int(j0) + j)]);
            if (std::fabs(zf - zs) > 1e-6 * std::max(1.0, std::fabs(zs)))
                other_scene("the bed differs at x = " + fmt(f.x(i)) + " m, y = " + fmt(f.y(j)) + " m (" + fmt(zf) +
                            " m in the flow, " + fmt(zs) + " m in the scene)");
        }
    cf::check_same_crs(flow.path(), flow.crs(), scene.path, scene.crs);
    // The bed agrees on the flow's window; the building mask only the checksum that flows
    // record tells (flows written before it: not checked).
    if (const std::string sum = flow.scene_buildings_sha256(); !sum.empty() && sum != scene_buildings_sha256(scene))
        fail(flow.path(), "",
             "was not computed on scene " + scene.path +
                 ": the bed is the same, but the building mask differs (scene_buildings_sha256 " + sum + " in the flow, " +
                 scene_buildings_sha256(scene) +
                 " for the scene); the bodies would meet other buildings than the flow had. Replay a flow with the scene it "
                 "was computed on");
}

void check_body_start(const BodyDef& b, const FlowReader& flow, const Scene* scene) {
    check_body_start(b, flow.grid(), "flow " + flow.path(), scene);
}

void check_body_start(const BodyDef& b, const Grid& g, const std::string& domain, const Scene* scene) {
    const std::string who = "body '" + b.name + "'";
    const std::string at = "at x = " + coordinate(b.x) + " m, y = " + coordinate(b.y) + " m";
    if (!std::isfinite(b.x) || !std::isfinite(b.y) || !g.contains(b.x, b.y))
        fail(who, "start",
             at + " is outside the domain of " + domain + " (x " + coordinate(g.x_min_edge()) + " to " + coordinate(g.x_max_edge()) +
                 ", y " + coordinate(g.y_min_edge()) + " to " + coordinate(g.y_max_edge()) + " m)");
    const double diagonal = std::hypot(b.length, b.width);
    const double extent = std::hypot(g.x_max_edge() - g.x_min_edge(), g.y_max_edge() - g.y_min_edge());
    if (!(diagonal < extent))
        fail(who, "size",
             "a " + fmt(b.length) + " x " + fmt(b.width) + " m body does not fit in the domain of " + domain +
                 " (diagonal " + fmt(extent) + " m)");
    if (!scene || scene->building.empty()) return;
    // The centre and the four corners: none on a building cell.
    const double c = std::cos(b.heading), s = std::sin(b.heading), hl = 0.5 * b.length, hw = 0.5 * b.width;
    const double px[5] = {b.x, b.x + c * hl - s * hw, b.x + c * hl + s * hw, b.x - c * hl - s * hw, b.x - c * hl + s * hw};
    const double py[5] = {b.y, b.y + s * hl + c * hw, b.y + s * hl - c * hw, b.y - s * hl + c * hw, b.y - s * hl - c * hw};
    const Grid& sg = scene->grid;
    for (int k = 0; k < 5; ++k) {
        if (!sg.contains(px[k], py[k])) continue;
        if (scene->building[sg.index(sg.cell_i(px[k]), sg.cell_j(py[k]))])
            fail(who, "start",
                 at +
                     (k == 0 ? std::string(": its centre")
                             : std::string(": a corner at x = " + coordinate(px[k]) + " m, y = " + coordinate(py[k]) + " m")) +
                     " is inside a building of scene " + scene->path + "; move the start into open ground or water");
    }
}

}  // namespace flotsam::debris
