// The body model against numbers that follow from its equations.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "cases/debris_flows.hpp"
#include "debris/ground_contact.hpp"
#include "debris/loads.hpp"
#include "debris/world.hpp"
#include "tests/test_support.hpp"

using namespace flotsam;
using namespace flotsam::debris;

namespace {

const Grid fine{160, 80, -0.795, -0.395, 0.01, 0.01};  // 1.6 m x 0.8 m around the origin, 1 cm cells

using test::body_at;

// Puts a body down already released (as if the water had once been deeper than the draft).
BodyState& released(World& w, std::size_t b) {
    w.states()[b].flags |= flag_released;
    return w.states()[b];
}

// The paper's body and water: L 0.25 m, B 0.10 m, s.g. 0.25, so d = 2.5 cm, m = 0.625 kg.
constexpr double rho = 1000.0, g = 9.81;

// The flow's load on a body at rest at the origin with `heading`, from a flow file, at t.
// The load on a body at rest at the origin: afloat, or (resting_on_ground) with its bottom
// on the ground at `bottom` [m].
FluidLoad load_at_rest(const std::string& path, const BodyDef& def, double heading, double t = 0.5, bool resting_on_ground = false,
                       double bottom = 0.0) {
    FlowReader flow(path);
    flow.prepare(t);
    const BodyParams p = make_body_params(def, rho);
    const FlowPointAccel centre = flow.sample_accel(0.0, 0.0, t);
    const Motion at_rest{{0.0, 0.0}, heading, {0.0, 0.0}, 0.0, 0.0, {0.0, 0.0}};
    const ObstacleMap ground(flow.grid(), flow.description().bed, {});
    const Resting rest{resting_on_ground, bottom, &ground};
    return fluid_load(flow, p, at_rest, centre, p.plan_area * std::min(p.draft, centre.depth), t, rho, rest);
}

// Sum of the friction patch capacities [N] of a body at rest at the origin.
double friction_capacity_at_rest(const std::string& path, ContactModel contact) {
    FlowReader flow(path);
    flow.prepare(0.5);
    BodyDef def = body_at(0.0, 0.0, 0.3, contact);
    const BodyParams p = make_body_params(def, rho);
    FootprintCache footprint;
    std::vector<GroundPatch> patches;
    ground_patches(flow, flow.grid(), p, Box::make({0.0, 0.0}, 0.3, def.length, def.width), flow.depth(0.0, 0.0, 0.5), 0.5, rho, g,
                    footprint, patches);
    double sum = 0.0;
    for (const auto& q : patches) sum += q.capacity;
    return sum;
}

}  // namespace

// The paper's body and its derived numbers.
TEST(DebrisBody, PaperBodyMassDraftAndYawInertia) {
    const BodyParams p = make_body_params(default_body_def(), rho);
    EXPECT_NEAR(p.mass, 0.625, 1e-12);
    EXPECT_NEAR(p.draft, 0.025, 1e-12);
    EXPECT_NEAR(p.inertia, 3.776e-3, 3.776e-3 * 1e-4);  // m (L² + B²)/12 = 3.7760e-3 kg m²
}

// Afloat at rest in a uniform 1 m/s current 10 cm deep: drag ½ ρ (Cd1 + Cd2) ℓ d U²
// with Cd1 0.8 on the face the flow meets and Cd2 0.4 on the one it leaves. Broadside
// (ℓ = L): 3.75 N; end-on (ℓ = B): 1.50 N; no side force, no torque. The first step
// (10 ms) then accelerates the body at F/(m + ρ C_a L B d) = F/1.25 kg.
TEST(DebrisBody, DragAfloatBroadsideAndEndOnMatchHandValues) {
    const auto dir = test::scratch_dir("body_drag");
    const auto path = test::uniform_flow(dir + "/f.nc", fine, 2, 0.1, 1.0, 0.0);
    const FluidLoad broadside = load_at_rest(path, default_body_def(), 0.5 * M_PI);
    EXPECT_NEAR(broadside.force.x, 3.75, 3.75e-2);
    EXPECT_NEAR(broadside.force.y, 0.0, 1e-9);
    EXPECT_NEAR(broadside.torque, 0.0, 1e-9);
    const FluidLoad end_on = load_at_rest(path, default_body_def(), 0.0);
    EXPECT_NEAR(end_on.force.x, 1.50, 1.50e-2);
    EXPECT_NEAR(end_on.force.y, 0.0, 1e-9);

    World w(path, {});
    w.add_body(body_at(0.0, 0.0, 0.5 * M_PI, ContactModel::local));
    w.advance_to(0.01);
    EXPECT_NEAR(w.states()[0].vx, 0.01 * 3.75 / 1.25, 0.01 * 0.03);
}

// Cd1 acts only on the face the flow meets, Cd2 only on the one it leaves: broadside at
// 1 m/s with Cd2 = 0 the drag is ½ ρ Cd1 L d U² = 2.5 N, with Cd1 = 0 it is
// ½ ρ Cd2 L d U² = 1.25 N.
TEST(DebrisBody, DragCoefficientsActOnTheirOwnFaces) {
    const auto dir = test::scratch_dir("body_cd");
    const auto path = test::uniform_flow(dir + "/f.nc", fine, 2, 0.1, 1.0, 0.0);
    BodyDef toward = default_body_def(), away = default_body_def();
    toward.cd2 = 0.0;
    away.cd1 = 0.0;
    EXPECT_NEAR(load_at_rest(path, toward, 0.5 * M_PI).force.x, 2.5, 2.5e-2);
    EXPECT_NEAR(load_at_rest(path, away, 0.5 * M_PI).force.x, 1.25, 1.25e-2);
}

// Friction capacity, centre and local contact alike: on dry ground μ m g = 2.4525 N; at
// h = 2 cm μ (m − ρ L B h) g = 0.4905 N. A body sliding on dry ground at 0.5 m/s then
// slows at μ g = 3.924 m/s² (0.1076 m/s after 0.1 s); in 2 cm of still water, with no
// drag, at 0.4905 N/(m + ρ C_a L B h) = 0.436 m/s² (0.1564 m/s after 0.1 s from 0.2).
TEST(DebrisBody, FrictionMatchesHandValuesDryAndAtTwoCentimetres) {
    const auto dir = test::scratch_dir("body_friction");
    const auto dry = test::uniform_flow(dir + "/dry.nc", fine, 2, 0.0, 0.0, 0.0);
    const auto wet = test::uniform_flow(dir + "/wet.nc", fine, 2, 0.02, 0.0, 0.0);
    for (ContactModel contact : {ContactModel::center, ContactModel::local}) {
        EXPECT_NEAR(friction_capacity_at_rest(dry, contact), 2.4525, 2.4525e-2) << enum_name(contact);
        EXPECT_NEAR(friction_capacity_at_rest(wet, contact), 0.4905, 0.4905e-2) << enum_name(contact);
        for (const auto& [path, v0, v_end] :
             {std::tuple{dry, 0.5, 0.5 - 3.924 * 0.1}, std::tuple{wet, 0.2, 0.2 - 0.4905 / 1.125 * 0.1}}) {
            World w(path, {});
            BodyDef b = body_at(0.0, 0.0, 0.0, contact);
            b.cd1 = b.cd2 = 0.0;
            w.add_body(b);
            released(w, 0).vx = v0;
            w.advance_to(0.1);
            EXPECT_NEAR(w.states()[0].vx, v_end, 0.01 * v_end) << enum_name(contact) << " from " << v0;
            EXPECT_EQ(w.states()[0].vy, 0.0);
        }
    }
}

// A steady shear u = G y (G = 2 s⁻¹, 10 cm deep) across a body at rest, heading 0: the
// end faces' drag turns it, with no net force. At the sample points y = ±B/8, ±3B/8 of
// each end face (segment B/4 × d), T = −ρ (B d/4) G² (Cd1 + Cd2) (1³ + 3³)(B/8)³ =
// −1.6406e-4 N m, so the first 10 ms step turns it at ω = Δt T/I: −4.345e-4 rad/s with
// the paper's I (Eq. 2), half that with the added yaw inertia (afloat at Cm = 2 it equals
// I).
TEST(DebrisBody, YawFollowsEquationTwoInertiaUnlessAddedYawInertiaIsAsked) {
    const auto dir = test::scratch_dir("body_yaw");
    const double G = 2.0;
    const auto path = test::write_flow(
        dir + "/shear.nc", fine, {0.0, 2.0}, [](double, double) { return -0.1; },
        [&](double, double y, double) {
            return test::FlowState{0.1f, float(G * y), 0.0f};
        });
    const double T = -rho * (0.1 * 0.025 / 4) * G * G * 1.2 * 28 * std::pow(0.1 / 8, 3);
    const FluidLoad load = load_at_rest(path, default_body_def(), 0.0);
    EXPECT_NEAR(load.torque, T, 0.01 * std::fabs(T));
    EXPECT_NEAR(load.force.x, 0.0, 1e-6 * std::fabs(T) / 0.1);
    for (bool added : {false, true}) {
        World w(path, {});
        BodyDef b = body_at(0.0, 0.0, 0.0, ContactModel::local);
        b.added_yaw_inertia = added;
        w.add_body(b);
        const double inertia = 3.776e-3 * (added ? 2.0 : 1.0);
        EXPECT_NEAR(effective_inertia(w.params()[0], 0.1 * 0.25 * 0.025, rho).inertia, inertia, inertia * 1e-4);
        w.advance_to(0.01);
        EXPECT_NEAR(w.states()[0].omega, 0.01 * T / inertia, 0.01 * std::fabs(0.01 * T / inertia)) << "added " << added;
    }
}

// A uniform flow accelerating at a = 0.1 m/s² from rest, Du/Dt = a. Afloat (ρ V_s = m)
// the inertia force ρ V_s Cm a over the mass m + ρ C_a V_s gives exactly a, whatever Cm:
// the body keeps pace with the water (V = a t, no drag). Resting in 2 cm (ρ V_s = 0.5 kg,
// μ = 0, no drag) it lags: dV/dt = ρ V_s Cm a / (m + ρ V_s (Cm − 1)) = 0.8 a, 0.889 a,
// 0.923 a at Cm = 1, 2, 3, so V(1 s) = 0.08, 0.0889, 0.0923 m/s.
TEST(DebrisBody, AcceleratingFlowMovesBodyByInertiaAndAddedMass) {
    const auto dir = test::scratch_dir("body_accel");
    const double a = 0.1;
    auto accelerating = [&](const std::string& name, double depth) {
        return test::write_flow(
            dir + "/" + name, fine, {0.0, 1.0, 2.0}, [](double, double) { return -0.1; },
            [&](double, double, double t) {
                return test::FlowState{float(depth), float(a * t), 0.0f};
            });
    };
    const auto deep = accelerating("deep.nc", 0.1), shallow = accelerating("shallow.nc", 0.02);
    for (double cm : {1.0, 2.0, 3.0}) {
        World afloat(deep, {});
        BodyDef b = body_at(0.0, 0.0, 0.3, ContactModel::local);
        b.cm = cm;
        afloat.add_body(b);
        afloat.advance_to(1.0);
        EXPECT_NEAR(afloat.states()[0].vx, a * 1.0, 0.01 * a) << "Cm " << cm;
        EXPECT_NEAR(afloat.states()[0].vy, 0.0, 1e-9);

        World resting(shallow, {});
        b.mu = 0.0;
        b.cd1 = b.cd2 = 0.0;
        resting.add_body(b);
        released(resting, 0);
        resting.advance_to(1.0);
        const double Vs_rho = rho * 0.25 * 0.1 * 0.02;
        const double expected = Vs_rho * cm * a / (0.625 + Vs_rho * (cm - 1.0)) * 1.0;
        EXPECT_NEAR(resting.states()[0].vx, expected, 0.01 * expected) << "Cm " << cm;
    }
}

// A free body in a uniform steady current: only the end faces feel drag, so
//   M dw/dt = −½ ρ (Cd1 + Cd2) B d w²,  w = U − V,  M = m + ρ C_a L B d,
// giving w(t) = U / (1 + t/τ) with τ = M / (½ ρ (Cd1 + Cd2) B d U). At t = τ the body
// has closed half the gap, at t = 3τ three quarters.
TEST(DebrisBody, RelaxesToUniformCurrentWithDragAndAddedMassTimeConstant) {
    const auto dir = test::scratch_dir("body_relax");
    const double U = 0.1, depth = 0.1;
    const Grid g{400, 40, -0.995, -0.195, 0.01, 0.01};  // 4 m long
    World w(test::uniform_flow(dir + "/f.nc", g, 60, depth, U, 0.0), {});
    const BodyParams p = make_body_params(default_body_def(), 1000.0);
    w.add_body(body_at(-0.6, 0.0, 0.0, ContactModel::local));
    const double M = p.mass + 1000.0 * (p.def.cm - 1.0) * p.plan_area * p.draft;
    const double tau = M / (0.5 * 1000.0 * (p.def.cd1 + p.def.cd2) * p.def.width * p.draft * U);
    EXPECT_NEAR(M, 1.25, 1e-12);  // added mass equals the body's own for s.g. 0.25 and C_a = 1
    w.advance_to(tau);
    EXPECT_NEAR((U - w.states()[0].vx) / U, 0.5, 0.005) << "tau = " << tau;
    w.advance_to(3 * tau);
    EXPECT_NEAR((U - w.states()[0].vx) / U, 0.25, 0.004);
    EXPECT_NEAR(w.states()[0].vy, 0.0, 1e-12);
    EXPECT_NEAR(w.states()[0].omega, 0.0, 1e-12);
}

TEST(DebrisBody, StaysPutInStillWater) {
    const auto dir = test::scratch_dir("body_still");
    for (double depth : {0.1, 0.02}) {  // floating, and resting on the bed
        World w(test::uniform_flow(dir + (depth > 0.05 ? "/deep.nc" : "/shallow.nc"), fine, 20, depth, 0.0, 0.0), {});
        w.add_body(body_at(0.0, 0.0, 0.3, ContactModel::local));
        w.add_body(body_at(0.3, 0.1, -0.5, ContactModel::center));
        released(w, 0);
        released(w, 1);
        w.advance_to(20.0);
        EXPECT_LT(std::fabs(w.states()[0].x - 0.0), 1e-12);
        EXPECT_LT(std::fabs(w.states()[0].y - 0.0), 1e-12);
        EXPECT_LT(std::fabs(w.states()[1].x - 0.3), 1e-12);
        EXPECT_LT(std::fabs(w.states()[1].theta + 0.5), 1e-12);
    }
}

// Grounded at depth 2 cm < draft: friction capacity μ (m − ρ L B h) g = 0.4905 N. Drag on
// the end face ½ ρ (Cd1 + Cd2) B h U² = 1.2 U² N reaches it at U* = 0.6393 m/s: 1 %
// below U* the body is held, 1 % above (2 % more force) it slides.
TEST(DebrisBody, StaticFrictionHoldsJustBelowTheDragThatEqualsItAndSlidesJustAbove) {
    const auto dir = test::scratch_dir("body_static");
    const double U_star = std::sqrt(0.4 * (0.625 - 1000.0 * 0.25 * 0.1 * 0.02) * 9.81 / (0.5 * 1000.0 * 1.2 * 0.1 * 0.02));
    EXPECT_NEAR(U_star, 0.6393, 1e-4);
    for (ContactModel contact : {ContactModel::center, ContactModel::local}) {
        World weak(test::uniform_flow(dir + "/weak.nc", fine, 5, 0.02, 0.99 * U_star, 0.0), {});
        weak.add_body(body_at(0.0, 0.0, 0.0, contact));
        released(weak, 0);
        weak.advance_to(5.0);
        EXPECT_EQ(weak.states()[0].x, 0.0) << enum_name(contact);
        EXPECT_TRUE(weak.states()[0].flags & flag_grounded);

        World strong(test::uniform_flow(dir + "/strong.nc", fine, 1, 0.02, 1.01 * U_star, 0.0), {});
        strong.add_body(body_at(0.0, 0.0, 0.0, contact));
        released(strong, 0);
        strong.advance_to(1.0);
        EXPECT_GT(strong.states()[0].x, 1e-4) << enum_name(contact);
        EXPECT_NEAR(strong.states()[0].y, 0.0, 1e-12);
    }
}

// A body must first float: at depth below the draft it waits, even in a strong current.
TEST(DebrisBody, StartsOnlyWhenDepthExceedsDraft) {
    const auto dir = test::scratch_dir("body_start");
    World w(test::uniform_flow(dir + "/f.nc", fine, 3, 0.024, 1.0, 0.0), {});
    w.add_body(body_at(0.0, 0.0, 0.0, ContactModel::local));
    w.advance_to(3.0);
    EXPECT_EQ(w.states()[0].x, 0.0);
    EXPECT_FALSE(w.states()[0].flags & flag_released);
}

// Spinning on dry ground: centre contact puts all friction at the centre, so the spin
// is untouched; local contact spreads it over the footprint and stops the spin.
TEST(DebrisBody, CentreContactNeverDampsYawLocalContactDoes) {
    const auto dir = test::scratch_dir("body_spin");
    const auto path = test::uniform_flow(dir + "/dry.nc", fine, 2, 0.0, 0.0, 0.0);
    World cc(path, {}), lc(path, {});
    cc.add_body(body_at(0.0, 0.0, 0.0, ContactModel::center));
    lc.add_body(body_at(0.0, 0.0, 0.0, ContactModel::local));
    released(cc, 0).omega = 1.0;
    released(lc, 0).omega = 1.0;
    cc.advance_to(1.0);
    lc.advance_to(1.0);
    EXPECT_EQ(cc.states()[0].omega, 1.0);
    EXPECT_NEAR(cc.states()[0].theta, 1.0, 1e-9);
    EXPECT_EQ(lc.states()[0].omega, 0.0);
    EXPECT_EQ(lc.states()[0].x, 0.0);
    // Spin-down: I dω/dt = −μ m g ∫ r dA / (L B). Over the rectangle, ∫ r dA =
    // 4 J(L/2, B/2) with J(a, b) = [2 a b D + a³ ln((b + D)/a) + b³ ln((a + D)/b)]/6,
    // D = √(a² + b²): 1.7670e-3 m³, so the torque is 0.17335 N m and dω/dt = 45.91 rad/s²
    // with I = 3.776e-3 kg m². The first 10 ms step takes 0.4591 rad/s off (the patches'
    // sum over 1 cm cells is 0.12 % below the integral).
    World first(path, {});
    first.add_body(body_at(0.0, 0.0, 0.0, ContactModel::local));
    released(first, 0).omega = 1.0;
    first.advance_to(0.01);
    EXPECT_NEAR((1.0 - first.states()[0].omega) / 0.01, 45.91, 0.4591);
}

// A floating body (5 mm under it) with one corner on a ridge (3 mm under the draft there)
// in a weak current across its long side. With local contact the ridge friction holds
// the corner, and the axis shift turns the body about the contact: the held corner
// barely moves while the centre swings along an arc (looked at over the first 8 s, about
// 37°: the turn goes on, and the part of the bottom over the ridge, so the axis, moves
// with it). Centre contact sees the centre afloat, so the body drifts off whole.
TEST(DebrisBody, PivotsAboutCornerHeldOnRidgeWithLocalContact) {
    const auto dir = test::scratch_dir("body_pivot");
    const double U = 0.04, level = 0.0;
    auto ridge = [](double x, double y) { return x > 0.09 && y > 0.01; };
    const auto path = test::write_flow(
        dir + "/ridge.nc", fine, {0.0, 30.0}, [&](double x, double y) { return ridge(x, y) ? -0.022 : -0.03; },
        [&](double x, double y, double) {
            return test::FlowState{float(level - (ridge(x, y) ? -0.022 : -0.03)), 0.0f, float(U)};
        });
    // held: the body point over the contact centroid after the first step (a material
    // point, tracked in the body frame).
    auto run = [&](ContactModel contact, bool axis_shift, double& held_move, double& centre_move, double& turn,
                   double& radius_change) {
        World w(path, {});
        BodyDef b = body_at(0.0, 0.0, 0.0, contact);
        b.axis_shift = axis_shift;
        w.add_body(b);
        released(w, 0);
        w.advance_to(0.01);
        const BodyState s0 = w.states()[0];
        const Vec2 held0 = (s0.flags & flag_pivoting) ? Vec2{s0.x + s0.pivot_ax, s0.y + s0.pivot_ay} : Vec2{0.107, 0.03};
        const Vec2 held_body = rotate(held0 - Vec2{s0.x, s0.y}, -s0.theta);
        w.advance_to(8.0);
        const BodyState& s = w.states()[0];
        const Vec2 centre{s.x, s.y};
        held_move = norm(centre + rotate(held_body, s.theta) - held0);
        centre_move = norm(centre);
        turn = s.theta;
        radius_change = std::fabs(norm(centre - held0) - norm(held0)) / norm(held0);
    };
    double held, centre, turn, radius;
    run(ContactModel::local, true, held, centre, turn, radius);
    EXPECT_GT(centre, 0.05);
    EXPECT_LT(turn, -0.5);           // clockwise: the free end swings downstream (+y)
    EXPECT_LT(held, 0.15 * centre);  // the held point stays
    EXPECT_LT(radius, 0.05);         // the centre keeps its distance from it: an arc

    run(ContactModel::center, true, held, centre, turn, radius);
    EXPECT_GT(held, 0.5 * centre);  // drifts off whole
    EXPECT_GT(centre, 0.05);

    // Local friction without the axis shift holds the body still: the turn comes from the shift.
    run(ContactModel::local, false, held, centre, turn, radius);
    EXPECT_LT(std::fabs(turn), 0.01);
    EXPECT_LT(centre, 1e-3);
}

// A body at rest (heading 0, centre at the origin) with 40 % of its footprint over 2.0 cm
// of water (a strip 1 cm ≤ y ≤ 5 cm along its north side, ground at −2 cm) and the rest
// over 3.0 cm (ground at −3 cm), level 0, on 1 cm cells, in a current of 0.1 m/s along its
// long axis (+x, across its 10 cm ends). It rests on the strip: its bottom is at −2 cm,
// 0.5 cm above where it would float. By hand:
//  * friction capacity (Eq. 5; only the strip's cells are shallower than the 2.5 cm
//    draft): 0.4 μ (m − ρ L B h) g = 0.4 × 0.4 × (0.625 − 0.5) × 9.81 = 0.1962 N;
//  * flow force: drag on the two ends, ½ ρ (Cd1 + Cd2) U² (B/4) Σ s_p over the four
//    samples of an end at y = 3.75, 1.25, −1.25, −3.75 cm, wetted from the bottom (−2 cm)
//    to the level: s_p = min(d, h(p) − (z_bot − z(p))) = 2.0, 2.25 (h bilinear between the
//    cell rows at 0.5 and 1.5 cm, z(p) the strip's), 2.0, 2.0 cm (3 cm of water, 1 cm of
//    it under the bottom): 600 × 0.025 × 0.0825 × 0.01 = 0.012375 N along +x; its torque
//    about the centre, T' = −Σ y_p F_p = −0.15 × 3.125e-5 = −4.688e-6 N m (the
//    wetted heights nearly even: the deeper south half's extra depth passes under the body);
//  * contact centroid x_sub = (0, 3 cm): T_sub = T' + (x_g − x_sub) × F =
//    −4.688e-6 + 0.03 × 0.012375 = 3.666e-4 N m; I_sub = I + M |x_g − x_sub|² with
//    I = m (L² + B²)/12 = 3.776e-3 kg m² and M = m + ρ C_a L B d = 1.25 kg (the centre is
//    in 3 cm of water): 4.901e-3 kg m²; T_sub / I_sub = 0.07479 rad/s².
// Eq. 6 holds at once (at rest, |F| ≤ |F_frc|), so the body turns counter-clockwise about
// the strip, its centre on an arc of 3 cm about x_sub (east, downstream, at first).
TEST(DebrisBody, AxisShiftTurnsAboutTheContactCentroidWithHandValues) {
    const auto dir = test::scratch_dir("body_axis_shift");
    const double U = 0.1;
    auto bed = [](double, double y) { return (y > 0.01 && y < 0.05) ? -0.02 : -0.03; };
    const auto path = test::write_flow(dir + "/strip.nc", fine, {0.0, 5.0}, bed, [&](double x, double y, double) {
        return test::FlowState{float(-bed(x, y)), float(U), 0.0f};
    });
    const BodyDef def = body_at(0.0, 0.0, 0.0, ContactModel::local);
    const BodyParams p = make_body_params(def, rho);
    {
        FlowReader flow(path);
        flow.prepare(0.0);
        FootprintCache footprint;
        std::vector<GroundPatch> patches;
        ground_patches(flow, flow.grid(), p, Box::make({0.0, 0.0}, 0.0, def.length, def.width), flow.depth(0.0, 0.0, 0.0), 0.0,
                        rho, g, footprint, patches);
        double capacity = 0.0, area = 0.0;
        Vec2 centroid;
        for (const auto& q : patches) {
            capacity += q.capacity;
            area += q.area;
            centroid += q.area * q.r;
        }
        centroid = (1.0 / area) * centroid;
        EXPECT_NEAR(area / p.plan_area, 0.4, 1e-9);
        EXPECT_NEAR(capacity, 0.1962, 0.001962);
        EXPECT_NEAR(centroid.x, 0.0, 1e-9);
        EXPECT_NEAR(centroid.y, 0.03, 1e-9);
    }
    const FluidLoad load = load_at_rest(path, def, 0.0, 0.0, true, -0.02);  // resting on the strip
    EXPECT_NEAR(load.force.x, 0.012375, 0.00012375);
    EXPECT_NEAR(load.force.y, 0.0, 1e-12);
    EXPECT_NEAR(load.torque, -4.688e-6, 4.688e-8);
    const double M = 1.25, I_sub = p.inertia + M * 0.03 * 0.03, T_sub = load.torque + 0.03 * load.force.x;
    EXPECT_NEAR(I_sub, 4.901e-3, 4.901e-5);
    EXPECT_NEAR(T_sub / I_sub, 0.07479, 0.0007479);

    World w(path, {});
    w.add_body(def);
    w.advance_to(0.01);  // one step of dt_max
    const BodyState s0 = w.states()[0];
    ASSERT_TRUE(s0.flags & flag_pivoting);
    EXPECT_NEAR(s0.pivot_rate / 0.01, 0.07479, 0.0007479);  // the initial angular acceleration about the contact
    EXPECT_EQ(s0.vx, 0.0);                                    // held by friction
    const Vec2 axis{s0.x + s0.pivot_ax, s0.y + s0.pivot_ay};
    EXPECT_NEAR(axis.x, 0.0, 1e-9);
    EXPECT_NEAR(axis.y, 0.03, 1e-9);
    w.advance_to(1.0);
    const BodyState& s = w.states()[0];
    const Vec2 centre{s.x, s.y};
    std::printf("after 1 s: turned %.4f rad (1/2 a t^2 = %.4f), centre (%.2f, %.2f) mm, %.3f cm from the first axis\n", s.theta,
                0.5 * 0.07479, 1e3 * s.x, 1e3 * s.y, 100 * norm(centre - axis));
    EXPECT_GT(s.theta, 0.0);  // counter-clockwise
    // Constant T_sub would give ½ (T_sub / I_sub) t² = 0.0374 rad; the drag on the turning
    // ends (about 1 cm/s at 0.07 rad/s) takes some of it.
    EXPECT_NEAR(s.theta, 0.0374, 0.1 * 0.0374);
    EXPECT_GT(s.x, 0.0);                                      // the centre swings east, downstream
    EXPECT_NEAR(norm(centre - axis), 0.03, 0.01 * 0.03);      // on an arc about the contact centroid
    EXPECT_NEAR(s.x, 0.03 * std::sin(s.theta), 0.05 * 0.03 * std::sin(s.theta));
    EXPECT_EQ(w.stats()[0].collisions, 0);
}

// Floating in water that turns as a solid body, u = −Ω y, v = Ω x (Ω = 0.5 rad/s, 10 cm
// deep), a body at rest at the centre of the rotation spins up to Ω by the drag on its
// faces (face velocities include ω ẑ × r). At a sample p on a face, the normal relative
// velocity is (Ω − ω) t_p, t_p its distance along the face from the face's middle, so the
// torque is K (Ω − ω)|Ω − ω| with K = ½ ρ d Σ Cd_p ℓ_p |t_p|³ over the 4 samples of each
// face (two of each face take Cd1, two Cd2): long faces ℓ = 6.25 cm, t = 3.125, 9.375 cm;
// ends ℓ = 2.5 cm, t = 1.25, 3.75 cm:
//   K = 12.5 × (2 × 1.2 × 0.0625 × (0.03125³ + 0.09375³) + 2 × 1.2 × 0.025 × (0.0125³ + 0.0375³))
//     = 1.6432e-3 N m s².
// I dδ/dt = −K δ|δ| for δ = Ω − ω gives δ = Ω / (1 + t/τ), τ = I / (K Ω) = 4.596 s: half
// the lag is left at τ, a quarter at 3τ. No net force (the field is odd about the centre,
// and Du/Dt = −Ω² x is zero there), so the body stays put.
TEST(DebrisBody, SpinsUpToSolidBodyRotationOfTheWater) {
    const auto dir = test::scratch_dir("body_vortex");
    const double Omega = 0.5, depth = 0.1;
    std::vector<double> times;
    for (int k = 0; k <= 15; ++k) times.push_back(k);
    const auto path = test::write_flow(
        dir + "/vortex.nc", fine, times, [](double, double) { return -0.1; },
        [&](double x, double y, double) {
            return test::FlowState{float(depth), float(-Omega * y), float(Omega * x)};
        });
    const BodyParams p = make_body_params(default_body_def(), rho);
    const double K = 0.5 * rho * p.draft *
                     (2 * 1.2 * 0.0625 * (std::pow(0.03125, 3) + std::pow(0.09375, 3)) +
                      2 * 1.2 * 0.025 * (std::pow(0.0125, 3) + std::pow(0.0375, 3)));
    EXPECT_NEAR(K, 1.6432e-3, 1e-7);
    const double tau = p.inertia / (K * Omega);
    EXPECT_NEAR(tau, 4.596, 0.005);
    World w(path, {});
    w.add_body(body_at(0.0, 0.0, 0.0, ContactModel::local));
    w.advance_to(tau);
    EXPECT_NEAR((Omega - w.states()[0].omega) / Omega, 0.5, 0.005);
    w.advance_to(3 * tau);
    EXPECT_NEAR((Omega - w.states()[0].omega) / Omega, 0.25, 0.0025);
    EXPECT_LT(std::hypot(w.states()[0].x, w.states()[0].y), 1e-9);
}

// The integrators' order on the relaxation above: with w = U/(1 + t/τ) the centre moves
// x(t) = x0 + U t − U τ ln(1 + t/τ). Halving the step halves the position error of the
// semi-implicit Euler step (first order) and quarters that of Heun (second order), and
// Heun at 20 ms is more accurate than Euler at 5 ms.
TEST(DebrisBody, HeunIsSecondOrderEulerFirstOnTheRelaxation) {
    const auto dir = test::scratch_dir("body_order");
    const double U = 0.1, depth = 0.1, t_end = 4.0;
    const Grid g{400, 40, -0.995, -0.195, 0.01, 0.01};
    const auto path = test::uniform_flow(dir + "/f.nc", g, t_end, depth, U, 0.0);
    const BodyParams p = make_body_params(default_body_def(), 1000.0);
    const double M = p.mass + 1000.0 * (p.def.cm - 1.0) * p.plan_area * p.draft;
    const double tau = M / (0.5 * 1000.0 * (p.def.cd1 + p.def.cd2) * p.def.width * p.draft * U);
    const double exact = -0.6 + U * t_end - U * tau * std::log(1.0 + t_end / tau);
    auto error = [&](Integrator integrator, double dt) {
        WorldDef def = default_world_def();
        def.step.dt_max = dt;
        def.step.vertex_step_fraction = 10.0;  // the step is dt_max throughout
        def.step.integrator = integrator;
        World w(path, {}, def);
        w.add_body(body_at(-0.6, 0.0, 0.0, ContactModel::local));
        w.advance_to(t_end);
        return std::fabs(w.states()[0].x - exact);
    };
    const double euler_ratio = error(Integrator::euler, 0.02) / error(Integrator::euler, 0.01);
    const double heun_ratio = error(Integrator::heun, 0.02) / error(Integrator::heun, 0.01);
    EXPECT_NEAR(euler_ratio, 2.0, 0.2);
    EXPECT_GT(heun_ratio, 3.5);  // 4.28 measured
    EXPECT_LT(heun_ratio, 4.6);
    EXPECT_LT(error(Integrator::heun, 0.02), 0.2 * error(Integrator::euler, 0.005));
}
