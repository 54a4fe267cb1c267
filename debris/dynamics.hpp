// One body through the flow: forces, friction, axis shift, collisions, time step.
// The equations are in docs/debris.md; every step is independent of other bodies, so
// many bodies can go through the same loaded frames in parallel.
#pragma once
#include <string>
#include <vector>

#include "common/enum_names.hpp"
#include "debris/body.hpp"
#include "debris/body_collision.hpp"
#include "debris/ground_contact.hpp"
#include "debris/flow_sampler.hpp"
#include "debris/footprint.hpp"
#include "debris/impacts.hpp"
#include "debris/loads.hpp"
#include "debris/obstacles.hpp"

namespace flotsam::debris {

// The fluid-force stage of a step: semi-implicit Euler (the force at the start of the
// step), or Heun (the mean of the accelerations at the start and at an Euler-predicted
// end, positions with the mean of the old and new velocity). Friction, the axis shift and
// collisions follow the same way in both. See docs/debris.md.
enum class Integrator { euler, heun };
inline constexpr EnumNames<Integrator, 2> integrator_names{"integrator",
                                                           {{{Integrator::euler, "euler"}, {Integrator::heun, "heun"}}}};
constexpr const auto& enum_names(Integrator) { return integrator_names; }

struct StepDef {
    double water_density = 1000.0;       // ρw [kg/m³]
    double gravity = 9.81;               // g [m/s²]
    double dt_max = 0.01;                // upper bound of the time step [s]
    double vertex_step_fraction = 0.25;  // largest corner displacement per step, in cells [-]
    int max_collision_passes = 10;       // MC pass bound [-]
    Integrator integrator = Integrator::euler;
    // The bodies of one run meet each other (debris/body_collision.hpp); false: each body
    // goes through the flow as if alone.
    bool body_contact = true;
};
StepDef default_step_def();

// Working memory of one thread (reused, so steps do not allocate).
struct StepScratch {
    FootprintCache footprint;
    std::vector<GroundPatch> patches;
    std::vector<ObstacleCollision> contacts;
    std::vector<BuildingTouch> touches;
    std::vector<std::int32_t> open_saved;    // a body's open contact episodes before a step that may be redone
    std::vector<ObstacleCollision> jammed_at;  // the overlaps a jammed step left
};

struct StepContext {
    const FlowSampler& flow;
    const ObstacleMap& obstacles;
    const StepDef& def;
};

// The body's bottom at the pose `box`, its centre in `centre_depth` of water, with these
// contact patches (MODEL.md, "Vertical position"): afloat at η_c − d, or on the highest
// ground under its footprint where that is higher. The one bottom that the faces' wetted
// height (debris/loads.hpp), the steps that block the body and its collisions use. The
// ground is looked at where some of it under the body may be above where it would float
// (a contact patch, or any ground within reach above that), so that no cell under the
// footprint is ever above the bottom: none of them can block the body.
Resting resting_place(const StepContext& ctx, const BodyParams& body, const Box& box, double centre_depth,
                      const std::vector<GroundPatch>& patches);

// One step of length dt from state.time. Returns the largest displacement of a corner
// by the free motion (before collisions) [m], which the caller checks against the cell.
// With `impacts`, the impacts on buildings are recorded there (debris/impacts.hpp);
// nothing of the motion depends on it.
double step_body(const StepContext& ctx, const BodyParams& body, BodyState& state, BodyStats& stats, double dt,
                 StepScratch& scratch, BodyImpacts* impacts = nullptr);

// The step the vertex-speed limit allows at this state [s] (≤ def.dt_max).
double stable_step(const StepContext& ctx, const BodyParams& body, const BodyState& state);

// How far around the centre one step can need flow [m]: the body, the largest step
// travel and the bilinear stencil. The loaded window must reach this far.
double window_pad(const StepContext& ctx, const BodyParams& body);

// Steps the body to t_end. Returns false, early, when the body would need flow outside
// the reader's loaded window (the caller moves the window and calls again).
bool advance_body(const StepContext& ctx, const BodyParams& body, BodyState& state, BodyStats& stats, double t_end,
                  StepScratch& scratch, BodyImpacts* impacts = nullptr);

// The bodies of one run, stepped together so that they meet each other
// (debris/body_collision.hpp): every step as long as the one its fastest body allows (no
// corner moving more than the vertex-step fraction of the smaller of a cell and the
// narrowest body), each body's own step, then the contacts between them. Deterministic:
// the bodies are stepped and their contacts resolved in a fixed order. A body another one
// hits is released (it moves; the ground's friction holds it where it is grounded).
struct GroupScratch {
    StepScratch step;
    BodyCollisionScratch contacts;
    std::vector<GroupBody> bodies;
    std::vector<BodyState> saved;
    std::vector<BodyStats> saved_stats;
    std::vector<std::size_t> saved_events;
    std::vector<std::vector<std::int32_t>> saved_open;
};
struct BodyGroup {
    const std::vector<int>& members;  // indices into the arrays below, in order
    const std::vector<BodyParams>& params;
    std::vector<BodyState>& states;
    std::vector<BodyStats>& stats;
    std::vector<BodyImpacts>* impacts;  // null: no buildings to record impacts on
};
// Steps the group to t_end; false, early, where one of its bodies would need flow outside
// the loaded window (as advance_body).
bool advance_group(const StepContext& ctx, BodyGroup& group, double t_end, GroupScratch& scratch);

}  // namespace flotsam::debris
