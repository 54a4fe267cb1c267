// Collision with fixed obstacles: impulses at the contacts and position correction.
#pragma once
#include <vector>

#include "debris/body.hpp"
#include "debris/obstacles.hpp"

namespace flotsam::debris {

struct CollisionOutcome {
    bool touched = false;     // some contact was found
    bool unresolved = false;  // MC: the pass bound was reached with contact left
    double residual = 0.0;    // deepest overlap left afterwards [m]
};

// Resolves overlaps of the body (state; `footprint` its pose, Box::make of it: made once
// a step, sincos included, by the caller) with blocked cells. mass and inertia are
// the body's effective ones (added mass included where it is implicit), so an impulse
// changes the same momentum the dynamics integrates.
//   single: the deepest contact only, one impulse and one correction.
//   multi:  up to max_passes of {detect all; for each contact, deepest first: impulse,
//           then move out by what is left of its depth}, until none is left.
CollisionOutcome resolve_collisions(const ObstacleMap& obstacles, const BodyParams& body, CollisionModel model, double mass,
                                    double inertia, double bottom, int max_passes, BodyState& state, const Box& footprint,
                                    std::vector<ObstacleContact>& scratch);

}  // namespace flotsam::debris
