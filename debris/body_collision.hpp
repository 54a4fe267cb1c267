// Bodies that meet each other. The bodies of one run share its world (World's groups): a
// container yard's boxes, a car park's cars. After each of them has taken its step (its
// own collisions with the buildings included), the contacts between them are resolved in
// the collision's multi-pass procedure (debris/collision.hpp), with the walls they are
// pressed on:
//
//   detection: a uniform grid of cells as wide as the largest body picks the pairs whose
//       bounding boxes overlap (the work stays linear in the count); a pair overlaps where
//       the separating-axis test of the two boxes finds no gap. Its normal is the axis of
//       least penetration, its contact point the middle of the incident face's part that
//       lies in the other box (the face clipped by the reference face's sides), its depth
//       the deepest such point below the reference face. One impulse per pair, at the
//       middle of the points below the face; the moves out hold both ends (the one above
//       the face as a gap not to close), so two faces nearly flat on each other do not rock.
//   impulses: at every approaching contact (pairs and walls, deepest first),
//       j = −(1 + e) v_n / (1/M_a + 1/M_b + (r_a × n)²/I_a + (r_b × n)²/I_b), equal and
//       opposite on the two bodies (momentum kept; e the mean of the two restitutions; no
//       friction between bodies, as with walls), in sweeps until none approaches (an
//       impact passes along a row of bodies one link per sweep); then the poses advanced
//       again from the step's start with the corrected velocities, once.
//   each pass: what overlap is left is moved out, each contact in turn as pseudo-impulses
//       share it (M and I weights), repeated until none is deeper than a thousandth of
//       the tolerance, the walls within the clearing margin held as gaps the moves may not
//       close; the contacts found again, an impulse where one approaches. So a body pressed
//       between a neighbour and a wall ends the step without overlap.
//
// Impacts between bodies are not impacts on buildings. A building loaded through a pile
// is hit by the bodies that touch it, each with its own approach speed and mass: the pile
// behind them acts only through how fast they arrive.
#pragma once
#include <array>
#include <vector>

#include "debris/body.hpp"
#include "debris/box.hpp"
#include "debris/collision.hpp"
#include "debris/impacts.hpp"
#include "debris/obstacles.hpp"

namespace flotsam::debris {

// The overlap of two bodies.
struct BodyCollision {
    int a = 0, b = 0;                 // the two bodies (indices into the group), a < b
    Vec2 normal;                      // unit, from b into a: the direction that separates a [-]
    double depth = 0.0;               // penetration along normal [m]
    Vec2 point;                       // where the impulses act: the middle of the points below the reference face [m]
    int points = 0;                   // the ends of the incident face's part across the reference face (1 at a corner's tip)
    Vec2 at[2];                       // [m]
    double depth_at[2] = {0.0, 0.0};  // each one's depth below the reference face; negative: the gap above it [m]
};

// Whether boxes a and b overlap by more than min_depth; the contact, with out.a and out.b
// left to the caller.
bool box_overlap(const Box& a, const Box& b, double min_depth, BodyCollision& out);

// The pairs (i, j), i < j, whose bounding boxes widened by `pad` [m] overlap, in increasing
// order; `cells` is working memory.
void candidate_pairs(const std::vector<Box>& boxes, double pad, std::vector<std::array<int, 2>>& out,
                     std::vector<std::array<long long, 2>>& cells);

// One body of a group while its contacts are resolved.
struct GroupBody {
    BodyState* state = nullptr;
    const BodyParams* body = nullptr;
    double mass = 0.0;                   // effective, added mass included where implicit [kg]
    double inertia = 0.0;                // effective yaw inertia [kg m²]
    Blocking blocking;                   // what blocks it (its bottom this step, the water over the cells)
    std::vector<BuildingTouch> touches;  // buildings touched: its own step's, and those its contacts in these passes add
    // Filled by resolve_body_collisions:
    bool met = false;           // it touched another body this step
    double body_overlap = 0.0;  // deepest overlap with another body left [m]
    double wall_overlap = 0.0;  // deepest overlap with a blocked cell left, where met [m]
};

struct BodyCollisionDef {
    int max_passes = 10;          // as the multi-collision's bound [-]
    StepMove move;                // the step being corrected (its Δt, the weight of the new velocity, the tolerance)
    bool note_buildings = false;  // fill GroupBody::touches
};

// Working memory of one group's resolution (reused from step to step).
struct BodyCollisionScratch {
    std::vector<Box> boxes;
    std::vector<std::array<int, 2>> pairs;
    std::vector<std::array<long long, 2>> cells;
    std::vector<BodyCollision> contacts;  // the pairs that overlap
    std::vector<BodyCollision> near;      // and those within the margin
    std::vector<ObstacleCollision> walls;
    struct Wall {
        int body;
        ObstacleCollision c;
    };
    std::vector<Wall> wall_contacts;
    std::vector<BodyState> reached;
    std::vector<Vec2> advanced;
    std::vector<double> advanced_turn;
    std::vector<Vec2> moved;
    std::vector<double> turned;
    std::vector<char> involved;
};

// Resolves the overlaps between the group's bodies (and the walls of the bodies that meet)
// after each took its step. Returns whether any two bodies touched.
bool resolve_body_collisions(const ObstacleMap& obstacles, std::vector<GroupBody>& group, const BodyCollisionDef& def,
                           BodyCollisionScratch& scratch);

// The deepest overlap between any two of the boxes [m] (0 where none overlap).
double deepest_body_overlap(const std::vector<Box>& boxes);

}  // namespace flotsam::debris
