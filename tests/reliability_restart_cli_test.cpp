// Restart through the command line, as a user runs it: stop, continue, the same bytes;
// a refused restart keeps the partial work; a signal is a stop (docs/reliability.md).
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "cases/debris_flows.hpp"
#include "common/netcdf.hpp"
#include "common/output_lock.hpp"
#include "common/sha256.hpp"
#include "formats/scene.hpp"
#include "fuzz/bad_files.hpp"
#include "tests/reliability_cases.hpp"

using namespace flotsam;
using namespace flotsam::test;
namespace fs = std::filesystem;

// Stop, restart (on another thread count), and the same bytes as a run never stopped.
// Stopped at the first frame after the start too (asked at 0.5 s, every 0.5 s): the
// stop waits for frame 2, since a file continued from frame 1 came out 1 kB smaller.
TEST(ReliabilityCli, RestartGivesTheBytesOfAnUninterruptedRun) {
    const SmallCase c = small_case("cli_restart");
    std::string out;
    const std::string ref = c.dir + "/ref.nc";
    ASSERT_EQ(test::run_cli(hydro_args(c, ref) + " --threads 1", &out), 0) << out;
    for (const std::string stop : {"--checkpoint-interval 1 --stop-after 2.5", "--checkpoint-interval 0.5 --stop-after 0.5"}) {
        SCOPED_TRACE(stop);
        const std::string f = c.dir + "/f" + std::to_string(stop.size()) + ".nc";
        ASSERT_EQ(test::run_cli(hydro_args(c, f) + " --threads 1 " + stop, &out), 0) << out;
        EXPECT_FALSE(fs::exists(f));
        ASSERT_TRUE(fs::exists(f + ".part"));
        ASSERT_TRUE(fs::exists(f + ".checkpoint.nc"));
        ASSERT_EQ(test::run_cli(hydro_args(c, f) + " --threads 2 --checkpoint-interval 1 --restart", &out), 0) << out;
        ASSERT_TRUE(fs::exists(f));
        EXPECT_FALSE(fs::exists(f + ".part"));
        EXPECT_FALSE(fs::exists(f + ".checkpoint.nc"));
        EXPECT_EQ(sha256_file(f), sha256_file(ref));
    }
}

// Three grids from the command line (lists), stopped and restarted: the checkpoint
// carries every slab, and the file is the uninterrupted run's bytes.
TEST(ReliabilityCli, ThreeSlabsRestartGivesTheBytesOfAnUninterruptedRun) {
    const SmallCase c = small_case("cli_restart_slabs");
    std::string out;
    const std::string ref = c.dir + "/ref.nc", f = c.dir + "/f.nc", slabs = " --nest-ratio 4,2,1 --nest-x -4.0,-1.2";
    ASSERT_EQ(test::run_cli(hydro_args(c, ref) + slabs + " --threads 1", &out), 0) << out;
    ASSERT_EQ(test::run_cli(hydro_args(c, f) + slabs + " --threads 1 --checkpoint-interval 1 --stop-after 2.5", &out), 0) << out;
    ASSERT_EQ(test::run_cli(hydro_args(c, f) + slabs + " --threads 2 --checkpoint-interval 1 --restart", &out), 0) << out;
    EXPECT_EQ(sha256_file(f), sha256_file(ref));
    const std::string source = nc::File::open_read(ref).att_text(NC_GLOBAL, "source").value_or("");
    EXPECT_NE(source.find("0.640000 x 0.160000 m west of x = -4.045000 m, 0.320000 x 0.160000 m from x = -4.045000 to -1.485000 m"), std::string::npos)
        << source;
    // With a time interface (two slabs of the finest cells, each with its own step), whose
    // refluxing keeps the CFL rate it knows: a restart, which computes the rate afresh,
    // takes the same steps.
    const std::string split = " --nest-ratio 4,1,1 --nest-x -1.2,0.4", g = c.dir + "/g.nc", ref2 = c.dir + "/ref2.nc";
    ASSERT_EQ(test::run_cli(hydro_args(c, ref2) + split + " --threads 1", &out), 0) << out;
    ASSERT_EQ(test::run_cli(hydro_args(c, g) + split + " --threads 1 --checkpoint-interval 1 --stop-after 2.5", &out), 0) << out;
    ASSERT_EQ(test::run_cli(hydro_args(c, g) + split + " --threads 2 --checkpoint-interval 1 --restart", &out), 0) << out;
    EXPECT_EQ(sha256_file(g), sha256_file(ref2));
    const std::string split_source = nc::File::open_read(ref2).att_text(NC_GLOBAL, "source").value_or("");
    EXPECT_NE(split_source.find("split at x = 0.275"), std::string::npos) << split_source;
}

// A restart with other settings is refused, names what differs, and leaves the
// interrupted run's files as they were; a fresh run over them is refused too.
TEST(ReliabilityCli, RefusedRestartNamesTheSettingsAndKeepsThePartialWork) {
    const SmallCase c = small_case("cli_restart_refused");
    std::string out;
    const std::string f = c.dir + "/f.nc";
    ASSERT_EQ(test::run_cli(hydro_args(c, f) + " --checkpoint-interval 1 --stop-after 2.5", &out), 0) << out;
    const std::string part_sha = sha256_file(f + ".part"), ckpt_sha = sha256_file(f + ".checkpoint.nc");
    EXPECT_NE(test::run_cli(hydro_args(c, f) + " --restart --cfl 0.4", &out), 0);
    EXPECT_NE(out.find("cfl: 0.8 in the checkpoint, 0.4 now"), std::string::npos) << out;
    EXPECT_NE(test::run_cli(hydro_args(c, f), &out), 0);  // a fresh run would overwrite the checkpoint
    EXPECT_NE(out.find("continue it with --restart"), std::string::npos) << out;
    // An edited boundary file is another run too.
    std::ofstream(c.series, std::ios::app) << "30.05,0\n";
    EXPECT_NE(test::run_cli(hydro_args(c, f) + " --restart", &out), 0);
    EXPECT_NE(out.find("west-series sha256"), std::string::npos) << out;
    ASSERT_TRUE(fs::exists(f + ".part"));
    EXPECT_EQ(sha256_file(f + ".part"), part_sha);
    EXPECT_EQ(sha256_file(f + ".checkpoint.nc"), ckpt_sha);
    EXPECT_FALSE(fs::exists(f));
}

// SIGTERM (what a batch system sends before it kills a job) or SIGINT (Ctrl-C): the run
// stops at its next frame with a checkpoint there (none was asked for), exits 1 saying how
// to continue, and the same command with --restart ends with the uninterrupted run's bytes.
TEST(ReliabilityCli, ASignalStopsTheRunAtAFrameAndRestartGivesTheSameBytes) {
    const SmallCase c = small_case("cli_signal");
    std::string out;
    // 10 000 steps of 1 ms (a few seconds): the run is surely under way when signalled,
    // and its next frame is 100 steps away at most (well within the second it waits).
    const auto args = [&](const std::string& f) {
        return "hydro --scene " + c.scene + " --west level --west-series " + c.series +
               " --duration 10 --output-interval 0.1 --max-dt 0.001 --label sig --out " + f;
    };
    const std::string ref = c.dir + "/ref.nc";
    ASSERT_EQ(test::run_cli(args(ref) + " --threads 1 --quiet", &out), 0) << out;
    for (const int sig : {SIGTERM, SIGINT}) {
        const std::string name = sig == SIGTERM ? "SIGTERM" : "SIGINT";
        SCOPED_TRACE(name);
        const std::string f = c.dir + "/f" + std::to_string(sig) + ".nc";
        FILE* run = test::start_cli(args(f) + " --threads 1");
        const pid_t holder = lock_holder(f, 20.0);
        ASSERT_GT(holder, 0);
        ASSERT_EQ(::kill(holder, sig), 0);
        EXPECT_EQ(test::finish_cli(run, &out), 1) << out;
        const std::string stop = f + ": interrupted (" + name + ") at t = ";
        const std::size_t at = out.find(stop);
        ASSERT_NE(at, std::string::npos) << out;
        const std::string t = out.substr(at + stop.size(), out.find(" s;", at) - at - stop.size());
        EXPECT_NE(out.find("continue it with the same command and --restart"), std::string::npos) << out;
        // The part's summary gives its span and cost, so that the parts of a continued
        // flow add up to its whole cost (pipelines/resolution_cost.py).
        EXPECT_NE(out.find("sig: interrupted (" + name + ") after "), std::string::npos) << out;
        EXPECT_NE(out.find(" steps (t = 0 to " + t + " s) in "), std::string::npos) << out;
        EXPECT_FALSE(fs::exists(f));
        ASSERT_TRUE(fs::exists(f + ".part"));
        ASSERT_TRUE(fs::exists(f + ".checkpoint.nc"));
        ASSERT_EQ(test::run_cli(args(f) + " --threads 2 --restart", &out), 0) << out;
        EXPECT_NE(out.find("sig: complete after "), std::string::npos) << out;
        EXPECT_NE(out.find(" steps (t = " + t + " to 10 s) in "), std::string::npos) << out;
        EXPECT_EQ(sha256_file(f), sha256_file(ref));
        EXPECT_FALSE(fs::exists(f + ".checkpoint.nc"));
    }
}

// A signal while the next frame is far off (a slow or stalled run): the run stops within
// a second or two, not at that frame. Here the only frame after t = 0 is at the end, some
// 10^6 steps away (minutes); stopped before its first checkpoint, it says so and keeps
// its partial output, and the same command starts afresh.
TEST(ReliabilityCli, ASignalFarFromTheNextFrameStopsTheRunAtOnce) {
    const SmallCase c = small_case("cli_signal_far");
    std::string out;
    const std::string f = c.dir + "/far.nc";
    const std::string args = "hydro --scene " + c.scene + " --west level --west-series " + c.series +
                             " --west-series-end transmissive --duration 1000 --output-interval 1000 --max-dt 0.001 "
                             "--threads 1 --label far --out " + f;
    FILE* run = test::start_cli(args);
    const pid_t holder = lock_holder(f, 20.0);
    ASSERT_GT(holder, 0);
    ::usleep(500000);  // under way: its steps measured
    const auto sent = std::chrono::steady_clock::now();
    ASSERT_EQ(::kill(holder, SIGTERM), 0);
    EXPECT_EQ(test::finish_cli(run, &out), 1) << out;
    const double waited = std::chrono::duration<double>(std::chrono::steady_clock::now() - sent).count();
    EXPECT_LT(waited, 20.0);  // the frame at t = 1000 s is minutes away
    EXPECT_NE(out.find(f + ": interrupted (SIGTERM) at t = "), std::string::npos) << out;
    EXPECT_NE(out.find("before its first checkpoint"), std::string::npos) << out;
    EXPECT_TRUE(fs::exists(f + ".part"));
    EXPECT_FALSE(fs::exists(f + ".checkpoint.nc"));
    EXPECT_FALSE(fs::exists(f));
}
