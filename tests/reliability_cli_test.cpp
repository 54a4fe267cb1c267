// Reliability through the command line, as a user runs it (issue 18): restart, one writer
// per output, finite numbers or a named error, inputs never outputs, readers that do
// not crash, a full disk. Each test runs the built `flotsam` binary.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "common/sha256.hpp"
#include "tests/test_support.hpp"

using namespace flotsam;
namespace fs = std::filesystem;

namespace {

// A 0.16 m scene (128 x 25 cells) and a 30 s boundary record: a hydro run of a few
// seconds takes well under a second.
struct SmallCase {
    std::string dir, scene, series;
};

SmallCase small_case(const std::string& name) {
    SmallCase c;
    c.dir = test::scratch_dir(name);
    c.scene = c.dir + "/scene.nc";
    c.series = c.dir + "/bc/wg1_r00.csv";
    std::string out;
    EXPECT_EQ(test::run_cli("scene generate --resolution 0.16 --out " + c.scene, &out), 0) << out;
    EXPECT_EQ(test::run_cli("boundary generate --count 1 --duration 30 --out-dir " + c.dir + "/bc", &out), 0) << out;
    return c;
}

std::string hydro_args(const SmallCase& c, const std::string& out) {
    return "hydro --scene " + c.scene + " --west level --west-series " + c.series +
           " --duration 6 --output-interval 0.5 --quiet --out " + out;
}

}  // namespace

// Stop, restart (on another thread count), and the same bytes as a run never stopped.
TEST(ReliabilityCli, RestartGivesTheBytesOfAnUninterruptedRun) {
    const SmallCase c = small_case("cli_restart");
    std::string out;
    const std::string ref = c.dir + "/ref.nc", f = c.dir + "/f.nc";
    ASSERT_EQ(test::run_cli(hydro_args(c, ref) + " --threads 1", &out), 0) << out;
    ASSERT_EQ(test::run_cli(hydro_args(c, f) + " --threads 1 --checkpoint-interval 1 --stop-after 2.5", &out), 0) << out;
    EXPECT_FALSE(fs::exists(f));
    ASSERT_TRUE(fs::exists(f + ".part"));
    ASSERT_TRUE(fs::exists(f + ".checkpoint.nc"));
    ASSERT_EQ(test::run_cli(hydro_args(c, f) + " --threads 2 --checkpoint-interval 1 --restart", &out), 0) << out;
    ASSERT_TRUE(fs::exists(f));
    EXPECT_FALSE(fs::exists(f + ".part"));
    EXPECT_FALSE(fs::exists(f + ".checkpoint.nc"));
    EXPECT_EQ(sha256_file(f), sha256_file(ref));
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
    EXPECT_NE(out.find("cfl: 0.45 in the checkpoint, 0.4 now"), std::string::npos) << out;
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
