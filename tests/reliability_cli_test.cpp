// Reliability through the command line, as a user runs it: restart, one writer
// per output, finite numbers or a named error, inputs never outputs, readers that do
// not crash, a full disk. Each test runs the built `flotsam` binary.
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
#include "fuzz/targets.hpp"
#include "tests/test_support.hpp"

using namespace flotsam;
namespace fs = std::filesystem;

namespace {

using test::SmallCase;
using test::small_case;

// The scene's whole grid, stored, on one uniform grid (not the Kainan scene's recommended
// window and nesting), so that flow cells are scene cells.
const std::string whole_grid = " --nest-ratio 1 --output-window -100,100,-100,100";

std::string hydro_args(const SmallCase& c, const std::string& out) {
    return "hydro --scene " + c.scene + " --west level --west-series " + c.series +
           " --duration 6 --output-interval 0.5 --quiet --out " + out;
}

// A flow and a sweep (with the spec) on the small case.
struct Outputs {
    std::string flow, sweep, spec;
};
Outputs flow_and_sweep(const SmallCase& c) {
    Outputs o{c.dir + "/flow.nc", c.dir + "/sweep.nc", c.dir + "/spec.toml"};
    std::string out;
    EXPECT_EQ(test::run_cli("hydro --scene " + c.scene + " --west level --west-series " + c.series + " --duration 4 --quiet" +
                                whole_grid + " --out " + o.flow,
                            &out),
              0)
        << out;
    const std::string spec = test::write_file(c.dir, "spec.toml",
                                              "[sweep]\nscene = \"" + c.scene + "\"\n[flows]\npaths = [\"" + o.flow +
                                                  "\"]\n[[body]]\nstart = \"FD\"\n[[body]]\nstart = \"LD\"\n"
                                                  "[variants]\nnames = [\"CC+SC\", \"LC+MC\"]\n");
    EXPECT_EQ(test::run_cli("sweep --spec " + spec + " --quiet --out " + o.sweep, &out), 0) << out;
    return o;
}
}  // namespace

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

// ---- one writer per output ----

namespace {

// The pid a run wrote into the lock file of its output ("pid N on HOST"), once written;
// 0 if none appears within `seconds`.
pid_t lock_holder(const std::string& out, double seconds) {
    for (int k = 0; k < int(seconds * 100); ++k) {
        std::ifstream in(out + ".lock");
        std::string word;
        long pid = 0;
        if (in >> word >> pid && word == "pid" && pid > 0) return pid_t(pid);
        ::usleep(10000);
    }
    return 0;
}

}  // namespace

// Two runs with one --out: the second stops at once naming the first, which finishes
// with the same bytes as if it had been alone; with and without HDF5's own locking.
TEST(ReliabilityCli, SecondWriterStopsAtOnceAndTheFirstFinishesIntact) {
    const SmallCase c = small_case("cli_two_writers");
    std::string out;
    const std::string args = "hydro --scene " + c.scene + " --west level --west-series " + c.series +
                             " --duration 30 --output-interval 0.5 --threads 1 --quiet" + whole_grid + " --out ";
    ASSERT_EQ(test::run_cli(args + c.dir + "/ref.nc", &out), 0) << out;
    const std::string ref = sha256_file(c.dir + "/ref.nc");
    for (const std::string env : {"", "HDF5_USE_FILE_LOCKING=FALSE"}) {
        SCOPED_TRACE(env.empty() ? "HDF5 file locking on" : env);
        const std::string f = c.dir + "/f" + std::to_string(env.size()) + ".nc";
        FILE* first = test::start_cli(args + f, env);
        // The first run is held (SIGSTOP) once it holds the output, so that the others
        // surely start while it runs, however loaded the machine: unheld it takes well
        // under a second, and a slow start of the others let it finish first (a flaky test).
        const pid_t holder = lock_holder(f, 20.0);
        ASSERT_GT(holder, 0);
        ASSERT_EQ(::kill(holder, SIGSTOP), 0);
        // Two more writers started at once while the first runs (they stop at once): one
        // with HDF5 locking as the test's environment has it, one with env.
        FILE* second = test::start_cli(args + f, "");
        FILE* third = test::start_cli(args + f, env);
        const int rc = test::finish_cli(second, &out);
        std::string out2;
        const int rc2 = test::finish_cli(third, &out2);
        EXPECT_NE(rc, 0);
        EXPECT_NE(out.find("another run is writing " + f + " (pid "), std::string::npos) << out;
        EXPECT_NE(rc2, 0);
        EXPECT_NE(out2.find("another run is writing"), std::string::npos) << out2;
        ASSERT_EQ(::kill(holder, SIGCONT), 0);
        ASSERT_EQ(test::finish_cli(first, &out), 0) << out;
        EXPECT_EQ(sha256_file(f), ref);
        EXPECT_FALSE(fs::exists(f + ".part"));
        EXPECT_FALSE(fs::exists(f + ".lock"));
    }
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

// Every command that writes an output takes its lock: with the lock held here (as a run
// would hold it), each stops at once and leaves the existing file alone.
TEST(ReliabilityCli, EveryWritingCommandTakesTheOutputLock) {
    const SmallCase c = small_case("cli_lock_all");
    std::string out;
    const std::string spec = flow_and_sweep(c).spec;
    const std::string target = c.dir + "/taken.nc";
    test::write_file(c.dir, "taken.nc", "precious");
    const OutputLock held(target);
    const std::vector<std::string> commands = {
        "hydro --scene " + c.scene + " --west level --west-series " + c.series + " --duration 4 --quiet --out " + target,
        "debris --flow " + c.dir + "/flow.nc --scene " + c.scene + " --start FD --quiet --out " + target,
        "sweep --spec " + spec + " --quiet --out " + target,
        "sweep merge " + c.dir + "/sweep.nc --out " + target,
        "stats --sweep " + c.dir + "/sweep.nc --out " + target,
        "scene generate --resolution 0.16 --out " + target,
        "scene import --dem " + c.scene + " --resolution 0.32 --out " + target,
    };
    for (const auto& cmd : commands) {
        EXPECT_NE(test::run_cli(cmd, &out), 0) << cmd;
        EXPECT_NE(out.find("another run is writing " + target + " (pid " + std::to_string(::getpid())), std::string::npos)
            << cmd << "\n"
            << out;
    }
    {
        const OutputLock records(c.dir + "/bc2/wg1_r01.csv");
        EXPECT_NE(test::run_cli("boundary generate --count 2 --duration 30 --out-dir " + c.dir + "/bc2", &out), 0);
        EXPECT_NE(out.find("another run is writing"), std::string::npos) << out;
        EXPECT_FALSE(fs::exists(c.dir + "/bc2/wg1_r00.csv"));  // stopped before writing anything
    }
    std::ifstream f(target);
    std::string text;
    std::getline(f, text);
    EXPECT_EQ(text, "precious");
}

// ---- inputs are never outputs ----

TEST(ReliabilityCli, AnOutputThatIsAnInputIsRefused) {
    const SmallCase c = small_case("cli_in_out");
    std::string out;
    const std::string spec = flow_and_sweep(c).spec;
    fs::create_symlink(c.scene, c.dir + "/link.nc");
    fs::create_directories(c.dir + "/sub");
    const std::string hydro = "hydro --west level --duration 4 --quiet ";
    struct Case {
        std::string args, input;
    };
    const std::vector<Case> cases = {
        {hydro + "--scene " + c.scene + " --west-series " + c.series + " --out " + c.scene, c.scene},
        {hydro + "--scene " + c.scene + " --west-series " + c.series + " --out " + c.dir + "/link.nc", c.scene},
        {hydro + "--scene " + c.scene + " --west-series " + c.series + " --out " + c.dir + "/sub/../scene.nc", c.scene},
        {hydro + "--scene " + c.scene + " --west-series " + c.series + " --out " + c.series, c.series},
        {"debris --flow " + c.dir + "/flow.nc --at 0.5,-1,0 --quiet --out " + c.dir + "/flow.nc", c.dir + "/flow.nc"},
        {"stats --sweep " + c.dir + "/sweep.nc --out " + c.dir + "/sweep.nc", c.dir + "/sweep.nc"},
        {"scene import --dem " + c.scene + " --resolution 0.32 --out " + c.scene, c.scene},
        {"sweep merge " + c.dir + "/sweep.nc --out " + c.dir + "/sweep.nc", c.dir + "/sweep.nc"},
    };
    for (const auto& k : cases) {
        const std::string before = sha256_file(k.input);
        EXPECT_NE(test::run_cli(k.args, &out), 0) << k.args;
        EXPECT_NE(out.find("is the input given as"), std::string::npos) << k.args << "\n" << out;
        EXPECT_EQ(sha256_file(k.input), before) << k.args;
    }
    // The summary of a sweep is an output too: never the main output.
    EXPECT_NE(test::run_cli("sweep --spec " + spec + " --quiet --out " + c.dir + "/o.nc --summary " + c.dir + "/o.nc", &out), 0);
    EXPECT_NE(out.find("is also the output given as --out"), std::string::npos) << out;
    EXPECT_FALSE(fs::exists(c.dir + "/o.nc"));
}

// ---- finite numbers in range, or a named error ----

TEST(ReliabilityCli, NonFiniteAndAbsurdOptionsAreNamedWithValueAndRange) {
    const SmallCase c = small_case("cli_ranges");
    std::string out;
    const std::string hydro =
        "hydro --scene " + c.scene + " --west level --west-series " + c.series + " --duration 4 --quiet --out " + c.dir + "/f.nc ";
    const std::string flow = flow_and_sweep(c).flow;
    const std::string debris = "debris --flow " + flow + " --scene " + c.scene + " --start FD --quiet --out " + c.dir + "/d.nc ";
    const std::string stats = "stats --sweep " + c.dir + "/sweep.nc --out " + c.dir + "/s.nc ";
    struct Case {
        std::string args, expect;
    };
    const std::vector<Case> cases = {
        {hydro + "--max-dt 0", "--max-dt: 0 is outside the allowed range (0, inf) s"},
        {hydro + "--manning-n nan", "--manning-n: nan is not a finite number (allowed: [0, 1) s m^-1/3)"},
        {hydro + "--manning-n -1", "--manning-n: -1 is outside the allowed range [0, 1)"},
        {hydro + "--gauge-interval 0", "--gauge-interval: 0 is outside the allowed range (0, inf) s"},
        {hydro + "--cfl inf", "--cfl: inf is not a finite number"},
        {hydro + "--output-interval 1e-9", "--output-interval: 1e-09 s over 4"},
        {hydro + "--output-window 20,30,20,30", "--output-window: x 20"},
        {hydro + "--gauge G,1,nan", "--gauge 'G,1,nan': y: nan is not a finite number"},
        {debris + "--cm nan", "--cm: nan is not a finite number (allowed: [1, 100])"},
        {debris + "--cd1 nan", "--cd1: nan is not a finite number"},
        {debris + "--restitution nan", "--restitution: nan is not a finite number (allowed: [0, 1])"},
        {debris + "--length 1e6", "--length: 1e+06 is outside the allowed range (0, 10000] m"},
        {debris + "--length 50", "body 'FD': size: a 50 x 0.1 m body does not fit in the domain"},
        {"debris --flow " + flow + " --at 1.37,-2.15,nan --quiet --out " + c.dir + "/d.nc",
         "--at: 1.37,-2.15,nan: expected x,y,heading_deg (finite numbers)"},
        {stats + "--arrival-time nan", "--arrival-time: nan is not a finite number"},
        {stats + "--yaw-window -1", "--yaw-window: -1 is outside the allowed range (0, inf) s"},
        {stats + "--kde-points 2e9", "--kde-points"},
        {"scene import --dem " + c.scene + " --resolution 1e-5 --out " + c.dir + "/i.nc", "--resolution: 1e-05 m would make"},
        {"scene generate --resolution 0 --out " + c.dir + "/g.nc", "--resolution: 0 is outside the allowed range (0, 100] m"},
        {"boundary generate --dt 0 --out-dir " + c.dir + "/bc3", "--dt: 0 is outside the allowed range (0, inf) s"},
    };
    for (const auto& k : cases) {
        EXPECT_EQ(test::run_cli(k.args, &out) == 0, false) << k.args;
        EXPECT_NE(out.find(k.expect), std::string::npos) << k.args << "\n" << out;
        EXPECT_EQ(out.find("internal error"), std::string::npos) << out;
    }
    // Sweep spec values go through the same ranges, naming file, line and key.
    const std::string bad_spec = test::write_file(c.dir, "bad.toml",
                                                  "[sweep]\nscene = \"" + c.scene + "\"\n[flows]\npaths = [\"" + flow +
                                                      "\"]\n[[body]]\nstart = \"FD\"\n[parameters]\ncd1 = 1e300\n");
    EXPECT_NE(test::run_cli("sweep --spec " + bad_spec + " --quiet --out " + c.dir + "/w.nc", &out), 0);
    EXPECT_NE(out.find("bad.toml: line 8: [parameters] key 'cd1': parameter set 'control' gets cd1 = 1e+300 is outside"),
              std::string::npos)
        << out;
    const std::string huge =
        test::write_file(c.dir, "huge.toml",
                         "[sweep]\nscene = \"" + c.scene + "\"\n[flows]\npaths = [\"" + flow +
                             "\"]\n[[body]]\nstart = \"FD\"\n[perturbation]\ncount = 1e6\nposition-std = 0.01\n"
                             "[parameters]\ndesign = \"random\"\nsamples = 1000000\n");
    EXPECT_NE(test::run_cli("sweep --spec " + huge + " --quiet --out " + c.dir + "/w.nc", &out), 0);
    EXPECT_NE(out.find("huge.toml: sweep size: "), std::string::npos) << out;
}

// Settings files: the same checks, naming the file and key; a misspelled section, a key
// given twice and an array for a one-value setting are named errors too.
TEST(ReliabilityCli, SettingsFileErrorsNameFileAndKey) {
    const SmallCase c = small_case("cli_settings");
    std::string out;
    const std::string hydro =
        "hydro --scene " + c.scene + " --west level --west-series " + c.series + " --quiet --out " + c.dir + "/f.nc --config ";
    struct Case {
        std::string text, expect;
    };
    const std::vector<Case> cases = {
        {"[hydor]\nduration = 5\n", "settings.toml: section [hydor]: 'hydor' is not a flotsam command"},
        {"duration = 5\nduration = 6\n", "settings.toml: line 2: key 'duration' given twice in the same table"},
        {"duration = [5, 6]\n", "settings.toml: line 1: key 'duration': takes one value, the file gives an array of 2"},
        {"[hydro]\nmax-dt = 0\n", "settings.toml: key 'max-dt': 0 is outside the allowed range (0, inf) s"},
        {"manning-n = -0.5\n", "settings.toml: key 'manning-n': -0.5 is outside the allowed range"},
        {"durtion = 5\n", "settings.toml: line 1: key 'durtion': is not a setting of 'flotsam hydro'"},
    };
    for (const auto& k : cases) {
        const std::string file = test::write_file(c.dir, "settings.toml", k.text);
        EXPECT_NE(test::run_cli(hydro + file, &out), 0) << k.text;
        EXPECT_NE(out.find(k.expect), std::string::npos) << k.text << "\n" << out;
    }
}

// A state that is no longer finite (a level series of 1e300 after 1 s) stops hydro with
// the time, the cell and the variable, a non-zero exit, and no flow file.
TEST(ReliabilityCli, HydroStopsAtTheFirstNonFiniteStateAndLeavesNoFile) {
    const SmallCase c = small_case("cli_nan_state");
    std::string csv = "time,eta\n0,0\n1,0.01\n";
    for (int t = 2; t <= 30; t += 2) csv += std::to_string(t) + ",1e300\n";
    const std::string series = test::write_file(c.dir, "bad.csv", csv);
    std::string out;
    const std::string f = c.dir + "/f.nc";
    EXPECT_NE(
        test::run_cli("hydro --scene " + c.scene + " --west level --west-series " + series + " --duration 6 --out " + f, &out), 0);
    EXPECT_NE(out.find("the run stopped: at t = "), std::string::npos) << out;
    EXPECT_NE(out.find("cell (i "), std::string::npos) << out;
    EXPECT_NE(out.find("no flow file was written"), std::string::npos) << out;
    EXPECT_EQ(out.find("complete after"), std::string::npos) << out;
    EXPECT_FALSE(fs::exists(f));
    EXPECT_FALSE(fs::exists(f + ".part"));
}

// ---- readers that cannot be made to crash ----

TEST(ReliabilityCli, TablesWhoseLengthsDisagreeAreNamedErrors) {
    const SmallCase c = small_case("cli_tables");
    const Outputs o = flow_and_sweep(c);
    std::string out;
    // A scene with 3 point names and a 1-entry point_kind (hydro and debris crashed on it).
    fuzz::copy_with_short_column(c.scene, c.dir + "/short_points.nc", "point_kind", 1);
    EXPECT_NE(test::run_cli("hydro --scene " + c.dir + "/short_points.nc --west wall --duration 1 --quiet --out " + c.dir + "/x.nc",
                            &out),
              0);
    EXPECT_NE(out.find("short_points.nc: variable 'point_kind': must be one-dimensional on dimension 'point' of length"),
              std::string::npos)
        << out;
    // A short section table (read out of bounds before).
    fuzz::copy_with_short_column(c.scene, c.dir + "/short_sections.nc", "section_y_max", 1);
    EXPECT_NE(test::run_cli("stats --sweep " + o.sweep + " --scene " + c.dir + "/short_sections.nc --out " + c.dir + "/s.nc", &out),
              0);
    EXPECT_NE(out.find("variable 'section_y_max': must be one-dimensional on dimension 'section'"), std::string::npos) << out;
    // A sweep file whose `body` column has 1 entry for every trajectory (stats crashed).
    fuzz::copy_with_short_column(o.sweep, c.dir + "/short_body.nc", "body", 1);
    EXPECT_NE(test::run_cli("stats --sweep " + c.dir + "/short_body.nc --out " + c.dir + "/s.nc", &out), 0);
    EXPECT_NE(out.find("short_body.nc: variable 'body': must be one-dimensional on dimension 'trajectory'"), std::string::npos)
        << out;
    fuzz::copy_with_short_column(o.sweep, c.dir + "/short_variant.nc", "variant", 1);
    EXPECT_NE(test::run_cli("stats --sweep " + c.dir + "/short_variant.nc --out " + c.dir + "/s.nc", &out), 0);
    EXPECT_NE(out.find("variable 'variant'"), std::string::npos) << out;
    EXPECT_EQ(out.find("internal error"), std::string::npos) << out;
}

TEST(ReliabilityCli, FlowsAreCheckedAgainstTheirSceneAndTheirValues) {
    const SmallCase c = small_case("cli_flow_checks");
    const Outputs o = flow_and_sweep(c);
    std::string out;
    const std::string debris = " --start FD --quiet --out " + c.dir + "/d.nc";
    // A flow from another scene (another building layout) with this scene's buildings.
    const std::string other = c.dir + "/other.nc";
    ASSERT_EQ(test::run_cli("scene generate --resolution 0.16 --seed 7 --out " + other, &out), 0) << out;
    EXPECT_NE(test::run_cli("debris --flow " + o.flow + " --scene " + other + debris, &out), 0);
    EXPECT_NE(out.find("was not computed on scene " + other + ": the bed differs at"), std::string::npos) << out;
    EXPECT_NE(out.find("sha256"), std::string::npos) << out;
    // A body inside a building, and one outside the domain.
    const Scene scene = read_scene(c.scene);
    std::size_t k = 0;
    while (k < scene.building.size() && !scene.building[k]) ++k;
    ASSERT_LT(k, scene.building.size());
    const double bx = scene.grid.x(int(k % std::size_t(scene.grid.nx))), by = scene.grid.y(int(k / std::size_t(scene.grid.nx)));
    EXPECT_NE(test::run_cli("debris --flow " + o.flow + " --scene " + c.scene + " --at " + std::to_string(bx) + "," +
                                std::to_string(by) + ",0 --quiet --out " + c.dir + "/d.nc",
                            &out),
              0);
    EXPECT_NE(out.find("body 'body0': start: at x = "), std::string::npos) << out;
    EXPECT_NE(out.find("its centre is inside a building"), std::string::npos) << out;
    EXPECT_NE(test::run_cli("debris --flow " + o.flow + " --at 100,100,0 --quiet --out " + c.dir + "/d.nc", &out), 0);
    EXPECT_NE(out.find("body 'body0': start: at x = 100 m, y = 100 m is outside the domain"), std::string::npos) << out;
    // A one-frame flow, a negative depth, a fill value in v.
    fuzz::copy_with_dimension(o.flow, c.dir + "/one_frame.nc", "time", 1);
    EXPECT_NE(test::run_cli("debris --flow " + c.dir + "/one_frame.nc --scene " + c.scene + debris, &out), 0);
    EXPECT_NE(out.find("one_frame.nc: variable 'time': 1 frame(s): a flow to replay needs at least two"), std::string::npos) << out;
    // Under the FD start, so that the frames the replay loads hold it.
    const std::size_t cells = std::size_t(scene.grid.nx) * std::size_t(scene.grid.ny);
    const ScenePoint* fd = scene.find_point("FD");
    ASSERT_NE(fd, nullptr);
    const int fi = scene.grid.cell_i(fd->x), fj = scene.grid.cell_j(fd->y);
    const std::string cell = "cell (i " + std::to_string(fi) + ", j " + std::to_string(fj) + ")";
    fuzz::copy_with_value(o.flow, c.dir + "/negative.nc", "h", cells + scene.grid.index(fi, fj), -0.1);
    EXPECT_NE(test::run_cli("debris --flow " + c.dir + "/negative.nc --scene " + c.scene + debris, &out), 0);
    EXPECT_NE(out.find("negative.nc: frame 1, " + cell + ": h = -0.1"), std::string::npos) << out;
    fuzz::copy_with_value(o.flow, c.dir + "/fill.nc", "v", scene.grid.index(fi, fj), 9.969209968386869e36);
    EXPECT_NE(test::run_cli("debris --flow " + c.dir + "/fill.nc --scene " + c.scene + debris, &out), 0);
    EXPECT_NE(out.find("fill.nc: frame 0, " + cell + ": v = "), std::string::npos) << out;
    EXPECT_EQ(out.find("internal error"), std::string::npos) << out;
}

// A square DEM stored as z(x, y) is read by its dimension names, not transposed.
TEST(ReliabilityCli, ATransposedDemIsReadByDimensionName) {
    const auto dir = test::scratch_dir("cli_dem_xy");
    auto write_dem = [&](const std::string& path, bool x_first) {
        nc::File f = nc::File::create(path);
        const int dx = f.def_dim("x", 4), dy = f.def_dim("y", 4);
        const int vx = f.def_var("x", NC_DOUBLE, {dx}), vy = f.def_var("y", NC_DOUBLE, {dy});
        const int vz = f.def_var("z", NC_DOUBLE, x_first ? std::vector<int>{dx, dy} : std::vector<int>{dy, dx});
        f.enddef();
        f.put(vx, std::vector<double>{0.5, 1.5, 2.5, 3.5});
        f.put(vy, std::vector<double>{0.5, 1.5, 2.5, 3.5});
        std::vector<double> z(16);
        for (int j = 0; j < 4; ++j)
            for (int i = 0; i < 4; ++i) z[x_first ? std::size_t(i * 4 + j) : std::size_t(j * 4 + i)] = 0.1 * i - 0.01 * j;
        f.put(vz, z);
        f.close();
    };
    write_dem(dir + "/yx.nc", false);
    write_dem(dir + "/xy.nc", true);
    std::string out;
    ASSERT_EQ(test::run_cli("scene import --dem " + dir + "/yx.nc --resolution 1 --out " + dir + "/a.nc", &out), 0) << out;
    ASSERT_EQ(test::run_cli("scene import --dem " + dir + "/xy.nc --resolution 1 --out " + dir + "/b.nc", &out), 0) << out;
    const Scene a = read_scene(dir + "/a.nc"), b = read_scene(dir + "/b.nc");
    EXPECT_EQ(a.z, b.z);
    EXPECT_NEAR(a.z[a.grid.index(3, 0)], 0.3, 1e-6);  // east is +x in both
}

// ---- a full disk ----

// A 200 kB file system (tmpfs, mounted here when permitted): hydro fails at the first
// frame it cannot write, names the path and "No space left on device", exits 1 (not a
// crash), and leaves no file that looks finished.
TEST(ReliabilityCli, AFullDiskIsANamedErrorNotACrash) {
    const SmallCase c = small_case("cli_full_disk");
    const std::string mnt = c.dir + "/tiny";
    fs::create_directories(mnt);
    if (std::system(("mount -t tmpfs -o size=200k tmpfs " + mnt + " 2>/dev/null").c_str()) != 0) {
        std::printf("skipped: cannot mount a 200 kB tmpfs here (needs root)\n");
        GTEST_SKIP() << "mounting a tmpfs is not permitted";
    }
    struct Unmount {
        std::string dir;
        ~Unmount() { (void)std::system(("umount " + dir).c_str()); }
    } unmount{mnt};
    std::string out;
    const std::string f = mnt + "/f.nc";
    const int rc = test::run_cli("hydro --scene " + c.scene + " --west level --west-series " + c.series +
                                     " --duration 30 --output-interval 0.1 --deflate 0 --quiet --out " + f,
                                 &out);
    EXPECT_EQ(rc, 1) << out;
    EXPECT_NE(out.find("No space left on device"), std::string::npos) << out;
    EXPECT_NE(out.find(f + ".part"), std::string::npos) << out;
    EXPECT_NE(out.find("while writing frame "), std::string::npos) << out;  // at a frame, not at the end
    EXPECT_FALSE(fs::exists(f));
    // Another writer on the (nearly) full file system: a scene.
    EXPECT_EQ(std::system(("dd if=/dev/zero of=" + mnt + "/filler bs=1k count=190 2>/dev/null").c_str()), 0);
    EXPECT_EQ(test::run_cli("scene generate --resolution 0.04 --out " + mnt + "/scene.nc", &out), 1) << out;
    EXPECT_NE(out.find("No space left on device"), std::string::npos) << out;
    EXPECT_FALSE(fs::exists(mnt + "/scene.nc"));
}

// A flow whose structure was corrupted (two bytes in its first 16 kB) so that libhdf5
// itself segfaults parsing it (ncdump does too): flotsam names the file instead of
// crashing (nc::probe_structure).
TEST(ReliabilityCli, AFileThatCrashesLibhdf5IsANamedError) {
    const std::string corrupt = std::string(FLOTSAM_SOURCE_DIR) + "/tests/data/corrupt/flow_libhdf5_segfault.nc";
    const auto dir = test::scratch_dir("cli_corrupt");
    std::string out;
    EXPECT_EQ(test::run_cli("debris --flow " + corrupt + " --at 0.5,-1,0 --quiet --out " + dir + "/d.nc", &out), 1) << out;
    EXPECT_NE(out.find("flow_libhdf5_segfault.nc: corrupted: libhdf5 crashed "), std::string::npos)
        << out;
}

// A flow whose data were damaged in one frame (its structure intact, so the structure
// probe passes): the debris run stops where it needs that frame, with an error naming
// the file, the variable and the frame, and leaves no output behind.
TEST(ReliabilityCli, ADamagedFlowFrameIsANamedErrorAndLeavesNoOutput) {
    const auto dir = test::scratch_dir("cli_damaged");
    const std::string flow = test::uniform_flow(dir + "/f.nc", Grid{40, 20, 0.025, -0.975, 0.05, 0.05}, 6.0, 0.1, 0.2, 0.0);
    test::damage_chunk(flow, "h", 4);
    std::string out;
    EXPECT_EQ(test::run_cli("debris --flow " + flow + " --at 1.0,-0.5,0 --quiet --out " + dir + "/d.nc", &out), 1) << out;
    EXPECT_NE(out.find(flow + ": variable 'h', frame 4, tile (0, 0)"), std::string::npos) << out;
    EXPECT_FALSE(fs::exists(dir + "/d.nc"));
    EXPECT_FALSE(fs::exists(dir + "/d.nc.part"));
}

// ---- no input crashes it, none is taken silently, no run is unbounded ----

namespace {

// Edits of a copy of a NetCDF file, as a user's other tools would make them.
std::string copy_of(const std::string& from, const std::string& to) {
    fs::copy_file(from, to, fs::copy_options::overwrite_existing);
    return to;
}

int var_id(int id, const std::string& var) {
    int v = NC_GLOBAL;
    if (var != "global") {
        EXPECT_EQ(nc_inq_varid(id, var.c_str(), &v), NC_NOERR) << var;
    }
    return v;
}

void set_text_attribute(const std::string& path, const std::string& var, const std::string& name, const std::string& text) {
    int id = -1;
    ASSERT_EQ(nc_open(path.c_str(), NC_WRITE, &id), NC_NOERR);
    ASSERT_EQ(nc_redef(id), NC_NOERR);
    ASSERT_EQ(nc_put_att_text(id, var_id(id, var), name.c_str(), text.size(), text.c_str()), NC_NOERR);
    ASSERT_EQ(nc_close(id), NC_NOERR);
}

std::vector<double> all_values(const std::string& path, const std::string& var) {
    const nc::File f = nc::File::open_read(path);
    return f.get_double(f.var(var));
}

// Every value of `var` multiplied by `factor` (for a file in other units).
void scale_values(const std::string& path, const std::string& var, double factor) {
    std::vector<double> v = all_values(path, var);
    for (double& a : v) a *= factor;
    int id = -1;
    ASSERT_EQ(nc_open(path.c_str(), NC_WRITE, &id), NC_NOERR);
    ASSERT_EQ(nc_put_var_double(id, var_id(id, var), v.data()), NC_NOERR);
    ASSERT_EQ(nc_close(id), NC_NOERR);
}

void set_all(const std::string& path, const std::string& var, double value) {
    std::vector<double> v = all_values(path, var);
    std::fill(v.begin(), v.end(), value);
    int id = -1;
    ASSERT_EQ(nc_open(path.c_str(), NC_WRITE, &id), NC_NOERR);
    ASSERT_EQ(nc_put_var_double(id, var_id(id, var), v.data()), NC_NOERR);
    ASSERT_EQ(nc_close(id), NC_NOERR);
}

// String `index` of a character array (flotsam's strings), NUL-padded to its length.
void set_string(const std::string& path, const std::string& var, std::size_t index, const std::string& text) {
    int id = -1;
    ASSERT_EQ(nc_open(path.c_str(), NC_WRITE, &id), NC_NOERR);
    const int v = var_id(id, var);
    int dims[2];
    std::size_t length = 0;
    ASSERT_EQ(nc_inq_vardimid(id, v, dims), NC_NOERR);
    ASSERT_EQ(nc_inq_dimlen(id, dims[1], &length), NC_NOERR);
    ASSERT_LE(text.size(), length);
    std::string padded = text;
    padded.resize(length, '\0');
    const std::size_t start[2] = {index, 0}, count[2] = {1, length};
    ASSERT_EQ(nc_put_vara_text(id, v, start, count, padded.data()), NC_NOERR);
    ASSERT_EQ(nc_close(id), NC_NOERR);
}

struct Case {
    std::string args, expect;
};

// Each command fails (exit 1, not a crash) with `expect` in its output, never an internal error.
void expect_named_errors(const std::vector<Case>& cases) {
    std::string out;
    for (const auto& k : cases) {
        const int rc = test::run_cli(k.args, &out);
        EXPECT_TRUE(rc == 1 || rc == 105) << "rc " << rc << ": " << k.args << "\n" << out;  // 105: CLI11's parse errors
        EXPECT_NE(out.find(k.expect), std::string::npos) << k.args << "\n" << out;
        EXPECT_EQ(out.find("internal error"), std::string::npos) << out;
    }
}

}  // namespace

// Files whose bytes were changed where libhdf5 keeps variable-length strings (its global
// heap) or metadata it frees at close: libhdf5 segfaulted reading the strings, or aborted
// with "free(): invalid size" closing the file, in hydro, debris and stats. The probe now
// reads every string and closes the file in a child first: a named error, saying what it
// was reading.
TEST(ReliabilityCli, FilesThatCrashLibhdf5OnTheirStringsOrAtCloseAreNamedErrors) {
    const SmallCase c = small_case("cli_corrupt_strings");
    const Outputs o = flow_and_sweep(c);
    const std::string data = std::string(FLOTSAM_SOURCE_DIR) + "/tests/data/corrupt/";
    const std::string scene_close = data + "scene_abort_at_close.nc", scene_strings = data + "scene_segfault_in_strings.nc",
                      sweep_strings = data + "sweep_segfault_in_strings.nc";
    std::string out;
    for (const std::string& scene : {scene_close, scene_strings}) {
        for (const std::string& cmd :
             {"hydro --scene " + scene + " --west wall --duration 0.5 --quiet --out " + c.dir + "/h.nc",
              "debris --flow " + o.flow + " --scene " + scene + " --start FD --quiet --out " + c.dir + "/d.nc",
              "stats --sweep " + o.sweep + " --scene " + scene + " --out " + c.dir + "/s.nc"}) {
            EXPECT_EQ(test::run_cli(cmd, &out), 1) << cmd << "\n" << out;
            EXPECT_NE(out.find(scene + ": corrupted: libhdf5 "), std::string::npos) << cmd << "\n" << out;
            EXPECT_EQ(out.find("free()"), std::string::npos) << out;  // the child's dying words are not the user's
        }
    }
    EXPECT_NE(test::run_cli("hydro --scene " + scene_close + " --west wall --duration 0.5 --quiet --out " + c.dir + "/h.nc", &out),
              0);
    EXPECT_NE(out.find("crashed closing the file"), std::string::npos) << out;
    EXPECT_NE(test::run_cli("stats --sweep " + sweep_strings + " --scene " + c.scene + " --out " + c.dir + "/s.nc", &out), 0);
    EXPECT_NE(out.find(sweep_strings + ": corrupted: libhdf5 crashed reading variable '"), std::string::npos) << out;
    EXPECT_FALSE(fs::exists(c.dir + "/h.nc.part"));
}

// An output that exists and is not a regular file (a device, a FIFO, a directory) is
// refused before any work: renaming <out>.part over /dev/null replaced the device.
TEST(ReliabilityCli, OutputsThatAreNotRegularFilesAreRefused) {
    const SmallCase c = small_case("cli_out_not_file");
    const Outputs o = flow_and_sweep(c);
    ASSERT_EQ(::mkfifo((c.dir + "/fifo.nc").c_str(), 0644), 0);
    fs::create_directories(c.dir + "/dir.nc");
    const std::string hydro = "hydro --scene " + c.scene + " --west wall --duration 0.5 --quiet --out ";
    expect_named_errors({
        {hydro + "/dev/null", "--out: /dev/null: is a character device, not a regular file"},
        {"debris --flow " + o.flow + " --scene " + c.scene + " --start FD --quiet --out /dev/full",
         "--out: /dev/full: is a character device"},
        {"sweep --spec " + o.spec + " --quiet --out /dev/null", "--out: /dev/null: is a character device"},
        {"scene generate --resolution 0.32 --out /dev/null", "--out: /dev/null: is a character device"},
        {"stats --sweep " + o.sweep + " --out " + c.dir + "/fifo.nc", "fifo.nc: is a FIFO (named pipe), not a regular file"},
        {hydro + c.dir + "/dir.nc", "dir.nc: is a directory, not a regular file"},
    });
    struct stat st {};
    ASSERT_EQ(::stat("/dev/null", &st), 0);
    EXPECT_TRUE(S_ISCHR(st.st_mode));
    EXPECT_FALSE(fs::exists("/dev/null.part"));
}

// Every run is estimated before it starts and refused past a stated bound, naming the
// option and the estimate; streams that never end are refused as inputs; sizes that do
// not fit name the file and variable; threads are capped at the processors.
TEST(ReliabilityCli, RunsAreBoundedBeforeTheyStart) {
    const SmallCase c = small_case("cli_bounded");
    const Outputs o = flow_and_sweep(c);
    const std::string debris = "debris --flow " + o.flow + " --scene " + c.scene + " --start FD --quiet --out " + c.dir + "/d.nc ";
    const std::string spec = test::write_file(c.dir, "dt.toml",
                                              "[sweep]\nscene = \"" + c.scene + "\"\ndt-max = 1e-12\n[flows]\npaths = [\"" + o.flow +
                                                  "\"]\n[[body]]\nstart = \"FD\"\n");
    std::string levels;
    for (int k = 1; k <= 1000; ++k) {
        if (k > 1) levels += ',';
        levels += std::to_string(k);
    }
    const std::string factorial = test::write_file(c.dir, "factorial.toml",
                                                   "[sweep]\nscene = \"" + c.scene + "\"\n[flows]\npaths = [\"" + o.flow +
                                                       "\"]\n[[body]]\nstart = \"FD\"\n[parameters]\ndesign = \"factorial\"\ncd1 = [" +
                                                       levels + "]\ncd2 = [" + levels + "]\ncm = [" + levels + "]\n");
    // A flow whose last frame is at 1e6 s (the replay would take hours).
    const std::string late = copy_of(o.flow, c.dir + "/late.nc");
    fuzz::copy_with_value(o.flow, late, "time", all_values(o.flow, "time").size() - 1, 1e6);
    // A scene declaring 2e5 x 1e5 cells (its z never written: the file is small).
    const std::string huge = c.dir + "/huge.nc";
    {
        nc::File f = nc::File::create(huge);
        const int dx = f.def_dim("x", 200000), dy = f.def_dim("y", 100000);
        const int vx = f.def_var("x", NC_DOUBLE, {dx}), vy = f.def_var("y", NC_DOUBLE, {dy});
        const int vz = f.def_var("z", NC_FLOAT, {dy, dx});
        f.def_chunking(vz, {256, 256});
        f.enddef();
        std::vector<double> x(200000), y(100000);
        for (std::size_t k = 0; k < x.size(); ++k) x[k] = double(k);
        for (std::size_t k = 0; k < y.size(); ++k) y[k] = double(k);
        f.put(vx, x);
        f.put(vy, y);
        f.close();
    }
    ASSERT_EQ(::mkfifo((c.dir + "/series_fifo.csv").c_str(), 0644), 0);
    expect_named_errors({
        {debris + "--dt-max 1e-12", "--dt-max: 1e-12 s over 0 to 4 s of " + o.flow + " would make 4e+12 steps of each body, more than the 1e+07"},
        {debris + "--vertex-step-fraction 1e-12", "--vertex-step-fraction: 1e-12 (steps of "},
        {"sweep --spec " + spec + " --quiet --out " + c.dir + "/w.nc", "dt.toml: [sweep] dt-max: 1e-12 s over 0 to 4 s"},
        {"debris --flow " + late + " --scene " + c.scene + " --start FD --quiet --out " + c.dir + "/d.nc",
         "--dt-max: 0.01 s over 0 to 1e+06 s of " + late + " would make 1e+08 steps of each body"},
        {"boundary generate --froude-scale 1e4 --duration 1e6 --dt 0.001 --out-dir " + c.dir + "/bc2",
         "--dt: 10 records of 1e+06 s every 0.001 s would make 1e+10 samples"},
        {"boundary generate --dt 1e-12 --out-dir " + c.dir + "/bc2", "--dt: 10 records of 420 s every 1e-12 s would make 4.2e+15 samples"},
        {"hydro --scene " + c.scene + " --west level --west-series /dev/zero --duration 1 --quiet --out " + c.dir + "/h.nc",
         "--west-series: /dev/zero: is a character device, not a regular file"},
        {"hydro --scene " + c.scene + " --west level --west-series " + c.dir + "/series_fifo.csv --duration 1 --quiet --out " + c.dir +
             "/h.nc",
         "series_fifo.csv: is a FIFO (named pipe), not a regular file"},
        {"hydro --scene " + c.scene + " --west wall --duration 10 --max-dt 1e-9 --cfl 1 --quiet --out " + c.dir + "/h.nc",
         "--max-dt: 10 s of " + c.scene + " over 3200 cells of 0.16 m (steps of about 1e-09 s) would make 3.2e+13 cell updates"},
        {"hydro --scene " + huge + " --west wall --duration 1 --quiet --out " + c.dir + "/h.nc",
         "huge.nc: variable 'z': 100000 x 200000 would make 2e+10 values"},
        {"sweep --spec " + factorial + " --quiet --out " + c.dir + "/w.nc",
         "factorial.toml: line 8: [parameters] key 'design': a factorial of 1000 (cd1) x 1000 (cd2) x 1000 (cm) levels is 1e+09 "
         "parameter sets, more than 1e6"},
    });
    std::string out;
    EXPECT_EQ(test::run_cli(debris + "--dt-max 1e-12", &out), 1);
    EXPECT_NE(out.find("pass --allow-large-run to run it anyway"), std::string::npos) << out;
    // The override: the same run starts (and is stopped here after 3 s).
    EXPECT_EQ(test::finish_cli(test::start_cli(debris + "--dt-max 1e-12 --allow-large-run --threads 1", "timeout 3"), &out), 124)
        << out;
    EXPECT_EQ(out.find("would make"), std::string::npos) << out;
    // Thousands of threads: capped at the processors (the run finishes, no .part left).
    ASSERT_EQ(test::run_cli("hydro --scene " + c.scene + " --west wall --duration 0.5 --threads 4096 --out " + c.dir + "/t.nc", &out),
              0)
        << out;
    EXPECT_NE(out.find("--threads 4096: capped at "), std::string::npos) << out;
    EXPECT_TRUE(fs::exists(c.dir + "/t.nc"));
    EXPECT_FALSE(fs::exists(c.dir + "/t.nc.part"));
}

// Attributes that change what the numbers mean: lengths, depths, speeds and times in
// other units are converted (the same run as in flotsam's own units), `positive = "down"`
// is honoured, and a unit flotsam cannot convert is refused by name.
TEST(ReliabilityCli, UnitsAreConvertedOrRefusedByName) {
    const SmallCase c = small_case("cli_units");
    const Outputs o = flow_and_sweep(c);
    std::string out;
    const auto debris = [&](const std::string& flow, const std::string& scene, const std::string& out_file) {
        return "debris --flow " + flow + " --scene " + scene + " --start FD --quiet --out " + out_file;
    };
    const std::string ref = c.dir + "/ref.nc";
    ASSERT_EQ(test::run_cli(debris(o.flow, c.scene, ref), &out), 0) << out;
    const std::vector<double> ref_x = all_values(ref, "x"), ref_y = all_values(ref, "y");
    const auto expect_same_tracks = [&](const std::string& file) {
        const std::vector<double> x = all_values(file, "x"), y = all_values(file, "y");
        ASSERT_EQ(x.size(), ref_x.size());
        for (std::size_t k = 0; k < x.size(); ++k) {
            EXPECT_NEAR(x[k], ref_x[k], 1e-4) << file << " sample " << k;
            EXPECT_NEAR(y[k], ref_y[k], 1e-4) << file << " sample " << k;
        }
    };
    // The scene in feet and kilometres, and with z counted downward: the flow's scene still.
    const std::string feet = copy_of(c.scene, c.dir + "/feet.nc");
    scale_values(feet, "z", 1.0 / 0.3048);
    set_text_attribute(feet, "z", "units", "ft");
    const std::string km = copy_of(c.scene, c.dir + "/km.nc");
    for (const char* v : {"x", "y", "point_x", "point_y"}) scale_values(km, v, 1e-3);
    set_text_attribute(km, "x", "units", "km");
    set_text_attribute(km, "y", "units", "km");
    const std::string down = copy_of(c.scene, c.dir + "/down.nc");
    scale_values(down, "z", -1.0);
    set_text_attribute(down, "z", "positive", "down");
    for (const std::string& scene : {feet, km, down}) {
        SCOPED_TRACE(scene);
        ASSERT_EQ(test::run_cli(debris(o.flow, scene, c.dir + "/t.nc"), &out), 0) << out;
        expect_same_tracks(c.dir + "/t.nc");
    }
    // The flow with time in hours, depth in cm, velocity in km/h.
    const std::string hours = copy_of(o.flow, c.dir + "/hours.nc");
    scale_values(hours, "time", 1.0 / 3600.0);
    set_text_attribute(hours, "time", "units", "hours since 2000-01-01 00:00:00");
    const std::string cm = copy_of(o.flow, c.dir + "/cm.nc");
    scale_values(cm, "h", 100.0);
    set_text_attribute(cm, "h", "units", "cm");
    const std::string kmh = copy_of(o.flow, c.dir + "/kmh.nc");
    for (const char* v : {"u", "v"}) {
        scale_values(kmh, v, 3.6);
        set_text_attribute(kmh, v, "units", "km h-1");
    }
    for (const std::string& flow : {hours, cm, kmh}) {
        SCOPED_TRACE(flow);
        ASSERT_EQ(test::run_cli(debris(flow, c.scene, c.dir + "/t.nc"), &out), 0) << out;
        expect_same_tracks(c.dir + "/t.nc");
    }
    // Units no converter knows: refused, naming the file, the variable and the unit.
    const std::string bananas = copy_of(o.flow, c.dir + "/bananas.nc");
    set_text_attribute(bananas, "time", "units", "bananas");
    const std::string furlongs = copy_of(o.flow, c.dir + "/furlongs.nc");
    set_text_attribute(furlongs, "u", "units", "furlongs per fortnight");
    const std::string sideways = copy_of(c.scene, c.dir + "/sideways.nc");
    set_text_attribute(sideways, "z", "positive", "sideways");
    const std::string fathoms = copy_of(c.scene, c.dir + "/fathoms.nc");
    set_text_attribute(fathoms, "z", "units", "fathoms");
    expect_named_errors({
        {debris(bananas, c.scene, c.dir + "/t.nc"),
         "bananas.nc: variable 'time' attribute 'units': 'bananas' is not a unit of time flotsam can convert"},
        {debris(furlongs, c.scene, c.dir + "/t.nc"),
         "furlongs.nc: variable 'u' attribute 'units': 'furlongs per fortnight' is not a unit of speed"},
        {debris(o.flow, sideways, c.dir + "/t.nc"), "sideways.nc: variable 'z' attribute 'positive': 'sideways' is neither 'up' nor 'down'"},
        {debris(o.flow, fathoms, c.dir + "/t.nc"), "fathoms.nc: variable 'z' attribute 'units': 'fathoms' is not a unit of length"},
    });
}

// Values outside physical bounds, fill values, inconsistent tables, files of another kind
// and absurd option values: each a named error (they were taken silently).
TEST(ReliabilityCli, ValuesAndTablesThatMeanNothingAreRefused) {
    const SmallCase c = small_case("cli_silent");
    const Outputs o = flow_and_sweep(c);
    const auto hydro = [&](const std::string& scene) {
        return "hydro --scene " + scene + " --west wall --duration 0.5 --quiet --out " + c.dir + "/h.nc";
    };
    const auto stats = [&](const std::string& sweep) { return "stats --sweep " + sweep + " --out " + c.dir + "/s.nc"; };
    const std::string zfill = copy_of(c.scene, c.dir + "/zfill.nc");
    fuzz::copy_with_value(c.scene, zfill, "z", 100, 9.969209968386869e36);
    const std::string z1e30 = copy_of(c.scene, c.dir + "/z1e30.nc");
    fuzz::copy_with_value(c.scene, z1e30, "z", 100, 1e30);
    const std::string kind = copy_of(c.scene, c.dir + "/kind.nc");
    set_string(kind, "point_kind", 0, "bogus");
    const std::string dup = copy_of(c.scene, c.dir + "/dup.nc");
    set_string(dup, "point_name", 1, Scene(read_scene(c.scene)).points[0].name);
    const std::string empty = copy_of(c.scene, c.dir + "/empty.nc");
    set_string(empty, "point_name", 1, "");
    const std::string section = copy_of(c.scene, c.dir + "/section.nc");
    fuzz::copy_with_value(c.scene, section, "section_y_min", 0, 5.0);
    const std::string all_building = copy_of(c.scene, c.dir + "/all_building.nc");
    set_all(all_building, "building", 1.0);
    const std::string member_twice = c.dir + "/member_twice.nc", member_negative = c.dir + "/member_negative.nc",
                      status = c.dir + "/status.nc";
    fuzz::copy_with_value(o.sweep, member_twice, "member_id", 1, 0);
    fuzz::copy_with_value(o.sweep, member_negative, "member_id", 1, -3);
    fuzz::copy_with_value(o.sweep, status, "status", 2, -1);  // 255 as a signed byte
    const std::string dir = c.dir + "/config_dir";
    fs::create_directories(dir);
    expect_named_errors({
        {hydro(zfill), "zfill.nc: variable 'z': value at flat index 100 is the fill value"},
        {hydro(z1e30), "z1e30.nc: variable 'z': 1e+30 m at cell (i 100, j 0) is outside [-11000, 9000] m"},
        {hydro(kind), "kind.nc: variable 'point_kind': point 0 ('WG1'): kind 'bogus' is neither 'gauge' nor 'start'"},
        {hydro(dup), "dup.nc: variable 'point_name': 'WG1' is the name of entries 0 and 1"},
        {hydro(empty), "empty.nc: variable 'point_name': entry 1 is an empty name"},
        {"stats --sweep " + o.sweep + " --scene " + section + " --out " + c.dir + "/s.nc",
         "section.nc: section 'fd_x1.8': section_y_min 5 m is not below section_y_max"},
        {hydro(all_building), "all_building.nc: variable 'building': every cell is a building"},
        {hydro(o.flow), "--scene " + o.flow + ": is a flow file (written by `flotsam hydro`), not a scene"},
        {"debris --flow " + c.scene + " --at 1,-1,0 --quiet --out " + c.dir + "/d.nc", "scene.nc: is a scene"},
        {stats(o.flow), o.flow + ": is a flow file (written by `flotsam hydro`), not a sweep file"},
        {stats(member_twice), "member_twice.nc: variable 'member_id': member_id 0 is given twice"},
        {stats(member_negative), "member_negative.nc: variable 'member_id': trajectory 1 has member_id -3, outside [0, 4)"},
        {stats(status), "status.nc: variable 'status': trajectory 0, time index 2: -1 is not a combination of the flags"},
        {stats(o.sweep) + " --yaw-bin 1e-300", "--yaw-bin: 1e-300 is outside the allowed range [0.01, 360] degree"},
        {"boundary generate --peak 1e308 --out-dir " + c.dir + "/bc2", "--peak: 1e+308 m: x --froude-scale 1 is a level of 1e+308 m"},
        {"boundary generate --duration 1e-300 --out-dir " + c.dir + "/bc2", "--duration: 1e-300 s: is not longer than --dt (0.1 s)"},
        {"hydro --scene " + c.scene + " --west wall --duration 1e-300 --quiet --out " + c.dir + "/h.nc",
         "--duration: 1e-300 s stores one frame (t = 0) only"},
        {hydro(c.scene) + " --config " + dir, "config_dir: is a directory, not a regular file"},
        {"hydro --scene " + c.scene + " --west wall --duration 0x10 --quiet --out " + c.dir + "/h.nc",
         "--duration: '0x10' is not a decimal number"},
    });
}

// Flows, scenes, statistics and trajectories given together must come from one scene:
// grid, bed, building mask and CRS, in every command that combines them; and what export
// writes must be a map (no all-missing depth, no arrival before the run, no NaN track).
TEST(ReliabilityCli, FilesGivenTogetherAreCheckedAgainstEachOther) {
    const SmallCase c = small_case("cli_together");
    const Outputs o = flow_and_sweep(c);
    std::string out;
    const std::string stats = c.dir + "/stats.nc", traj = c.dir + "/traj.nc";
    ASSERT_EQ(test::run_cli("stats --sweep " + o.sweep + " --out " + stats, &out), 0) << out;
    ASSERT_EQ(test::run_cli("debris --flow " + o.flow + " --scene " + c.scene + " --start FD --quiet --out " + traj, &out), 0) << out;
    // The same bed with one more building cell (cell 0, in the flume's water).
    const std::string mask = copy_of(c.scene, c.dir + "/mask.nc");
    fuzz::copy_with_value(c.scene, mask, "building", 0, 1);
    // Another resolution, and another layout, with their flows.
    const std::string coarse = c.dir + "/coarse.nc", other = c.dir + "/other.nc";
    ASSERT_EQ(test::run_cli("scene generate --resolution 0.32 --out " + coarse, &out), 0) << out;
    ASSERT_EQ(test::run_cli("scene generate --resolution 0.16 --seed 7 --out " + other, &out), 0) << out;
    const std::string hydro = " --west level --west-series " + c.series + " --duration 4 --quiet" + whole_grid + " --out ";
    ASSERT_EQ(test::run_cli("hydro --scene " + coarse + hydro + c.dir + "/coarse_flow.nc", &out), 0) << out;
    ASSERT_EQ(test::run_cli("hydro --scene " + other + hydro + c.dir + "/other_flow.nc", &out), 0) << out;
    const std::string nan_depth = copy_of(o.flow, c.dir + "/nan_depth.nc");
    set_all(nan_depth, "max_depth", std::nan(""));
    const std::string early = copy_of(o.flow, c.dir + "/early.nc");
    fuzz::copy_with_value(o.flow, early, "arrival_time", 10, -5.0);
    const std::string nan_x = copy_of(traj, c.dir + "/nan_x.nc");
    fuzz::copy_with_value(traj, nan_x, "x", 3, std::nan(""));
    const std::string transposed = c.dir + "/transposed.nc";  // drawn as garbage lines before
    fuzz::copy_with_transposed(traj, transposed, "x");
    const std::string flow_index = c.dir + "/flow_index.nc", one_body = c.dir + "/one_body.nc";
    fuzz::copy_with_value(o.sweep, flow_index, "flow_index", 0, 99);
    fuzz::copy_with_dimension(o.sweep, one_body, "body", 1);
    const std::string gis = " --out-dir " + c.dir + "/gis";
    expect_named_errors({
        {"debris --flow " + o.flow + " --scene " + mask + " --start FD --quiet --out " + c.dir + "/d.nc",
         "was not computed on scene " + mask + ": the bed is the same, but the building mask differs"},
        {"stats --sweep " + o.sweep + " --scene " + mask + " --out " + c.dir + "/s.nc", "was run on another scene than " + mask},
        {"export --stats " + stats + " --flow " + c.dir + "/coarse_flow.nc" + gis, "coarse_flow.nc: comes from a scene of 0.32 m cells"},
        {"export --flow " + o.flow + " --flow " + c.dir + "/other_flow.nc" + gis,
         "other_flow.nc: variable 'z': the bed differs from that of " + o.flow},
        {"export --flow " + nan_depth + gis, "nan_depth.nc: variable 'max_depth': missing (NaN or a fill value) at flat index 0"},
        {"export --flow " + early + gis, "early.nc: variable 'arrival_time': -5 at flat index 10 is outside [-1e-06, 4]"},
        {"export --trajectories " + nan_x + gis, "nan_x.nc: variable 'x': trajectory 0, time index 3: nan is not a position"},
        {"export --trajectories " + transposed + gis, "transposed.nc: variable 'x': must have dimensions (trajectory, time)"},
        {"export --trajectories " + flow_index + gis, "flow_index.nc: trajectory 0: body, variant, flow or parameter set not in"},
        {"export --trajectories " + one_body + gis, "one_body.nc: trajectory "},
        {"export --trajectories " + traj + " --flow " + c.dir + "/other_flow.nc" + gis, "comes from another scene than"},
    });
    EXPECT_FALSE(fs::exists(c.dir + "/gis"));  // refused before anything was written
}

// Errors that were there but unclear now name the input and what is wrong.
TEST(ReliabilityCli, ErrorsNameTheInputAndWhatIsWrong) {
    const SmallCase c = small_case("cli_unclear");
    const Outputs o = flow_and_sweep(c);
    std::string out;
    // A byte-order mark before the first key is not part of it.
    const std::string bom = test::write_file(c.dir, "bom.toml", "\xEF\xBB\xBF" "duration = 0.5\nmax-dt = 0\n");
    // A scene recommending a value its option refuses: the scene's attribute is named.
    const std::string defaults = copy_of(c.scene, c.dir + "/defaults.nc");
    set_text_attribute(defaults, "global", "flotsam_hydro_defaults", "max-dt = -1");
    // A header naming time second.
    std::ifstream in(c.series);
    std::string line, csv = "eta,time\n";
    std::getline(in, line);
    while (std::getline(in, line)) csv += line + "\n";
    const std::string swapped = test::write_file(c.dir, "swapped.csv", csv);
    // A sweep part without trajectories (shard 0 of 8 of a 4-member sweep).
    ASSERT_EQ(test::run_cli("sweep --spec " + o.spec + " --shard 0/8 --quiet --out " + c.dir + "/empty.nc", &out), 0) << out;
    expect_named_errors({
        {"hydro --scene " + c.scene + " --west wall --quiet --out " + c.dir + "/h.nc --config " + bom,
         "bom.toml: key 'max-dt': 0 is outside the allowed range (0, inf) s"},
        {"hydro --scene " + defaults + " --west wall --duration 0.5 --quiet --out " + c.dir + "/h.nc",
         "defaults.nc: attribute 'flotsam_hydro_defaults', line 'max-dt = -1': -1 is outside the allowed range (0, inf) s"},
        {"hydro --scene " + c.scene + " --west level --west-series " + swapped + " --duration 1 --quiet --out " + c.dir + "/h.nc",
         "swapped.csv: line 1: header 'eta,time': names time in column 2"},
        {"stats --sweep " + c.dir + "/empty.nc --out " + c.dir + "/s.nc",
         "empty.nc: dimension 'trajectory': the sweep file holds no trajectories (0 members)"},
    });
    EXPECT_EQ(test::run_cli("hydro --scene " + c.scene + " --west wall --quiet --out " + c.dir + "/h.nc --config " + bom, &out), 1);
    EXPECT_EQ(out.find("\xEF\xBB\xBF"), std::string::npos) << out;
}
