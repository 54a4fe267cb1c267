// Many independent bodies replayed through one flow. The world owns the flow reader
// and the obstacle map; advance_to(t) walks frame interval by frame interval, loading
// each pair of frames once, and advances every body through it (in parallel with
// OpenMP; each body is independent, so results do not depend on the thread count).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "debris/body.hpp"
#include "debris/dynamics.hpp"
#include "debris/flow_reader.hpp"
#include "debris/obstacles.hpp"
#include "formats/scene.hpp"

namespace flotsam::debris {

struct WorldDef {
    StepDef step = default_step_def();
    FlowReaderDef flow = default_flow_reader_def();
    double window_margin = 1.0;  // loaded window reaches this far beyond the bodies [m]
    int threads = 0;             // OpenMP threads over bodies; 0: the OpenMP default
};
WorldDef default_world_def();

// The settings of the step and of the flow replay (common/settings.hpp; defaults: the
// structs' initialisers): options of `flotsam debris`, keys of a sweep's [sweep] table.
const Settings<StepDef>& step_settings();               // dt-max, vertex-step-fraction, integrator
const Settings<FlowReaderDef>& flow_replay_settings();  // time-interpolation

// The scene's building mask sampled at the flow grid's cell centres (empty: none).
std::vector<std::uint8_t> buildings_on_grid(const Scene& scene, const Grid& grid);

class World {
public:
    // A world without bodies; `building` on the flow's grid (empty: none). make_world()
    // below is the usual way in.
    World(const std::string& flow_path, std::vector<std::uint8_t> building, const WorldDef& def = default_world_def());

    // Adds a body at the current time; returns its index.
    std::size_t add_body(const BodyDef& def);
    void advance_to(double t);

    double time() const { return time_; }
    const FlowReader& flow() const { return flow_; }
    const ObstacleMap& obstacles() const { return obstacles_; }
    const WorldDef& def() const { return def_; }
    std::size_t size() const { return states_.size(); }
    const std::vector<BodyState>& states() const { return states_; }
    std::vector<BodyState>& states() { return states_; }  // tests set initial conditions
    const std::vector<BodyParams>& params() const { return params_; }
    const std::vector<BodyStats>& stats() const { return stats_; }
    // Clears the "colliding since the last output" bit of every body.
    void clear_event_flags();

private:
    void fit_window();  // the loaded window: all bodies plus the margin

    WorldDef def_;
    FlowReader flow_;
    ObstacleMap obstacles_;
    double time_ = 0.0;
    bool window_fitted_ = false;
    std::vector<BodyState> states_;   // hot, per step
    std::vector<BodyParams> params_;  // cold, read only
    std::vector<BodyStats> stats_;
};

// The world of one flow: the scene's building mask on the flow's grid (scene null: no
// buildings), and the bodies. The flow must have been computed on the scene, and each
// body must start on the grid and off the buildings (debris/scene_match.hpp: the errors
// name the files or the body). Used by `flotsam debris` and by every flow of a sweep.
World make_world(const std::string& flow_path, const Scene* scene, const std::vector<BodyDef>& bodies, const WorldDef& def);

}  // namespace flotsam::debris
