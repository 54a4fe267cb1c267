// The named points, sections and regions of the Kainan port-city flume (SCENE.md), in
// the benchmark frame (x east, y north, metres). One definition serves both the
// generated analogue and an import of the real layout, so statistics refer to the same
// places in either scene.
#pragma once
#include <array>
#include <vector>

#include "common/grid.hpp"
#include "data/manning.hpp"
#include "formats/scene.hpp"

namespace flotsam {

// The feature tables a scene carries besides its fields.
struct SceneFeatures {
    std::vector<ScenePoint> points;  // gauges and debris starts [m, degrees]
    std::vector<Section> sections;   // north-south passage lines [m]
    std::vector<Region> regions;     // arrival-count polygons [m]
};

// Kainan extent (cell edges) [m]: the real file's 1 cm centres -12.36..8.00, -4.00..-0.01.
inline constexpr double kainan_x_min_edge = -12.365;
inline constexpr double kainan_x_max_edge = 8.005;
inline constexpr double kainan_y_min_edge = -4.005;
inline constexpr double kainan_y_max_edge = -0.005;

// Which Kainan scene the features are for: the generated analogue (its channels are those
// of data/scene_generator.cpp) or an import of the measured layout, whose channels lie
// elsewhere (Channel B some 0.3 m further south): each scene's `channel_a` and `channel_b`
// regions lie on its own channels.
enum class KainanLayout { generated, measured };

// WG1, WG2, the FD and LD starts, the FD/LD/channel sections and the four regions.
SceneFeatures kainan_features(KainanLayout layout);

// The flume's roughness (SCENE.md): n = 0.025 seaward of x = -0.66 m (the flume's
// mortar), 0.013 on the city model.
std::vector<ManningRule> kainan_manning();

// The hydro settings a Kainan scene recommends (Scene::hydro_defaults; `flotsam hydro`
// applies them unless given): frames stored over the city and the port entrance only
// (x >= -1 m: the debris never goes into the flume, whose frames would be 55 % of the
// file), and the nested grid of docs/accuracy.md, 4 x the scene's spacing west of
// x = -1.2 m, where the flume is plain water.
std::string kainan_hydro_defaults();

// True when the grid's edges match the Kainan extent to within one cell of the grid.
bool matches_kainan_extent(const Grid& g);

// Copies the feature tables into a scene.
void apply_features(Scene& scene, const SceneFeatures& f);

}  // namespace flotsam
