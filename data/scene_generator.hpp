// A synthetic analogue of the Kainan port-city flume (SCENE.md, "The real layout,
// coarsely"), built at any grid spacing from continuous shapes rasterised at cell
// centres, with building blocks drawn from a seeded generator. Same definition => same
// scene bit for bit, on any standard library.
#pragma once
#include <cstdint>
#include <vector>

#include "formats/scene.hpp"

namespace flotsam {

// What to generate. Defaults give the project's default scene.
struct SceneGenDef {
    double resolution = 0.04;            // grid spacing [m]
    std::uint64_t seed = 1;              // building layout seed
    double lot_build_probability = 0.7;  // chance that a lot holds a building [-]
    double building_height_min = 0.04;   // building height above the local ground [m]
    double building_height_max = 0.05;   // [m]
    double quay_clearance = 0.08;        // open ground kept between a building and water [m]
    double ld_clearance = 0.20;          // open ground around the LD start [m]
};

// The scene and the ground it stands on.
struct GeneratedScene {
    Scene scene;                 // z (buildings included), manning_n, building mask, features
    std::vector<double> ground;  // bare ground or seabed under each cell, no buildings or wall [m]
};

GeneratedScene generate_scene(const SceneGenDef& def);

// Bare elevation of the analogue at a point (flume bed, slope, harbour, land) [m].
double generated_bare_elevation(double x, double y);

}  // namespace flotsam
