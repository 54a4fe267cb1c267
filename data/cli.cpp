// Command-line surface of the data stage: `scene generate`, `scene import`,
// `boundary generate`.
#include <cstdio>
#include <string>

#include "app/commands.hpp"
#include "common/scene.hpp"
#include "data/scene_generator.hpp"

namespace flotsam {

namespace {

void register_scene_generate(CLI::App* scene, const std::string& command_line) {
    auto def = std::make_shared<SceneGenDef>();
    auto out = std::make_shared<std::string>();
    CLI::App* sub = scene->add_subcommand("generate",
        "Write the synthetic analogue of the Kainan port-city flume (SCENE.md) at any grid spacing; "
        "deterministic from --seed; marked synthetic in its metadata");
    sub->add_option("--resolution", def->resolution, "grid spacing [m], e.g. 0.01, 0.02, 0.04")->capture_default_str();
    sub->add_option("--seed", def->seed, "seed of the building layout")->capture_default_str();
    sub->add_option("--out", *out, "output scene file (NetCDF)")->required();
    sub->add_option("--lot-build-probability", def->lot_build_probability, "chance that a city lot holds a building")->capture_default_str();
    add_config_option(sub);
    sub->callback([def, out, command_line] {
        const GeneratedScene g = generate_scene(*def);
        write_scene(*out, g.scene, command_line);
        std::printf("scene: %s (%d x %d cells of %.4g m, synthetic)\n", out->c_str(), g.scene.grid.nx, g.scene.grid.ny, def->resolution);
    });
}

}  // namespace

void register_data_commands(CLI::App& app, const std::string& command_line) {
    CLI::App* scene = app.add_subcommand("scene", "Scenes: generate the synthetic analogue or import a user DEM");
    scene->require_subcommand(1);
    register_scene_generate(scene, command_line);
}

}  // namespace flotsam
