// The body model against numbers that follow from its equations.
#include <gtest/gtest.h>

#include <cmath>

#include "cases/debris_flows.hpp"
#include "debris/world.hpp"
#include "tests/test_support.hpp"

using namespace flotsam;
using namespace flotsam::debris;

namespace {

const Grid fine{160, 80, -0.795, -0.395, 0.01, 0.01};  // 1.6 m x 0.8 m around the origin, 1 cm cells

BodyDef body_at(double x, double y, double heading, ContactModel contact) {
    BodyDef b = default_body_def();
    b.x = x;
    b.y = y;
    b.heading = heading;
    b.contact = contact;
    return b;
}

// Puts a body down already released (as if the water had once been deeper than the draft).
BodyState& released(World& w, std::size_t b) {
    w.states()[b].flags |= flag_released;
    return w.states()[b];
}

}  // namespace

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

// Grounded at depth 2 cm < draft: friction capacity μ (m − ρ L B h) g = 0.49 N. Drag on
// the end face ½ ρ (Cd1 + Cd2) B h U² = 1.2 U² N: 0.11 N at 0.3 m/s (held), 1.2 N at
// 1 m/s (slides).
TEST(DebrisBody, StaticFrictionHoldsUnderWeakFlowAndSlidesUnderStrong) {
    const auto dir = test::scratch_dir("body_static");
    for (ContactModel contact : {ContactModel::center, ContactModel::local}) {
        World weak(test::uniform_flow(dir + "/weak.nc", fine, 5, 0.02, 0.3, 0.0), {});
        weak.add_body(body_at(0.0, 0.0, 0.0, contact));
        released(weak, 0);
        weak.advance_to(5.0);
        EXPECT_EQ(weak.states()[0].x, 0.0) << enum_name(contact);
        EXPECT_TRUE(weak.states()[0].flags & flag_grounded);

        World strong(test::uniform_flow(dir + "/strong.nc", fine, 1, 0.02, 1.0, 0.0), {});
        strong.add_body(body_at(0.0, 0.0, 0.0, contact));
        released(strong, 0);
        strong.advance_to(1.0);
        EXPECT_GT(strong.states()[0].x, 0.1) << enum_name(contact);
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
    // Spin-down: I dω/dt = −μ m g ∫ r dA / (L B) ≈ −0.2 N m, so ω = 1 stops within ~0.03 s.
    EXPECT_LT(lc.states()[0].theta, 0.03);
    EXPECT_EQ(lc.states()[0].x, 0.0);
}

// A floating body (5 mm under it) with one corner on a ridge (3 mm under the draft there)
// in a weak current across its long side. With local contact the ridge friction holds
// the corner, and the axis shift turns the body about the contact: the held corner
// barely moves while the centre swings along an arc. Centre contact sees the centre
// afloat, so the body drifts off whole.
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
        w.advance_to(20.0);
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
    EXPECT_GT(centre, 0.1);

    // Local friction without the axis shift holds the body still: the turn comes from the shift.
    run(ContactModel::local, false, held, centre, turn, radius);
    EXPECT_LT(std::fabs(turn), 0.01);
    EXPECT_LT(centre, 1e-3);
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
