#include "data/scene_generator.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <string>

#include "common/error.hpp"
#include "data/kainan_features.hpp"
#include "data/resample.hpp"

namespace flotsam {

namespace {

constexpr double flume_bed = -0.877;    // [m]
constexpr double slope = 0.1;           // 1:10
constexpr double quay_north_y = -2.05;  // basin north quay [m]
constexpr double basin_west_x = 0.90, basin_east_x = 3.75;
constexpr double wall_top = 0.09;  // the breakwater wall on the reclaimed block [m]

// Uniform numbers from mt19937_64 by our own mapping: std::uniform_real_distribution is
// not specified bit for bit, and the scene must not depend on the standard library.
class Rng {
public:
    explicit Rng(std::uint64_t seed) : engine_(seed) {}
    double uniform() { return double(engine_() >> 11) * 0x1.0p-53; }  // [0, 1)
    double uniform(double a, double b) { return a + (b - a) * uniform(); }

private:
    std::mt19937_64 engine_;
};

struct Rect {
    double x0, x1, y0, y1;  // [m]
    bool contains(double x, double y) const { return x >= x0 && x < x1 && y >= y0 && y < y1; }
    Rect grown(double d) const { return {x0 - d, x1 + d, y0 - d, y1 + d}; }
    double distance_to(double x, double y) const {
        const double dx = std::max({x0 - x, 0.0, x - x1}), dy = std::max({y0 - y, 0.0, y - y1});
        return std::hypot(dx, dy);
    }
};

struct Building {
    Rect footprint;
    double height;  // above local ground [m]
};

double smoothstep(double u) {
    u = std::clamp(u, 0.0, 1.0);
    return u * u * (3.0 - 2.0 * u);
}

double distance_to_segment(double x, double y, double ax, double ay, double bx, double by) {
    const double vx = bx - ax, vy = by - ay;
    const double t = std::clamp(((x - ax) * vx + (y - ay) * vy) / (vx * vx + vy * vy), 0.0, 1.0);
    return std::hypot(x - ax - t * vx, y - ay - t * vy);
}

double distance_to_path(double x, double y, const std::vector<std::array<double, 2>>& p) {
    double d = 1e30;
    for (std::size_t k = 0; k + 1 < p.size(); ++k)
        d = std::min(d, distance_to_segment(x, y, p[k][0], p[k][1], p[k + 1][0], p[k + 1][1]));
    return d;
}

const std::vector<std::array<double, 2>> channel_a_path = {{3.70, -2.00}, {4.30, -1.80}, {4.80, -1.35}, {5.20, -1.55}};
const std::vector<std::array<double, 2>> channel_b_path = {{3.70, -2.62}, {5.00, -3.60}};

// The flume slope meets the model at -0.1 m: x = -0.66 north of the port, -0.3 south of it.
double flume_bed_at(double x, double y) {
    const double toe_x = -0.66 + 0.36 * smoothstep((-2.55 - y) / 0.4);
    return std::max(flume_bed, -0.1 + slope * (x - toe_x));
}

bool seaward(double x, double y) { return x < -0.66 + 0.36 * smoothstep((-2.55 - y) / 0.4); }

// South quay of the basin: y = -2.65, widening to -2.97 at the east end.
double basin_south_y(double x) { return -2.65 - 0.32 * std::clamp((x - 3.0) / 0.2, 0.0, 1.0); }

// 2 cm at the quays, 4 cm from 0.3 m off them (so the FD start, 0.1 m off the north quay, is ~2.7 cm deep).
double basin_bed(double x, double y) {
    const double off_quay = std::min({quay_north_y - y, y - basin_south_y(x), basin_east_x - x});
    return -(0.02 + 0.02 * std::min(off_quay / 0.3, 1.0));
}

// Land: about +1 cm at the shore, rising gently north of the basin (LD start ~1.5 cm) and
// to +0.1 m on the south-east high ground.
double land_ground(double x, double y) {
    const double north_rise = x > 0.85 ? 0.01 * std::clamp((y - quay_north_y) / 1.6, 0.0, 1.0) : 0.0;
    const double south_east = 0.09 * smoothstep((x - 4.8) / 2.5) * smoothstep((-2.9 - y) / 0.9);
    return 0.01 + north_rise + south_east;
}

bool is_wall(double x, double y) { return x >= 0.08 && x < 0.12 && y >= -2.45 && y < -0.15; }

}  // namespace

double generated_bare_elevation(double x, double y) {
    if (seaward(x, y)) return flume_bed_at(x, y);
    if (x < 1.0 && y >= -3.9 && y < -2.75) return -0.10 + 0.05 * std::clamp((x + 0.3) / 1.3, 0.0, 1.0);  // port entrance
    if (x >= basin_west_x && x < basin_east_x && y >= basin_south_y(x) && y < quay_north_y) return basin_bed(x, y);
    if (x >= 0.45 && x < 1.0 && y >= -2.75 && y < quay_north_y) return -0.045;  // harbour mouth
    if (x >= 0.45 && x < 0.85 && y >= quay_north_y) return -0.04;               // north channel
    if (distance_to_path(x, y, channel_a_path) < 0.04) return -0.02;
    if (distance_to_path(x, y, channel_b_path) < 0.02) return -0.015;
    if (x > 7.1 && y > -1.0) return -0.03;  // open water, north-east
    return land_ground(x, y);
}

namespace {

// A large group of buildings just east of the LD start (nearest wall 0.21 m from it).
std::vector<Building> ld_group() {
    return {{{3.15, 3.45, -1.55, -1.15}, 0.045}, {{3.50, 3.75, -1.55, -1.20}, 0.048}, {{3.15, 3.75, -1.95, -1.62}, 0.042}};
}

const Rect ld_group_area{3.05, 3.85, -2.00, -1.05};
const Rect station_area{4.85, 5.85, -1.50, -0.90};

bool buildable(const Rect& r, const SceneGenDef& def) {
    const double ld_x = 2.94, ld_y = -1.26;
    if (r.x0 < 0.86 || r.x1 > 7.99 || r.y0 < -3.99 || r.y1 > -0.01) return false;
    if (r.distance_to(ld_x, ld_y) < def.ld_clearance + 0.05) return false;
    for (const Rect& keep : {ld_group_area, station_area})
        if (r.x0 < keep.x1 && r.x1 > keep.x0 && r.y0 < keep.y1 && r.y1 > keep.y0) return false;
    // No water under the footprint grown by the quay clearance (sampled every 1 cm).
    const Rect g = r.grown(def.quay_clearance);
    const int nx = int(std::ceil((g.x1 - g.x0) / 0.01)), ny = int(std::ceil((g.y1 - g.y0) / 0.01));
    for (int j = 0; j <= ny; ++j)
        for (int i = 0; i <= nx; ++i)
            if (generated_bare_elevation(g.x0 + (g.x1 - g.x0) * i / nx, g.y0 + (g.y1 - g.y0) * j / ny) < 0.0) return false;
    return true;
}

// Street positions along one axis: blocks of 0.3-0.7 m between streets 3-16 cm wide
// (a third of them narrower than 8 cm, so narrower than the 0.25 m debris is long).
std::vector<std::array<double, 2>> blocks_along(Rng& rng, double from, double to) {
    std::vector<std::array<double, 2>> out;
    double at = from;
    while (at < to) {
        const double len = rng.uniform(0.3, 0.7);
        out.push_back({at, std::min(at + len, to)});
        const double street = rng.uniform() < 0.35 ? rng.uniform(0.03, 0.08) : rng.uniform(0.08, 0.16);
        at += len + street;
    }
    return out;
}

// Each block splits into 1-3 by 1-3 lots; a lot holds a building set back 0.5-2 cm from
// its edges (the alleys between neighbours) with probability lot_build_probability.
void add_block(Rng& rng, const Rect& block, const SceneGenDef& def, std::vector<Building>& out) {
    const int nx = 1 + int(rng.uniform() * 3.0), ny = 1 + int(rng.uniform() * 3.0);
    const double wx = (block.x1 - block.x0) / nx, wy = (block.y1 - block.y0) / ny;
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
            const bool build = rng.uniform() < def.lot_build_probability;
            const double setback = rng.uniform(0.005, 0.02);
            const double height = rng.uniform(def.building_height_min, def.building_height_max);
            const Rect lot{block.x0 + i * wx + setback, block.x0 + (i + 1) * wx - setback, block.y0 + j * wy + setback,
                           block.y0 + (j + 1) * wy - setback};
            if (build && buildable(lot, def)) out.push_back({lot, height});
        }
}

std::vector<Building> city_buildings(const SceneGenDef& def) {
    Rng rng(def.seed);
    std::vector<Building> out = ld_group();
    const auto columns = blocks_along(rng, 0.9, 8.0);
    const auto rows = blocks_along(rng, -4.0, 0.0);
    for (const auto& r : rows)
        for (const auto& c : columns) add_block(rng, {c[0], c[1], r[0], r[1]}, def, out);
    return out;
}

void check(const SceneGenDef& def) {
    if (!(def.resolution >= 0.002 && def.resolution <= 0.5))
        fail("--resolution", "", "grid spacing " + std::to_string(def.resolution) + " m is outside [0.002, 0.5] m");
    if (!(def.building_height_min > 0.0 && def.building_height_max >= def.building_height_min))
        fail("scene generate", "building heights", "need 0 < min <= max");
    if (!(def.lot_build_probability >= 0.0 && def.lot_build_probability <= 1.0))
        fail("scene generate", "lot_build_probability", "must be in [0, 1]");
}

}  // namespace

GeneratedScene generate_scene(const SceneGenDef& def) {
    check(def);
    GeneratedScene out;
    Scene& s = out.scene;
    s.grid = grid_covering(kainan_x_min_edge, kainan_x_max_edge, kainan_y_min_edge, kainan_y_max_edge, def.resolution);
    const Grid& g = s.grid;
    out.ground.resize(g.size());
    s.z.resize(g.size());
    s.building.assign(g.size(), 0);
    for (int j = 0; j < g.ny; ++j)
        for (int i = 0; i < g.nx; ++i) {
            const std::size_t k = g.index(i, j);
            const double x = g.x(i), y = g.y(j);
            out.ground[k] = generated_bare_elevation(x, y);
            s.z[k] = out.ground[k];
            if (is_wall(x, y)) {
                s.z[k] = wall_top;
                s.building[k] = 1;
            }
        }
    for (const Building& b : city_buildings(def)) {
        const int i0 = g.cell_i(b.footprint.x0), i1 = g.cell_i(b.footprint.x1);
        const int j0 = g.cell_j(b.footprint.y0), j1 = g.cell_j(b.footprint.y1);
        for (int j = j0; j <= j1; ++j)
            for (int i = i0; i <= i1; ++i)
                if (b.footprint.contains(g.x(i), g.y(j))) {
                    const std::size_t k = g.index(i, j);
                    s.z[k] = out.ground[k] + b.height;
                    s.building[k] = 1;
                }
    }
    s.manning_n = manning_field(g, kainan_manning());
    apply_features(s, kainan_features(KainanLayout::generated));
    s.hydro_defaults = kainan_hydro_defaults();
    s.synthetic = true;
    s.title = "SYNTHETIC analogue of the 1/250 Kainan port-city flume (not the measured model)";
    s.comment = "Generated by flotsam scene generate, seed " + std::to_string(def.seed) + ", grid spacing " +
                std::to_string(def.resolution) +
                " m: the coarse layout of SCENE.md with seeded building blocks. "
                "Synthetic: use for tests and demonstrations, not for validation.";
    return out;
}

}  // namespace flotsam
