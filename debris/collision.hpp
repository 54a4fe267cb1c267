// Collision with fixed obstacles: impulses at the contacts and position correction.
#pragma once
#include <vector>

#include "debris/body.hpp"
#include "debris/impacts.hpp"
#include "debris/obstacles.hpp"

namespace flotsam::debris {

// A step ends with its collisions unresolved where an overlap deeper than this many
// cells (of the obstacle grid) is left. Contact detection is exact to round-off (some
// 1e-15 m), so anything deeper than round-off is an overlap; but an overlap of 1e-3 of a
// cell is 250 times below the quarter cell a corner may move in one step (the step limit
// that keeps bodies out of one-cell walls), it is seen again and pushed out at the next
// step, and it is the size of the second-order error of re-advancing a turning body along
// a straight step (r (ω Δt)² / 2: 6e-6 m for the paper's box at 1 rad/s and 10 ms, 6e-4
// of a 1 cm cell). A micrometre of overlap is not an unresolved collision.
inline constexpr double unresolved_overlap_cells = 1e-3;  // [-]

// The move out of overlaps keeps out of the blocked cells within this many cells of the
// body too, so that it does not push the body from one wall into another (a move out is
// the size of an overlap, a fraction of the quarter cell a corner moves in a step). The
// margin only chooses which cells are looked at: each such cell is a contact of the body's
// own box, its gap the most the move may close (ObstacleMap::find_contacts) [-].
inline constexpr double clearing_margin_cells = 0.25;

// No move out of walls carries a corner further than this many cells in one pass: an
// overlap a step makes is at most the quarter cell a corner moves, and further would
// carry it through a wall one cell thick. Nearly opposed contacts at nearly one point (a
// corner pressed both ways) admit only moves of kilometres and turns of many revolutions
// [-]. (At the margin instead, wedged bodies took more than the passes allow: a wedged LD
// box on the 1 cm ground jammed 1 035 steps instead of 14.)
inline constexpr double largest_move_cells = 1.0;

struct CollisionOutcome {
    bool touched = false;     // some contact was found
    bool unresolved = false;  // MC: the pass bound was reached with an overlap deeper than the tolerance left
    double residual = 0.0;    // deepest overlap left afterwards [m]
    int passes = 0;           // MC: detection passes that found contact [-]
};

// How the step being corrected moved the body: the collision advances the position and
// heading again from the start of the step with the corrected velocities, as the step
// did (paper §3.3, step 3: "correct the position based on the corrected momentum", with
// the motion's own time step).
struct StepMove {
    double dt = 0.0;           // the step [s]
    double new_weight = 1.0;   // share of the end-of-step velocity in the move: 1 (Euler), ½ (Heun) [-]
    double tolerance = 0.0;    // overlap left that still counts as resolved [m]
};

// What one body's collisions are resolved against, and with what: the obstacles and what
// blocks it, its effective mass and yaw inertia (added mass included where it is
// implicit, so an impulse changes the same momentum the dynamics integrates), the pass
// bound and the step being corrected.
struct CollisionSetup {
    const ObstacleMap& obstacles;
    Blocking blocking;
    const BodyParams& body;  // its collision model and restitution
    double mass = 0.0;       // [kg]
    double inertia = 0.0;    // [kg m²]
    int max_passes = 10;     // MC [-]
    StepMove move;
};

// Resolves overlaps of the body (state; `footprint` its pose, Box::make of it: made once
// a step, sincos included, by the caller) with blocked cells. A rotation about the contact
// centroid (the axis shift) is part of the momentum: it is handed to the centre's velocity
// and yaw rate first (V + ω_p ẑ × (x_g − x_sub), ω + ω_p).
//   single: the deepest contact only, one impulse, then a move out by its depth.
//   multi:  up to max_passes of {detect all; for each contact, deepest first, the impulse
//           (only where the contact approaches); the pose advanced again from the start of
//           the step with the corrected velocities; where an overlap is left (one the step
//           began with, a turning body's arc against the straight re-advance, two contacts
//           whose impulses undo each other in a wedge), the least move out of all of it at
//           once: the smallest M |Δx|² + I Δθ² that clears every contact to first order and
//           closes no gap to a cell within the clearing margin, so a body wedged across a
//           gap turns and slides out of it}.
// With `touches`, appends each building contacted (debris/impacts.hpp, BuildingTouch):
// nothing of the motion depends on it.
CollisionOutcome resolve_collisions(const CollisionSetup& setup, BodyState& state, const Box& footprint,
                                    std::vector<ObstacleCollision>& scratch, std::vector<BuildingTouch>* touches = nullptr);

// The axis shift's rotation about x_sub (a body turning about its contact centroid) as the
// centre's velocity and yaw rate, before an impulse changes them.
void hand_pivot_to_centre(BodyState& state);

// The deepest overlap of the pose `box` with what blocks the body [m]; `scratch` is left
// holding the overlaps.
double deepest_overlap(const ObstacleMap& obstacles, const Blocking& blocking, const Box& box,
                       std::vector<ObstacleCollision>& scratch);

}  // namespace flotsam::debris
