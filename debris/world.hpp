// Bodies replayed through one flow. The world owns the flow reader and the obstacle map;
// advance_to(t) walks frame interval by frame interval, loading each pair of frames once,
// and advances every body through it. Bodies of one group (a run: a yard's bodies, the
// bodies of one `flotsam debris`) meet each other and step together
// (debris/body_collision.hpp); bodies of different groups never meet. Groups go in
// parallel with OpenMP, each in a fixed order, so results do not depend on the thread
// count.
// With read_ahead, the frame the next interval needs is read meanwhile on one more
// thread.
#pragma once
#include <cstdint>
#include <memory>
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
    // The loaded window reaches this many body lengths beyond each body (0.125 m for the
    // paper's 0.25 m box); only how often the window moves depends on it, not a result.
    // A move reads only the tiles the window did not hold (FlowReader::set_regions), so a
    // small margin pays: over ten 1 cm flows 0.5 reads 2.8 times less than 4 (docs/sweep.md).
    double window_margin_lengths = 0.5;  // [-]
    int threads = 0;                     // OpenMP threads over bodies; 0: the OpenMP default
    // One more thread, beside those, reads the next frame while the bodies step through
    // the current interval (FlowReader::read_ahead; the same results to the bit). It is
    // busy for the reading only (about a third of one thread's time in the 4 cm sweep
    // bench) and never runs outside advance_to().
    bool read_ahead = true;
};
WorldDef default_world_def();

// The settings of the step and of the flow replay (common/settings.hpp; defaults: the
// structs' initialisers): options of `flotsam debris`, keys of a sweep's [sweep] table.
const Settings<StepDef>& step_settings();               // dt-max, vertex-step-fraction, integrator, body-contact
const Settings<FlowReaderDef>& flow_replay_settings();  // time-interpolation

// `def` with the settings that are lengths or times set for these bodies: they follow the
// shortest body's length L by Froude's law, s = L / 0.25 m (the paper's box, for which
// the defaults were set, gets them unchanged): the largest step (0.01 s) x sqrt(s) unless
// the user gave one, and the flow reader's acceleration depth (1e-3 m) x s (the dry
// tolerance is the flow file's). A body scaled by Froude (lengths x s, times x sqrt(s))
// then takes the same steps in scaled time, and a prototype-scale run is the flume's
// scaled (tests/froude_test.cpp). Used by `flotsam debris` and by sweeps.
WorldDef scaled_to_bodies(WorldDef def, const std::vector<BodyDef>& bodies, bool dt_max_given);

// The work of a replay, estimated before it starts (docs/reliability.md, "Every run is
// bounded"): each body steps from t0 to t_end at the smaller of dt-max and the
// vertex-step limit at the flow's largest stored speed (vertex-step-fraction x the
// smaller cell of `cells` / speed). Refused when one body would take more than
// max_body_steps_per_body steps or all `bodies` together more than max_body_steps,
// unless `allowed`; the error names the binding option (`dt_name` or `fraction_name`,
// as the command spells them), the span and the flow, and `file` (a spec) when given.
// Returns the estimated steps of one body.
double check_replay_work(const FlowReader& flow, const Grid& cells, const StepDef& step, double t0, double t_end, double bodies,
                       bool allowed, const std::string& dt_name, const std::string& fraction_name, const std::string& file = "");

// The scene's building mask sampled at the flow grid's cell centres (empty: none).
std::vector<std::uint8_t> buildings_on_grid(const Scene& scene, const Grid& grid);
// The scene's building ids (formats/scene.hpp, scene_building_ids) on the cells of `grid`
// where `mask` marks a building: the id of the scene cell holding the centre, or where
// that one holds none (a finer ground's building cell beside the scene's), of the nearest
// scene building cell among its eight neighbours; 0 where none is (empty: no mask).
std::vector<std::int32_t> building_ids_on_grid(const Scene& scene, const Grid& grid, const std::vector<std::uint8_t>& mask);

// The ground the bodies stand on where it is finer than the flow's bed (docs/debris.md,
// "Ground finer than the flow"): ground contact, the resting height, steps and
// buildings on this grid, the depth the flow's level over it (FlowReader::set_ground).
struct Ground {
    Grid grid;                           // covers the flow's grid (positions as the flow's)
    std::vector<float> z;                // ground elevation [m], buildings included
    std::vector<std::uint8_t> building;  // 1 where a building stands (empty: none)
};
// The cells of `scene` over the flow's grid. The scene must cover the flow's grid with
// cells no larger than the flow's; errors name both files.
Ground ground_from_scene(const Scene& scene, const FlowReader& flow);

class World {
public:
    // A world without bodies on an opened flow (open_flow) or the flow file at `flow_path`;
    // `building` on the flow's grid (empty: none). make_world() below is the usual way in.
    // With `ground`, the bodies stand on it instead of the flow's bed, and `building` is
    // not used (the ground's own buildings are).
    World(std::unique_ptr<FlowReader> flow, std::vector<std::uint8_t> building, const WorldDef& def = default_world_def(),
          const Ground* ground = nullptr);
    World(const std::string& flow_path, std::vector<std::uint8_t> building, const WorldDef& def = default_world_def(),
          const Ground* ground = nullptr);

    // Adds a body at the current time (its position in the flow's own coordinates) to
    // group `group` (bodies of a group meet each other; < 0: a group of its own); returns
    // its index.
    std::size_t add_body(const BodyDef& def, int group = -1);
    void advance_to(double t);

    double time() const { return time_; }
    // Positions inside the world (states(), flow(), obstacles()) are relative to this
    // origin [m]: (0, 0) for a grid in local metres (the flume), a round kilometre at the
    // grid's lower-left corner for map coordinates (UTM northings run to 10^7 m, where a
    // double resolves 1 nm and contact tolerances would sit at the rounding level, so a
    // body's path would depend on where on Earth the port lies). record() adds it back.
    double origin_x() const { return origin_x_; }
    double origin_y() const { return origin_y_; }
    // Whether the flow grid covers the point (x, y) given in the flow's own coordinates.
    bool covers(double x, double y) const { return flow_->grid().contains(x - origin_x_, y - origin_y_); }
    const FlowReader& flow() const { return *flow_; }
    const ObstacleMap& obstacles() const { return obstacles_; }
    const WorldDef& def() const { return def_; }
    std::size_t size() const { return states_.size(); }
    const std::vector<BodyState>& states() const { return states_; }
    std::vector<BodyState>& states() { return states_; }  // tests set initial conditions
    const std::vector<BodyParams>& params() const { return params_; }
    const std::vector<BodyStats>& stats() const { return stats_; }
    // The buildings' ids on the obstacle grid (default: the mask's connected components).
    void set_building_ids(std::vector<std::int32_t> ids) { obstacles_.set_building_ids(std::move(ids)); }
    // Every impact on a building so far, by body and then time, in the flow's own
    // coordinates, with Impact::trajectory the body's index (debris/impacts.hpp).
    std::vector<Impact> impacts() const;
    // Clears the "colliding since the last output" bit of every body.
    void clear_event_flags();

private:
    void fit_window();  // the loaded tiles: those under each body plus the margin

    WorldDef def_;
    std::unique_ptr<FlowReader> flow_;
    double origin_x_ = 0.0, origin_y_ = 0.0;
    ObstacleMap obstacles_;
    double time_ = 0.0;
    bool window_fitted_ = false;
    std::vector<BodyState> states_;   // hot, per step
    std::vector<BodyParams> params_;  // cold, read only
    std::vector<BodyStats> stats_;
    std::vector<BodyImpacts> impacts_;  // cold, written on events
    std::vector<int> group_of_;         // per body
    std::vector<std::vector<int>> units_;  // the bodies stepped together, in order of their first body (rebuilt after add_body)
};

// The flow file opened for a world with `def` (its replay settings, and as many decoding
// threads as step the bodies unless set).
std::unique_ptr<FlowReader> open_flow(const std::string& path, const WorldDef& def);

// The world of one flow: the scene's building mask and ids on the flow's grid (scene null:
// no buildings), and the bodies. The flow must have been computed on the scene, and each
// body must start on the grid and off the buildings (debris/scene_match.hpp: the errors
// name the files or the body). With `ground` (a finer scene of the same place, null:
// none) the bodies stand on its ground and keep off its buildings too. Used by every
// flow of a sweep (`flotsam debris` is a sweep of one); the reader is the world's from
// then on.
// `groups`: each body's group (World::add_body; empty: each alone).
World make_world(std::unique_ptr<FlowReader> flow, const Scene* scene, const std::vector<BodyDef>& bodies, const WorldDef& def,
                 const Scene* ground = nullptr, const std::vector<int>& groups = {});
// The same, opening the flow file at `flow_path`.
World make_world(const std::string& flow_path, const Scene* scene, const std::vector<BodyDef>& bodies, const WorldDef& def,
                 const Scene* ground = nullptr, const std::vector<int>& groups = {});

}  // namespace flotsam::debris
