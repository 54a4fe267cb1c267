#include "debris/scene_match.hpp"

#include <cmath>
#include <cstdio>

#include "common/checks.hpp"
#include "common/error.hpp"
#include "common/sha256.hpp"

namespace flotsam::debris {


void check_flow_matches_scene(const FlowReader& flow, const Scene& scene) {
    const FlowDescription& d = flow.description();
    const Grid& f = flow.grid();
    const Grid& s = scene.grid;
    auto other_scene = [&](const std::string& what) {
        std::string sums;
        if (const auto sha = d.scene_sha256; !sha.empty() && !scene.path.empty())
            sums = " (the flow was computed on a scene with sha256 " + sha + ", " + scene.path + " has " + sha256_file(scene.path) +
                   ")";
        fail(d.path, "",
             "was not computed on scene " + scene.path + ": " + what + sums + "; replay a flow with the scene it was computed on");
    };
    if (std::fabs(f.dx - s.dx) > 1e-6 * s.dx || std::fabs(f.dy - s.dy) > 1e-6 * s.dy)
        other_scene("its cells are " + number_text(f.dx) + " x " + number_text(f.dy) + " m, the scene's " + number_text(s.dx) + " x " + number_text(s.dy) + " m");
    const double oi = (f.x0 - s.x0) / s.dx, oj = (f.y0 - s.y0) / s.dy;
    const long i0 = std::lround(oi), j0 = std::lround(oj);
    if (std::fabs(oi - double(i0)) > 1e-3 || std::fabs(oj - double(j0)) > 1e-3 || i0 < 0 || j0 < 0 || i0 + f.nx > s.nx ||
        j0 + f.ny > s.ny)
        other_scene("its grid (x " + number_text(f.x_min_edge()) + " to " + number_text(f.x_max_edge()) + ", y " + number_text(f.y_min_edge()) + " to " +
                    number_text(f.y_max_edge()) + " m) is not a window of the scene's (x " + number_text(s.x_min_edge()) + " to " +
                    number_text(s.x_max_edge()) + ", y " + number_text(s.y_min_edge()) + " to " + number_text(s.y_max_edge()) + " m)");
    const auto& bed = d.bed;
    for (int j = 0; j < f.ny; ++j)
        for (int i = 0; i < f.nx; ++i) {
            const double zf = bed[f.index(i, j)], zs = float(scene.z[s.index(int(i0) + i, int(j0) + j)]);
            if (std::fabs(zf - zs) > 1e-6 * std::max(1.0, std::fabs(zs)))
                other_scene("the bed differs at x = " + number_text(f.x(i)) + " m, y = " + number_text(f.y(j)) + " m (" + number_text(zf) +
                            " m in the flow, " + number_text(zs) + " m in the scene)");
        }
    cf::check_same_crs(d.path, d.crs, scene.path, scene.crs);
    // The bed agrees on the flow's window; the building mask only the checksum that flows
    // record tells (flows written before it: not checked).
    if (const std::string sum = d.scene_buildings_sha256; !sum.empty() && sum != scene_buildings_sha256(scene))
        fail(d.path, "",
             "was not computed on scene " + scene.path +
                 ": the bed is the same, but the building mask differs (scene_buildings_sha256 " + sum + " in the flow, " +
                 scene_buildings_sha256(scene) +
                 " for the scene); the bodies would meet other buildings than the flow had. Replay a flow with the scene it "
                 "was computed on");
}

void check_body_start(const BodyDef& b, const FlowReader& flow, const Scene* scene) {
    check_body_start(b, flow.grid(), "flow " + flow.description().path, scene);
}

void check_body_start(const BodyDef& b, const Grid& g, const std::string& domain, const Scene* scene) {
    const std::string who = "body '" + b.name + "'";
    const std::string at = "at x = " + coordinate_text(b.x) + " m, y = " + coordinate_text(b.y) + " m";
    if (!std::isfinite(b.x) || !std::isfinite(b.y) || !g.contains(b.x, b.y))
        fail(who, "start",
             at + " is outside the domain of " + domain + " (x " + coordinate_text(g.x_min_edge()) + " to " + coordinate_text(g.x_max_edge()) +
                 ", y " + coordinate_text(g.y_min_edge()) + " to " + coordinate_text(g.y_max_edge()) + " m)");
    const double diagonal = std::hypot(b.length, b.width);
    const double extent = std::hypot(g.x_max_edge() - g.x_min_edge(), g.y_max_edge() - g.y_min_edge());
    if (!(diagonal < extent))
        fail(who, "size",
             "a " + number_text(b.length) + " x " + number_text(b.width) + " m body does not fit in the domain of " + domain +
                 " (diagonal " + number_text(extent) + " m)");
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
                             : std::string(": a corner at x = " + coordinate_text(px[k]) + " m, y = " + coordinate_text(py[k]) + " m")) +
                     " is inside a building of scene " + scene->path + "; move the start into open ground or water");
    }
}

}  // namespace flotsam::debris
