// The synthetic WG1 records: leading-wave peak, 1 mm ensemble spread, rest at t = 0,
// smoothness, reproducibility; and the loader's errors on bad user records.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <functional>

#include "common/error.hpp"
#include "common/sha256.hpp"
#include "data/boundary_generator.hpp"
#include "tests/test_support.hpp"

using namespace flotsam;
using test::error_of;
using test::write_file;

namespace {}  // namespace

TEST(BoundaryRecords, ShapeSpreadAndSmoothness) {
    const auto dir = test::scratch_dir("bnd");
    const auto paths = write_boundary_records(dir, generate_boundary_records({}));
    ASSERT_EQ(paths.size(), 10u);
    std::vector<TimeSeries> recs;
    for (const auto& p : paths) recs.push_back(load_boundary_record(p, 420.0));  // read back what users would load
    const std::size_t n = recs[0].time.size();
    ASSERT_EQ(n, 4201u);
    double max_mean = -1, t_max = 0;
    for (std::size_t k = 0; k < n; ++k) {
        const double t = recs[0].time[k];
        double mean = 0, var = 0;
        for (const auto& r : recs) mean += r.value[k];
        mean /= 10;
        for (const auto& r : recs) var += (r.value[k] - mean) * (r.value[k] - mean);
        const double sd = std::sqrt(var / 9);
        if (mean > max_mean) {
            max_mean = mean;
            t_max = t;
        }
        if (t >= 30.0) {
            EXPECT_GE(sd, 0.0007) << t;
            EXPECT_LE(sd, 0.0013) << t;
        }
        for (const auto& r : recs) {
            if (k == 0) {
                EXPECT_EQ(r.value[0], 0.0);
            }  // the flume starts at rest
            if (k > 0) {
                EXPECT_LT(std::abs(r.value[k] - r.value[k - 1]), 0.0003) << t;
            }  // no jumps: < 0.3 mm per 0.1 s
        }
    }
    EXPECT_NEAR(max_mean, 0.06, 0.005);
    EXPECT_GE(t_max, 290.0);
    EXPECT_LE(t_max, 320.0);
    // Early timing: about 1 cm after 30 s, still rising at 300 s, falling by 420 s.
    EXPECT_NEAR(leading_wave({}, 30.0), 0.01, 0.003);
    EXPECT_LT(leading_wave({}, 420.0), 0.5 * leading_wave({}, 300.0));
    // Departures are time-correlated: successive samples of one departure move much less
    // than the 1 mm spread (white noise would jump by ~1.4 mm).
    const double d0 = recs[3].value[2000] - leading_wave({}, 200.0), d1 = recs[3].value[2001] - leading_wave({}, 200.1);
    EXPECT_LT(std::abs(d1 - d0), 0.0002);
}

TEST(BoundaryRecords, ByteIdenticalForSameSeed) {
    const auto a = test::scratch_dir("bnd-a"), b = test::scratch_dir("bnd-b"), c = test::scratch_dir("bnd-c");
    const auto pa = write_boundary_records(a, generate_boundary_records({.seed = 5}));
    const auto pb = write_boundary_records(b, generate_boundary_records({.seed = 5}));
    const auto pc = write_boundary_records(c, generate_boundary_records({.seed = 6}));
    for (std::size_t r = 0; r < pa.size(); ++r) {
        EXPECT_EQ(sha256_file(pa[r]), sha256_file(pb[r]));
        EXPECT_NE(sha256_file(pa[r]), sha256_file(pc[r]));
    }
}

TEST(BoundaryRecords, BadUserRecordsNameFileAndLine) {
    const auto dir = test::scratch_dir("bnd-bad");
    std::string msg =
        error_of([&] { load_boundary_record(write_file(dir, "back.csv", "time,eta\n0,0\n0.1,0.001\n0.1,0.002\n"), 0.1); });
    EXPECT_NE(msg.find("back.csv: line 4"), std::string::npos) << msg;
    msg = error_of([&] { load_boundary_record(write_file(dir, "nan.csv", "time,eta\n0,0\n0.1,nan\n"), 0.1); });
    EXPECT_NE(msg.find("nan.csv: line 3"), std::string::npos) << msg;
    msg = error_of([&] { load_boundary_record(write_file(dir, "short.csv", "time,eta\n0,0\n5,0.001\n"), 420.0); });
    EXPECT_NE(msg.find("short.csv"), std::string::npos) << msg;
    EXPECT_NE(msg.find("420"), std::string::npos) << msg;
}

TEST(BoundaryCli, WritesRecordsAndSummary) {
    const auto dir = test::scratch_dir("bnd-cli");
    std::string out;
    EXPECT_EQ(test::run_cli("boundary generate --out-dir " + dir + " --count 4 --seed 2 --duration 60", &out), 0) << out;
    EXPECT_NE(out.find("boundary summary"), std::string::npos) << out;
    EXPECT_EQ(load_boundary_record(dir + "/wg1_r03.csv", 60.0).time.size(), 601u);
    EXPECT_NE(test::run_cli("boundary generate --out-dir " + dir + " --count 0", &out), 0);
    EXPECT_NE(out.find("--count"), std::string::npos) << out;
}
