// The hydro benchmarks' scene: the real layout imported from the paper's DEM at a grid
// spacing, or the generated scene where the DEM is not at hand (a clone without ../shared).
#pragma once
#include <filesystem>
#include <string>

#include "data/dem_import.hpp"
#include "data/scene_generator.hpp"

namespace flotsam::test {

struct BenchScene {
    Scene scene;
    std::string what;  // for the benchmark's heading
};

inline BenchScene bench_scene(const std::string& dem, double resolution) {
    BenchScene b;
    if (std::filesystem::exists(dem)) {
        ImportDef d;
        d.dem_path = dem;
        d.resolution = resolution;
        b.scene = import_scene(d);
        b.what = "real layout (" + dem + ")";
    } else {
        SceneGenDef d;
        d.resolution = resolution;
        b.scene = generate_scene(d).scene;
        b.what = "generated scene (real DEM not found at " + dem + ")";
    }
    return b;
}

}  // namespace flotsam::test
