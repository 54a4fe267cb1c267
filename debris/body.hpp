// One debris body: what the user defines (BodyDef), what follows from it once
// (BodyParams, cold, read every step but never written), and what changes every step
// (BodyState, hot and small). See docs/debris.md for the equations.
#pragma once
#include <cstdint>
#include <string>

#include "common/enum_names.hpp"
#include "common/settings.hpp"
#include "debris/obstacles.hpp"
#include "formats/trajectory_file.hpp"

namespace flotsam::debris {

// Friction model: the whole bottom at the centre (CC, STOC-DM) or cell by cell under
// the footprint (LC, Chida & Mori), with the axis shift.
enum class ContactModel { center, local };
inline constexpr EnumNames<ContactModel, 5> contact_model_names{"contact model",
                                                                {{{ContactModel::center, "center"},
                                                                  {ContactModel::local, "local"},
                                                                  {ContactModel::center, "centre"},
                                                                  {ContactModel::center, "CC"},
                                                                  {ContactModel::local, "LC"}}}};
constexpr const auto& enum_names(ContactModel) { return contact_model_names; }

// Collision model: one contact per step (SC, STOC-DM) or repeated until none (MC).
enum class CollisionModel { single, multi };
inline constexpr EnumNames<CollisionModel, 4> collision_model_names{"collision model",
                                                                    {{{CollisionModel::single, "single"},
                                                                      {CollisionModel::multi, "multi"},
                                                                      {CollisionModel::single, "SC"},
                                                                      {CollisionModel::multi, "MC"}}}};
constexpr const auto& enum_names(CollisionModel) { return collision_model_names; }

// Added mass on the left-hand side (implicit, the baseline) or as last step's
// acceleration on the right-hand side (explicit, kept only for the stability study).
enum class AddedMass { implicit, explicit_ };
inline constexpr EnumNames<AddedMass, 2> added_mass_names{
    "added-mass treatment", {{{AddedMass::implicit, "implicit"}, {AddedMass::explicit_, "explicit"}}}};
constexpr const auto& enum_names(AddedMass) { return added_mass_names; }

// How the rate of the rotation about the contact centroid (the axis shift, paper Eqs.
// 6-10) goes from one step to the next while Eq. 6 holds (docs/debris.md, "Axis shift"):
// `carried`, the yaw equation about the contact, I_sub dω_p/dt = T_sub, integrated from
// the last step's rate; `restarted`, from rest every step (Δθ_sub = Δt² T_sub / I_sub);
// `braked`, carried and slowed every step by the friction's moment about the centroid,
// which the paper's T' leaves out (kept for comparison).
enum class PivotRate { carried, restarted, braked };
inline constexpr EnumNames<PivotRate, 3> pivot_rate_names{
    "pivot rate",
    {{{PivotRate::carried, "carried"}, {PivotRate::restarted, "restarted"}, {PivotRate::braked, "braked"}}}};
constexpr const auto& enum_names(PivotRate) { return pivot_rate_names; }

// The most drag sample points along one face (the range of BodyDef::samples_per_face).
inline constexpr int max_samples_per_face = 16;

struct BodyDef {
    std::string name;                // label in outputs (e.g. the scene point "FD")
    double x = 0.0;                  // initial centre [m]
    double y = 0.0;                  // initial centre [m]
    double heading = 0.0;            // long axis from +x, counter-clockwise [rad]
    double length = 0.25;            // L, along the heading [m]
    double width = 0.10;             // B [m]
    double height = 0.10;            // D [m]
    double specific_gravity = 0.25;  // body density / water density [-]
    double cd1 = 0.8;                // drag coefficient, flow toward a face [-]
    double cd2 = 0.4;                // drag coefficient, flow leaving a face [-]
    double cm = 2.0;                 // inertia coefficient Cm = 1 + C_a [-]
    double mu = 0.4;                 // Coulomb friction coefficient with the ground [-]
    double restitution = 0.5;        // e in collisions with obstacles, 0..1 [-]
    ContactModel contact = ContactModel::local;
    CollisionModel collision = CollisionModel::multi;
    AddedMass added_mass = AddedMass::implicit;
    bool added_yaw_inertia = false;  // yaw inertia I + ρ C_a V_s (L² + B²)/12 instead of Eq. 2's I (an extension) [-]
    bool axis_shift = true;          // LC only: rotate about the contact centroid (paper Eqs. 6-10)
    PivotRate pivot_rate = PivotRate::carried;  // LC only: the axis shift's rate from step to step
    BlockingGround blocking_ground = BlockingGround::land;  // ground that can block (docs/debris.md, "Ground and obstacles")
    int samples_per_face = 4;        // drag sample points along each side face, 1 to max_samples_per_face [-]
    // The body's crushing stiffness for the impact-force estimate (debris/impacts.hpp); not a
    // setting of the motion, set by the catalogue entry. 0: Froude-scaled from the paper's
    // box (default_impact_stiffness) [N/m].
    double impact_stiffness = 0.0;
    double step_tolerance =
        0.2;  // a cell the body moves into blocks where its ground rises above the body's bottom by more than this × draft (docs/debris.md, "Ground and obstacles") [-]
};
BodyDef default_body_def();  // the paper's control case, LC + MC

// The body's settings, one table per family (common/settings.hpp): key, member, unit,
// help and valid range; the defaults are BodyDef's initialisers above. Every table is
// an option of `flotsam debris`; in a sweep spec the shape and model go in [[body]] (the
// model also in [sweep], for every body), the coefficients are what [parameters]
// designs vary, and the variant is [variants].
const Settings<BodyDef>& body_shape_settings();        // length, width, height, specific-gravity
const Settings<BodyDef>& body_coefficient_settings();  // cd1, cd2, cm, mu, restitution
const Settings<BodyDef>& body_model_settings();  // added-mass, axis-shift, pivot-rate, added-yaw-inertia, samples-per-face,
                                                 // step-tolerance, blocking-ground
const Settings<BodyDef>& body_variant_settings();      // contact, collision

// Derived once from a BodyDef.
struct BodyParams {
    BodyDef def;
    double mass = 0.0;           // m = s.g. ρ L B D [kg]
    double draft = 0.0;          // d = m / (ρ L B) [m]
    double inertia = 0.0;        // I = m (L² + B²) / 12 about the vertical axis through the centre [kg m²]
    double plan_area = 0.0;      // L B [m²]
    double radius_sq = 0.0;      // (L² + B²) / 12, I / m [m²]
    double step_height = 0.0;    // step_tolerance × draft [m]
    double half_diagonal = 0.0;  // ½ √(L² + B²): the farthest a corner is from the centre [m]
    double impact_stiffness = 0.0;  // k of the impact force, def's or the Froude default [N/m]
    double impact_threshold = 0.0;  // approach speed below which a contact is no impact [m/s]
    double impact_separation = 0.0; // clearance that ends a contact episode [m]
};
BodyParams make_body_params(const BodyDef& def, double water_density);  // throws on bad values

// The per-step state: small, read and written every step.
struct BodyState {
    double x = 0.0, y = 0.0;                                // centre [m]
    double theta = 0.0;                                     // heading [rad]
    double vx = 0.0, vy = 0.0;                              // translational velocity V of Eq. 1 [m/s]
    double omega = 0.0;                                     // yaw rate about the centre [rad/s]
    double pivot_rate = 0.0;                                // yaw rate about the contact centroid while the axis is shifted [rad/s]
    double pivot_ax = 0.0, pivot_ay = 0.0;                  // that centroid relative to the centre [m]
    double torque_prev = 0.0;                               // T' of the last step: flow torque without friction [N m]
    double ax_prev = 0.0, ay_prev = 0.0, alpha_prev = 0.0;  // last accelerations, explicit added mass only [m/s², rad/s²]
    double
        centre_vx = 0.0,
        centre_vy =
            0.0;  // the centre's velocity over the last step, (x^(n+1) − x^n)/Δt: V, the pivot's Δx_sub and collision moves [m/s]
    double time = 0.0;       // [s]
    std::uint8_t flags = 0;  // BodyFlag bits
};
BodyState initial_state(const BodyDef& def, double time);

// Counters over a run, for reports and tests (cold: written only on events).
struct BodyStats {
    long steps = 0;
    long collisions = 0;                // steps with at least one obstacle contact
    long unresolved = 0;                // MC: steps that end with an overlap deeper than the tolerance (debris/collision.hpp)
    long axis_shifts = 0;               // steps rotated about the contact centroid
    double max_residual_overlap = 0.0;  // deepest obstacle overlap left after collision handling [m]
    long jams = 0;                      // MC: steps undone because the passes could not clear the overlap
    long body_contacts = 0;             // steps with a contact with another body of its run
    double max_body_overlap = 0.0;      // deepest overlap with another body left after collision handling [m]
};

}  // namespace flotsam::debris
