// flotsam stats on synthetic trajectories whose statistics are known exactly: straight
// lines crossing a section at known y and speed, a known yaw history, bodies inside
// known regions at 300 s, distances in a known ratio to the control, and paths over
// known map cells.
#include "sweep/sweep_stats.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>

#include "common/netcdf.hpp"
#include "common/sha256.hpp"
#include "sweep/sweep_file.hpp"
#include "sweep/trajectory_kernels.hpp"
#include "tests/test_support.hpp"

using namespace flotsam;
using namespace flotsam::sweep;

namespace {

struct Sample {
    double x, y, yaw_deg, u, v;
};
using Motion = std::function<Sample(double t)>;

// A sweep of hand-made trajectories on times 0, dt, ..., t_end.
struct SyntheticSweep {
    SweepResult r;
    SyntheticSweep(double dt, double t_end, int param_sets = 1) {
        r.spec_file = "synthetic.toml";
        r.spec_sha256 = "0";
        r.design = "one_at_a_time";
        r.flows = {"f0.nc", "f1.nc"};
        r.bodies = {"FD", "LD"};
        r.variants = {"CC+SC", "LC+MC"};
        for (int p = 0; p < param_sets; ++p)
            r.params.push_back({p == 0 ? "control" : "set" + std::to_string(p), paper_control(), p == 0});
        r.output_interval = dt;
        for (int k = 0; dt * k <= t_end + 1e-9; ++k) r.time.push_back(dt * k);
    }
    int add(int body, int variant, int param_set, int flow, const Motion& m) {
        MemberRecord rec;
        rec.id = int(r.members.size());
        rec.body = body;
        rec.variant = variant;
        rec.param_set = param_set;
        rec.flow = flow;
        rec.body_name = r.bodies[std::size_t(body)];
        rec.variant_name = r.variants[std::size_t(variant)];
        rec.def.contact = variant ? debris::ContactModel::local : debris::ContactModel::center;
        rec.def.collision = variant ? debris::CollisionModel::multi : debris::CollisionModel::single;
        for (double t : r.time) {
            const Sample s = m(t);
            rec.track.x.push_back(s.x);
            rec.track.y.push_back(s.y);
            rec.track.yaw_deg.push_back(s.yaw_deg);
            rec.track.u.push_back(s.u);
            rec.track.v.push_back(s.v);
            rec.track.omega.push_back(0.0);
            rec.track.status.push_back(3);
        }
        rec.def.x = rec.track.x[0];
        rec.def.y = rec.track.y[0];
        rec.heading0_deg = rec.track.yaw_deg[0];
        r.members.push_back(rec);
        r.member_count = int(r.members.size());
        return rec.id;
    }
};

// Constant velocity from (x0, y0) with a fixed heading.
Motion line(double x0, double y0, double u, double v, double yaw = 0.0) {
    return [=](double t) { return Sample{x0 + u * t, y0 + v * t, yaw, u, v}; };
}

Scene scene_with(const Grid& g) {
    Scene s;
    s.grid = g;
    s.z.assign(g.size(), 0.0);
    return s;
}

}  // namespace

// Five bodies leave x = 0 at 0.1 m/s east with northward speeds 0.01 k: they cross
// x = 1.05 at t = 10.5 s, y = 0.105 k, speed √(0.1² + (0.01 k)²).
TEST(SweepStats, SectionPassagePositionSpeedAndDensity) {
    SyntheticSweep sw(1.0, 20.0);
    for (int k = 1; k <= 5; ++k) sw.add(0, 1, 0, 0, line(0.0, 0.0, 0.1, 0.01 * k));
    sw.add(0, 1, 0, 1, line(0.0, 3.0, 0.1, 0.0));   // crosses north of the section's end: not counted
    sw.add(0, 1, 0, 1, line(0.0, 0.0, 0.01, 0.0));  // never reaches it
    Scene scene = scene_with(Grid{30, 20, 0.05, -0.45, 0.1, 0.1});
    scene.sections = {{"s1", 1.05, -1.0, 1.0}};
    const SweepStats s = compute_stats(sw.r, scene);
    ASSERT_EQ(s.groups.size(), 1u);
    EXPECT_EQ(s.groups[0].body, "FD");
    EXPECT_EQ(s.groups[0].variant, "LC+MC");
    const SectionSummary& q = s.section[0][0];
    EXPECT_EQ(q.count, 5);
    EXPECT_NEAR(q.y_mean, 0.315, 1e-12);
    EXPECT_NEAR(q.y_median, 0.315, 1e-12);
    EXPECT_NEAR(q.y_std, 0.105 * std::sqrt(2.5), 1e-12);  // sample std of 1..5 is √2.5
    std::vector<double> speeds;
    for (int k = 1; k <= 5; ++k) speeds.push_back(std::hypot(0.1, 0.01 * k));
    EXPECT_NEAR(q.speed_mean, mean_of(speeds), 1e-12);
    EXPECT_NEAR(q.speed_median, speeds[2], 1e-12);
    EXPECT_NEAR(s.passage_time[0][0], 10.5, 1e-12);
    EXPECT_NEAR(s.passage_y[2][0], 0.315, 1e-12);
    EXPECT_TRUE(std::isnan(s.passage_y[5][0]));
    EXPECT_TRUE(std::isnan(s.passage_y[6][0]));
    // Silverman's bandwidth by hand: σ, IQR from type-7 quartiles (2nd and 4th values).
    const double sigma = std_of(speeds), iqr = speeds[3] - speeds[1];
    EXPECT_NEAR(q.bandwidth, 0.9 * std::min(sigma, iqr / 1.34) * std::pow(5.0, -0.2), 1e-15);
    // The density integrates to one (trapezoid over the axis, which spans 3 h past the largest).
    double area = 0.0;
    for (std::size_t k = 1; k < s.speed.size(); ++k) area += 0.5 * (q.kde[k] + q.kde[k - 1]) * (s.speed[k] - s.speed[k - 1]);
    EXPECT_NEAR(area, 1.0, 0.01);
}

TEST(SweepStats, KernelDensityOfOneValueIsTheGaussian) {
    const double h = silverman_bandwidth({0.2}, 1e-3);
    EXPECT_DOUBLE_EQ(h, 0.02);  // no spread: 10 % of the value
    EXPECT_NEAR(gaussian_kde({0.2}, h, 0.2), 1.0 / (0.02 * std::sqrt(2 * M_PI)), 1e-12);
    EXPECT_NEAR(gaussian_kde({0.2}, h, 0.24), std::exp(-2.0) / (0.02 * std::sqrt(2 * M_PI)), 1e-12);
    // Values 1..5: σ = √2.5, IQR = 2 → h = 0.9 · (2 / 1.34) · 5^(−1/5).
    EXPECT_NEAR(silverman_bandwidth({5, 3, 1, 4, 2}, 1e-3), 0.9 * (2 / 1.34) * std::pow(5.0, -0.2), 1e-14);
}

// A body that starts moving at t = 1 s (0.01 m/s east), turns to +30° by t = 15 s, back
// to −10° by 25 s and to −60° only at 32 s, after the 30 s window: largest rotation +30°.
TEST(SweepStats, LargestYawInTheFirstThirtySeconds) {
    SyntheticSweep sw(1.0, 60.0);
    auto yaw = [](double t) {
        if (t <= 5) return 0.0;
        if (t <= 15) return 3.0 * (t - 5);
        if (t <= 25) return 30.0 - 4.0 * (t - 15);
        return t <= 31 ? -10.0 : -60.0;
    };
    sw.add(0, 0, 0, 0, [&](double t) { return Sample{0.01 * t, 0.0, yaw(t), 0.01, 0.0}; });
    sw.add(0, 0, 0, 0, line(0.0, 1.0, 0.05, 0.0, 20.0));   // axis 20° from the motion
    sw.add(0, 0, 0, 0, line(0.0, 2.0, 0.05, 0.05, 0.0));   // moving at 45°, axis along x: −45°
    sw.add(0, 0, 0, 0, line(0.0, 3.0, 0.05, 0.0, 170.0));  // 170° is the same line as −10°
    sw.add(0, 0, 0, 0, line(0.0, 4.0, 0.0, 0.0, 0.0));     // never moves
    const SweepStats s = compute_stats(sw.r, scene_with(Grid{10, 10, 0.5, 0.5, 1, 1}));
    EXPECT_DOUBLE_EQ(s.motion_start[0], 1.0);  // 0.01 m ≥ 5 mm first at t = 1 s
    EXPECT_DOUBLE_EQ(s.max_rotation[0], 30.0);
    EXPECT_DOUBLE_EQ(s.max_yaw_to_motion[0], 30.0);
    EXPECT_NEAR(s.max_yaw_to_motion[1], 20.0, 1e-12);
    EXPECT_NEAR(s.max_yaw_to_motion[2], -45.0, 1e-12);
    EXPECT_NEAR(s.max_yaw_to_motion[3], -10.0, 1e-12);
    EXPECT_DOUBLE_EQ(s.max_rotation[1], 0.0);
    EXPECT_NEAR(s.motion_direction[2], 45.0, 1e-12);
    EXPECT_NEAR(s.motion_direction[0], 0.0, 1e-12);
    EXPECT_TRUE(std::isnan(s.motion_start[4]));
    EXPECT_TRUE(std::isnan(s.max_rotation[4]));
    // 10° bins from −180: +30 falls in [30, 40), 0 in [0, 10), −45 in [−50, −40).
    ASSERT_EQ(s.yaw_edges.size(), 37u);
    const auto& h = s.rotation_hist[0];
    EXPECT_EQ(h[21], 1);
    EXPECT_EQ(h[18], 3);
    int total = 0;
    for (int c : h) total += c;
    EXPECT_EQ(total, 4);                     // the body that never moved has no rotation
    EXPECT_EQ(s.yaw_motion_hist[0][13], 1);  // −45
    EXPECT_EQ(s.yaw_motion_hist[0][17], 1);  // −10
}

// The paper's Fig. 16 counts from the run's start (here t0 = 100 s on the flow's clock),
// not from motion start. A turns +40° in place over the first 10 s, then drifts
// south-east: its rotation after motion start is 0°, from the start +40°, direction
// −45°. B turns to −20° by 20 s heading north-east and to −90° only after the window.
// C turns +10° and heads east. D turns 0° and never moves (no direction). Rotations
// (40, −20, 10) against directions (−45, 45, 0) correlate with r = −1 exactly.
TEST(SweepStats, LargestRotationFromTheStartAndItsCorrelationWithTheDirection) {
    SyntheticSweep sw(1.0, 60.0);
    for (double& t : sw.r.time) t += 100.0;
    auto a = [](double t) {
        t -= 100.0;
        const double k = std::max(0.0, t - 10.0);
        return Sample{0.01 * k, -0.01 * k, std::min(t, 10.0) * 4.0, t > 10 ? 0.01 : 0.0, t > 10 ? -0.01 : 0.0};
    };
    auto b = [](double t) {
        t -= 100.0;
        return Sample{0.01 * t, 1.0 + 0.01 * t, t <= 30.0 ? -std::min(t, 20.0) : -90.0, 0.01, 0.01};
    };
    auto c = [](double t) {
        t -= 100.0;
        return Sample{0.01 * t, 2.0, std::min(t, 5.0) * 2.0, 0.01, 0.0};
    };
    sw.add(0, 1, 0, 0, a);
    sw.add(0, 1, 0, 0, b);
    sw.add(0, 1, 0, 0, c);
    sw.add(0, 1, 0, 0, line(0.0, 3.0, 0.0, 0.0, 0.0));
    const SweepStats s = compute_stats(sw.r, scene_with(Grid{10, 10, 0.5, 0.5, 1, 1}));
    EXPECT_DOUBLE_EQ(s.motion_start[0], 111.0);  // 1.4 cm from the start one second after it leaves
    EXPECT_DOUBLE_EQ(s.max_rotation[0], 0.0);    // after motion start: it turned before
    EXPECT_DOUBLE_EQ(s.max_rotation_from_start[0], 40.0);
    EXPECT_DOUBLE_EQ(s.max_rotation_from_start[1], -20.0);
    EXPECT_DOUBLE_EQ(s.max_rotation_from_start[2], 10.0);
    EXPECT_DOUBLE_EQ(s.max_rotation_from_start[3], 0.0);
    EXPECT_NEAR(s.movement_direction[0], -45.0, 1e-12);  // south-east: negative
    EXPECT_NEAR(s.movement_direction[1], 45.0, 1e-12);   // north-east: positive
    EXPECT_NEAR(s.movement_direction[2], 0.0, 1e-12);
    EXPECT_TRUE(std::isnan(s.movement_direction[3]));
    const SweepStats::RotationSummary& q = s.rotation_from_start[0];
    EXPECT_EQ(q.count, 4);
    EXPECT_DOUBLE_EQ(q.median, 5.0);
    EXPECT_DOUBLE_EQ(q.mean, 7.5);
    EXPECT_DOUBLE_EQ(q.min, -20.0);
    EXPECT_DOUBLE_EQ(q.max, 40.0);
    EXPECT_NEAR(q.direction_correlation, -1.0, 1e-12);
    const auto& h = s.rotation_from_start_hist[0];
    EXPECT_EQ(h[22], 1);  // [40, 50)
    EXPECT_EQ(h[16], 1);  // [−20, −10)
    EXPECT_EQ(h[19], 1);  // [10, 20)
    EXPECT_EQ(h[18], 1);  // [0, 10)
}

TEST(SweepStats, PearsonCorrelationByHand) {
    // a = (1, 2, 3, 4), b = (2, 1, 4, 3): deviations (−1.5, −0.5, 0.5, 1.5) and (−0.5, −1.5,
    // 1.5, 0.5); Σ ab = 0.75 + 0.75 + 0.75 + 0.75 = 3, Σ a² = Σ b² = 5: r = 0.6. The NaN pair
    // is left out; no spread gives NaN.
    EXPECT_NEAR(pearson_correlation({1, 2, 3, 4, 7}, {2, 1, 4, 3, std::nan("")}), 0.6, 1e-15);
    EXPECT_TRUE(std::isnan(pearson_correlation({1, 1, 1}, {1, 2, 3})));
    EXPECT_TRUE(std::isnan(pearson_correlation({1}, {2})));
}

// Region counts use the position at 300 s, not the last one.
TEST(SweepStats, ArrivalCountsPerRegionAtThreeHundredSeconds) {
    SyntheticSweep sw(10.0, 400.0);
    Scene scene = scene_with(Grid{40, 10, 0.05, 0.05, 0.1, 0.1});
    scene.regions = {{"a", {{{0, 0}}, {{1, 0}}, {{1, 1}}, {{0, 1}}}}, {"b", {{{2, 0}}, {{3, 0}}, {{3, 1}}, {{2, 1}}}}};
    sw.add(0, 0, 0, 0, line(0.5, 0.5, 0.0, 0.0));      // stays in a
    sw.add(0, 0, 0, 0, line(-0.5, 0.5, 0.01, 0.0));    // x = 2.5 at 300 s (b), 3.5 at 400 s
    sw.add(0, 0, 0, 1, line(-0.5, 0.5, 0.0035, 0.0));  // x = 0.55 at 300 s (a)
    sw.add(1, 0, 0, 0, line(2.5, 2.0, 0.0, 0.0));      // LD, in neither
    const SweepStats s = compute_stats(sw.r, scene);
    ASSERT_EQ(s.groups.size(), 2u);
    EXPECT_EQ(s.region_count[0][0], 2);
    EXPECT_EQ(s.region_count[0][1], 1);
    EXPECT_EQ(s.region_count[1][0] + s.region_count[1][1], 0);
    EXPECT_EQ(s.region_at_arrival[1], 1);
    EXPECT_EQ(s.region_at_arrival[3], -1);
}

// Control bodies move 0.1 m/s on both flows; set 1 at 0.12 (R = 0.2); set 2 at 0.05 and
// 0.15 (mean as the control: R = 0, spread 0.05√2 t).
TEST(SweepStats, DistanceFromStartAndRelativeErrorToTheControl) {
    SyntheticSweep sw(1.0, 50.0, 3);
    for (int f = 0; f < 2; ++f) {
        sw.add(0, 1, 0, f, line(0.0, 0.0, 0.1, 0.0));
        sw.add(0, 1, 1, f, line(0.0, 0.0, 0.0, 0.12));
    }
    sw.add(0, 1, 2, 0, line(0.0, 0.0, 0.05, 0.0));
    sw.add(0, 1, 2, 1, line(0.0, 0.0, -0.15, 0.0));
    const SweepStats s = compute_stats(sw.r, scene_with(Grid{10, 10, 0.5, 0.5, 1, 1}));
    ASSERT_EQ(s.control, 0);
    EXPECT_TRUE(std::isnan(s.relative_error[0][1][0]));  // control distance 0 at t = 0: undefined
    for (std::size_t k = 1; k < s.time.size(); ++k) {
        const double t = s.time[k];
        EXPECT_NEAR(s.distance_mean[0][0][k], 0.1 * t, 1e-12);
        EXPECT_NEAR(s.distance_mean[0][1][k], 0.12 * t, 1e-12);
        EXPECT_NEAR(s.relative_error[0][1][k], 0.2, 1e-12);
        EXPECT_NEAR(s.relative_error[0][2][k], 0.0, 1e-12);
        EXPECT_NEAR(s.relative_error[0][0][k], 0.0, 1e-12);
        EXPECT_NEAR(s.distance_std[0][2][k], 0.05 * std::sqrt(2.0) * t, 1e-12);
    }
    EXPECT_EQ(s.param_members[0][2], 2);
}

// Two bodies along the row y = 1.5 of a 1 m grid: one to x = 9.8 at 1 m/s, one to 4.8 at
// 2 m/s (then still). Cells 0-4 of that row: probability 1, largest speed 2; cells
// 5-9: 0.5 and 1; every other cell: 0 and no speed.
TEST(SweepStats, PassProbabilityAndLargestSpeedPerCell) {
    SyntheticSweep sw(0.1, 10.0);
    sw.add(0, 0, 0, 0, [](double t) { return t <= 9.6 ? Sample{0.2 + t, 1.5, 0, 1, 0} : Sample{9.8, 1.5, 0, 0, 0}; });
    sw.add(0, 0, 0, 1, [](double t) { return t <= 2.3 ? Sample{0.2 + 2 * t, 1.5, 0, 2, 0} : Sample{4.8, 1.5, 0, 0, 0}; });
    const SweepStats s = compute_stats(sw.r, scene_with(Grid{10, 5, 0.5, 0.5, 1, 1}));
    for (int j = 0; j < 5; ++j)
        for (int i = 0; i < 10; ++i) {
            const std::size_t c = s.map.index(i, j);
            if (j != 1) {
                EXPECT_EQ(s.pass_probability[0][c], 0.0f);
                EXPECT_TRUE(std::isnan(s.max_speed[0][c]));
                continue;
            }
            EXPECT_EQ(s.pass_probability[0][c], i < 5 ? 1.0f : 0.5f) << i;
            EXPECT_NEAR(s.max_speed[0][c], i < 5 ? 2.0 : 1.0, 1e-6) << i;
            EXPECT_EQ(s.pass_probability_all[c], s.pass_probability[0][c]);
        }
    // Coarsened by 2: 5 × 3 cells of 2 m; the row j = 0 holds y = 1.5.
    StatsDef def = default_stats_def();
    def.map_coarsen = 2;
    const SweepStats c = compute_stats(sw.r, scene_with(Grid{10, 5, 0.5, 0.5, 1, 1}), def);
    EXPECT_EQ(c.map.nx, 5);
    EXPECT_EQ(c.map.ny, 3);
    EXPECT_DOUBLE_EQ(c.map.x0, 1.0);
    EXPECT_EQ(c.pass_probability[0][c.map.index(2, 0)], 1.0f);  // x 4..6: both
    EXPECT_EQ(c.pass_probability[0][c.map.index(3, 0)], 0.5f);
}

// The sweep file reads back to the same bytes, and the CLI writes the NetCDF and CSVs.
TEST(SweepStats, FilesRoundTripAndTheCommandWritesTables) {
    const auto dir = test::scratch_dir("sweep_stats_cli");
    SyntheticSweep sw(1.0, 20.0);
    for (int k = 1; k <= 3; ++k) sw.add(0, 1, 0, k % 2, line(0.0, 0.0, 0.1, 0.01 * k, 5.0 * k));
    write_sweep_file(dir + "/a.nc", sw.r);
    write_sweep_file(dir + "/b.nc", read_sweep_file(dir + "/a.nc"));
    EXPECT_EQ(sha256_file(dir + "/a.nc"), sha256_file(dir + "/b.nc"));

    Scene scene = scene_with(Grid{30, 20, 0.05, -0.45, 0.1, 0.1});
    scene.sections = {{"s1", 1.05, -1.0, 1.0}};
    scene.regions = {{"r", {{{0, -1}}, {{3, -1}}, {{3, 1}}, {{0, 1}}}}};
    write_scene(dir + "/scene.nc", scene, "test");
    std::string out;
    ASSERT_EQ(
        test::run_cli("stats --sweep " + dir + "/a.nc --scene " + dir + "/scene.nc --out " + dir + "/st.nc --csv " + dir + "/csv",
                      &out),
        0)
        << out;
    const nc::File f = nc::File::open_read(dir + "/st.nc");
    EXPECT_EQ(f.get_int(f.var("passage_count"))[0], 3);
    EXPECT_NEAR(f.get_double(f.var("passage_y_mean"))[0], 0.21, 1e-12);
    EXPECT_EQ(f.get_int(f.var("region_count"))[0], 3);
    EXPECT_EQ(f.shape(f.var("pass_probability")), (std::vector<std::size_t>{1, 20, 30}));
    EXPECT_EQ(f.get_int(f.var("max_rotation_from_start_count"))[0], 3);
    EXPECT_NEAR(f.get_double(f.var("max_rotation_from_start_max"))[0], 0.0, 1e-12);  // constant headings
    for (const char* name : {"sections.csv", "speed_kde.csv", "yaw_histogram.csv", "rotation_from_start.csv", "regions.csv",
                             "distance.csv", "members.csv"})
        EXPECT_TRUE(std::filesystem::exists(dir + "/csv/" + name)) << name;
    // Again into the same folders (make's rerun of an out-of-date statistics file); a
    // --csv that is a file is refused.
    ASSERT_EQ(
        test::run_cli("stats --sweep " + dir + "/a.nc --scene " + dir + "/scene.nc --out " + dir + "/st.nc --csv " + dir + "/csv",
                      &out),
        0)
        << out;
    EXPECT_NE(test::run_cli("stats --sweep " + dir + "/a.nc --scene " + dir + "/scene.nc --out " + dir + "/st2.nc --csv " + dir +
                                "/b.nc",
                            &out),
              0);
    EXPECT_NE(out.find("--csv: " + dir + "/b.nc: is a file"), std::string::npos) << out;

    // A shard is refused until merged.
    SweepResult part = sw.r;
    part.shard = {0, 2};
    write_sweep_file(dir + "/part.nc", part);
    EXPECT_NE(test::run_cli("stats --sweep " + dir + "/part.nc --scene " + dir + "/scene.nc --out " + dir + "/x.nc", &out), 0);
    EXPECT_NE(out.find("merge the parts first"), std::string::npos) << out;
}

// pipelines.resolution_stats's intervals over the records, on hand-made stats
// folders of ten records, two members each (FD CC+SC). The reference has one member of
// every record in Channel A and all crossing x = 1.8 m at y = -2.20 m, 5 cm/s. Resampling
// the records, paired:
// - a copy differs by 0 in every resample: [+0, +0];
// - a sweep with no member in Channel A, crossing 0.10 m further south at 7 cm/s, differs
//   by exactly -10 members, -0.10 m and +2.0 cm/s in every resample;
// - a sweep that lost one member of record 0 differs by minus the times record 0 is drawn,
//   binomial(10, 0.1): P(0) = 0.349, P(>= 3) = 0.070, P(>= 4) = 0.013, so its 5 % quantile
//   is -3 and its 95 % quantile 0. One record's difference is not called a difference.
// Then --floor: a difference is bold only beyond both its interval and the chaos floor.
TEST(ResolutionStats, IntervalsOverResampledRecords) {
    const auto dir = test::scratch_dir("resolution_stats");
    const auto folder = [&](const std::string& name, int in_channel, double y, double speed, bool lose_record_0) {
        std::string m = "member,body,variant,param_label,flow,region_at_arrival,fd_x1.8_time_s,fd_x1.8_y_m,fd_x1.8_speed_m_s\n";
        int count = 0;
        for (int f = 0; f < 10; ++f)
            for (int k = 0; k < 2; ++k) {
                const bool inside = k == 0 && in_channel && !(lose_record_0 && f == 0);
                count += inside;
                m += std::to_string(2 * f + k) + ",FD,CC+SC," + (k ? "set1" : "control") + "," + std::to_string(f) + "," +
                     (inside ? "channel_a" : "") + ",40," + std::to_string(y) + "," + std::to_string(speed) + "\n";
            }
        const std::string d = dir + "/" + name;
        std::filesystem::create_directories(d);
        test::write_file(d, "members.csv", m);
        test::write_file(
            d, "regions.csv",
            "body,variant,param_label,region,count,members\nFD,CC+SC,all,channel_a," + std::to_string(count) + ",20\n");
        test::write_file(d, "sections.csv",
                         "body,variant,param_label,section,count,y_median_m,speed_median_m_s\nFD,CC+SC,all,fd_x1.8,20," +
                             std::to_string(y) + "," + std::to_string(speed) + "\n");
        return name + "=" + d;
    };
    const std::string runs = folder("ref", 1, -2.2, 0.05, false) + " " + folder("same", 1, -2.2, 0.05, false) + " " +
                             folder("shifted", 0, -2.3, 0.07, false) + " " + folder("one", 1, -2.2, 0.05, true);
    const auto table_of = [&](const std::string& extra) {
        const std::string cmd = "cd " FLOTSAM_SOURCE_DIR " && /usr/bin/python3 -m pipelines.resolution_stats --regions channel_a " +
                                runs + extra + " > " + dir + "/table.md 2>&1";
        const int rc = std::system(cmd.c_str());
        std::ifstream f(dir + "/table.md");
        const std::string table((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
        EXPECT_EQ(rc, 0) << table;
        return table;
    };
    const std::string table = table_of("");
    EXPECT_NE(table.find("| FD CC+SC | channel_a | 10/20 | 10/20 [+0, +0] | 0/20 [-10, -10] | 9/20 [-3, +0] |"), std::string::npos)
        << table;
    EXPECT_NE(table.find("| FD CC+SC | fd_x1.8 | 20, -2.20 m, 5.0 cm/s | 20, -2.20 m [+0.00, +0.00], 5.0 cm/s [+0.0, +0.0] | "
                         "20, -2.30 m [-0.10, -0.10], 7.0 cm/s [+2.0, +2.0] | 20, -2.20 m [+0.00, +0.00], 5.0 cm/s [+0.0, +0.0] |"),
              std::string::npos)
        << table;
    // The chaos floor: with "one" as a perturbed copy of the reference, the count's floor
    // is |9 - 10| = 1 and the sections' 0, so the shifted sweep (-10 members, -0.10 m,
    // +2.0 cm/s, every interval excluding 0) is beyond it everywhere: bold.
    const std::string floored = table_of(" --floor perturbed=" + dir + "/one");
    EXPECT_NE(floored.find("| FD CC+SC | channel_a | 10/20 | 10/20 [+0, +0] | **0/20 [-10, -10]** | 9/20 [-3, +0] | ±1 |"),
              std::string::npos)
        << floored;
    EXPECT_NE(floored.find("| 20, **-2.30 m [-0.10, -0.10]**, **7.0 cm/s [+2.0, +2.0]** | 20, -2.20 m [+0.00, +0.00], 5.0 cm/s "
                           "[+0.0, +0.0] | ±0.00 m, ±0.0 cm/s |"),
              std::string::npos)
        << floored;
    // With the shifted sweep itself as the floor, its own difference (10) is not beyond
    // the floor (10): beyond the records, but not called a difference.
    const std::string within = table_of(" --floor perturbed=" + dir + "/shifted");
    EXPECT_NE(within.find("| FD CC+SC | channel_a | 10/20 | 10/20 [+0, +0] | 0/20 [-10, -10] | 9/20 [-3, +0] | ±10 |"),
              std::string::npos)
        << within;
}
