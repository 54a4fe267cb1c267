// The ground under a body is contact (friction, axis shift), never a wall: a body at
// rest in still water stays at rest on slopes, across ridges and at the real layout's
// starts; a ridge higher than the step tolerance holds a corner the body pivots about.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>

#include "cases/debris_flows.hpp"
#include "data/dem_import.hpp"
#include "debris/world.hpp"
#include "tests/test_support.hpp"

using namespace flotsam;
using namespace flotsam::debris;

namespace {

const Grid fine{160, 80, -0.795, -0.395, 0.01, 0.01};  // 1.6 m x 0.8 m around the origin, 1 cm cells
constexpr double draft = 0.025;                        // the paper's body [m]
constexpr double deg = M_PI / 180.0;

// Still water at `level` over `bed`, frames at 0 and t_end.
std::string still_water(const std::string& path, const Grid& g, const test::BedFn& bed, double level, double t_end = 10.0) {
    return test::write_flow(path, g, {0.0, t_end}, bed, [&](double x, double y, double) {
        return test::FlowState{float(std::max(level - bed(x, y), 0.0)), 0.0f, 0.0f};
    });
}

using test::body_at;

// Largest displacement [m] and turn [rad] of any body after `t` s, all released at 0;
// each body's is printed after `label`.
struct Drift {
    double move = 0.0, turn = 0.0;
};
Drift drift_after(World& w, double t, const std::string& label) {
    std::vector<BodyState> start = w.states();
    for (auto& s : w.states()) s.flags |= flag_released;  // as if the water had been deeper once
    w.advance_to(t);
    Drift d;
    for (std::size_t b = 0; b < w.size(); ++b) {
        const BodyState& s = w.states()[b];
        const double move = std::hypot(s.x - start[b].x, s.y - start[b].y), turn = std::fabs(s.theta - start[b].theta);
        std::printf("%s, body %zu (%s, heading %.0f deg): moved %.2f mm, turned %.3f deg\n", label.c_str(), b,
                    enum_name(w.params()[b].def.contact), start[b].theta / deg, 1e3 * move, turn / deg);
        d.move = std::max(d.move, move);
        d.turn = std::max(d.turn, turn);
    }
    return d;
}

}  // namespace

// A uniform slope along x, the body end-on, broadside and at 30°, with both contact
// models, at two still-water levels: one that just floats the centre (depth d + 1 mm
// there; the uphill end then rests on ground up to 5.25 mm (5 %) or 11.5 mm (10 %) above
// the floating bottom, beyond the 5 mm step tolerance) and one that grounds it (d − 5 mm).
// Before the ground was told apart from walls, such bodies slid downhill through
// "collisions".
TEST(DebrisGround, BodyAtRestOnSlopeStaysInStillWater) {
    const auto dir = test::scratch_dir("ground_slope");
    for (double slope : {0.05, 0.10}) {
        auto bed = [=](double x, double) { return -0.03 - slope * x; };
        for (double centre_depth : {draft + 0.001, draft - 0.005}) {
            World w(still_water(dir + "/slope.nc", fine, bed, bed(0.0, 0.0) + centre_depth), {});
            for (double heading : {0.0, 90.0, 30.0})
                for (ContactModel contact : {ContactModel::local, ContactModel::center})
                    w.add_body(body_at(0.0, 0.0, heading * deg, contact));
            char label[64];
            std::snprintf(label, sizeof label, "slope %.0f %%, centre depth %.1f mm", 100 * slope, 1e3 * centre_depth);
            const Drift d = drift_after(w, 10.0, label);
            EXPECT_LT(d.move, 1e-3) << label;
            EXPECT_LT(d.turn, 0.1 * deg) << label;
        }
    }
}

// A floating body (3 cm of water, bottom at −2.5 cm) with a corner or an end on a ridge
// whose top stands 3, 7 or 15 mm above that bottom: the ridge is under the footprint, so
// it is ground to rest on, not a wall.
TEST(DebrisGround, BodyAtRestAcrossRidgeStaysInStillWater) {
    const auto dir = test::scratch_dir("ground_ridge");
    for (double ridge : {0.003, 0.007, 0.015}) {
        auto bed = [=](double x, double y) { return (x > 0.09 && y > 0.01) ? -draft + ridge : -0.03; };
        World w(still_water(dir + "/ridge.nc", fine, bed, 0.0), {});
        w.add_body(body_at(0.0, 0.0, 0.0));                        // a corner on the ridge
        w.add_body(body_at(0.05, 0.0, 0.0));                       // one end across it
        w.add_body(body_at(0.02, 0.02, 20.0 * deg));               // at an angle
        w.add_body(body_at(0.0, 0.0, 0.0, ContactModel::center));  // centre contact alike
        char label[64];
        std::snprintf(label, sizeof label, "ridge %.0f mm above the bottom", 1e3 * ridge);
        const Drift d = drift_after(w, 10.0, label);
        EXPECT_LT(d.move, 1e-3) << label;
        EXPECT_LT(d.turn, 0.1 * deg) << label;
    }
}

// The ridge case of DebrisBody.PivotsAboutCornerHeldOnRidgeWithLocalContact (ridge top
// 3 mm above the floating bottom) with the ridge higher than any step tolerance: 7 and
// 15 mm above it. A current of 8 cm/s (+y) across the long side: its drag (the faces
// wetted from the bottom, which rests on the ridge, up to the level: 1.8 and 1.0 cm of the
// 3 cm of water; 0.017 and 0.0096 N) is below the friction on the ridge corner (x > 0.09,
// y > 0.01; 1.4 cm² of the 250 cm² bottom, μ (m − ρ L B h) g S/(L B) = 0.038 N at 7 mm,
// 0.082 N at 15 mm), so the corner is held (|F| ≤ |F_frc|, Eq. 6) and the axis shift turns
// the body about it clockwise (the free west end swings downstream, +y), the held point
// staying put and the centre on an arc; looked at over the first 4 s (about 30° and 19°,
// the less wetted body turning less). The ridge is under the footprint: ground
// to rest on and pivot about, never a wall (and below still water, so never a wall
// under the default rule either).
TEST(DebrisGround, PivotsClockwiseAboutCornerHeldOnRidgeAboveStepTolerance) {
    const auto dir = test::scratch_dir("ground_pivot");
    for (double ridge : {0.007, 0.015}) {
        auto bed = [=](double x, double y) { return (x > 0.09 && y > 0.01) ? -draft + ridge : -0.03; };
        const auto path = test::write_flow(dir + "/ridge.nc", fine, {0.0, 30.0}, bed, [&](double x, double y, double) {
            return test::FlowState{float(-bed(x, y)), 0.0f, 0.08f};
        });
        World w(path, {});
        w.add_body(body_at(0.0, 0.0, 0.0));
        w.states()[0].flags |= flag_released;
        w.advance_to(0.01);
        const BodyState s0 = w.states()[0];
        std::printf("pivot on a %.0f mm ridge, after 0.01 s: centre (%.1f, %.1f) mm, pivoting %d\n", 1e3 * ridge, 1e3 * s0.x,
                    1e3 * s0.y, (s0.flags & flag_pivoting) ? 1 : 0);
        ASSERT_TRUE(s0.flags & flag_pivoting) << "ridge " << ridge;
        const Vec2 held0{s0.x + s0.pivot_ax, s0.y + s0.pivot_ay};  // the contact centroid
        EXPECT_GT(held0.x, 0.09);
        EXPECT_GT(held0.y, 0.01);
        const Vec2 held_body = rotate(held0 - Vec2{s0.x, s0.y}, -s0.theta);  // a material point
        w.advance_to(2.0);
        {
            // The stored velocity is the centre's: while the corner is held, the force
            // balance's V is zero and the centre moves on its arc at ω_p ẑ × (x_g − x_sub).
            const BodyState& s = w.states()[0];
            ASSERT_TRUE(s.flags & flag_pivoting);
            const Vec2 arc = spin(s.pivot_rate, Vec2{-s.pivot_ax, -s.pivot_ay});
            EXPECT_EQ(std::hypot(s.vx, s.vy), 0.0);
            EXPECT_GT(norm(arc), 1e-3);
            EXPECT_NEAR(s.centre_vx, arc.x, 0.01 * norm(arc));
            EXPECT_NEAR(s.centre_vy, arc.y, 0.01 * norm(arc));
        }
        w.advance_to(4.0);
        const BodyState& s = w.states()[0];
        const Vec2 centre{s.x, s.y};
        const double held_move = norm(centre + rotate(held_body, s.theta) - held0);
        std::printf(
            "pivot on a %.0f mm ridge: turned %.1f deg, centre moved %.1f cm, held point %.1f cm, %ld axis-shift steps, %ld "
            "collision steps\n",
            1e3 * ridge, s.theta / deg, 100 * norm(centre), 100 * held_move, w.stats()[0].axis_shifts, w.stats()[0].collisions);
        EXPECT_LT(s.theta, ridge < 0.01 ? -0.45 : -0.28) << "ridge " << ridge;  // clockwise
        EXPECT_GT(norm(centre), 0.03);
        EXPECT_LT(held_move, 0.15 * norm(centre)) << "ridge " << ridge;
        EXPECT_LT(std::fabs(norm(centre - held0) - norm(held0)) / norm(held0), 0.05);  // an arc about the held point
        EXPECT_GT(w.stats()[0].axis_shifts, 100);
        EXPECT_EQ(w.stats()[0].collisions, 0);  // the ridge never acted as a wall
    }
}

// The real layout (../shared/data) imported at 1, 2 and 4 cm; still water over a window
// around the FD and LD starts at two levels: the initial one (0) and one that just floats
// the body's centre (depth d + 2 mm there). Each start stays put.
class RealLayoutStarts : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        const std::string dem = test::shared_data("city-topography-from-figure.nc");
        if (dem.empty()) return;
        for (double res : {0.01, 0.02, 0.04}) scenes_[res] = import_scene({dem, "", res});
    }
    static void TearDownTestSuite() { scenes_.clear(); }
    static std::map<double, Scene> scenes_;
};
std::map<double, Scene> RealLayoutStarts::scenes_;

TEST_F(RealLayoutStarts, StayAtRestInStillWaterAtOneTwoAndFourCentimetres) {
    if (scenes_.empty()) GTEST_SKIP() << "shared data not present";
    const auto dir = test::scratch_dir("ground_real");
    for (const auto& [res, scene] : scenes_) {
        for (const char* name : {"FD", "LD"}) {
            const ScenePoint* p = scene.find_point(name);
            ASSERT_NE(p, nullptr) << name;
            // A window of the scene's grid 1.2 m square around the start.
            const Grid& sg = scene.grid;
            const int n = int(std::lround(0.6 / sg.dx)), ic = sg.cell_i(p->x), jc = sg.cell_j(p->y);
            const Grid g{2 * n + 1, 2 * n + 1, sg.x(ic - n), sg.y(jc - n), sg.dx, sg.dy};
            auto bed = [&](double x, double y) { return scene.z[sg.index(sg.cell_i(x), sg.cell_j(y))]; };
            const double ground = bed(p->x, p->y);
            for (double level : {0.0, ground + draft + 0.002}) {
                char label[80];
                std::snprintf(label, sizeof label, "%s at %.0f cm, still water at %+.1f mm", name, 100 * res, 1e3 * level);
                World w(still_water(dir + "/still.nc", g, bed, level), buildings_on_grid(scene, g));
                BodyDef b = body_at(p->x, p->y, p->heading_deg * deg);
                w.add_body(b);
                b.contact = ContactModel::center;
                w.add_body(b);
                const Drift d = drift_after(w, 10.0, label);
                EXPECT_LT(d.move, 1e-3) << label;
                EXPECT_LT(d.turn, 0.1 * deg) << label;
            }
        }
    }
}
