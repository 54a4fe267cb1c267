// Outputs through the command line: one writer per output, no output over an input
// (or a file written into an output folder over one), outputs that are files, a full
// disk named (docs/reliability.md).
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
#include "data/gdal_support.hpp"
#include "formats/scene.hpp"
#include "fuzz/bad_files.hpp"
#include "tests/reliability_cases.hpp"

using namespace flotsam;
using namespace flotsam::test;
namespace fs = std::filesystem;

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
    // Files a command writes into an output folder, and its second outputs, are outputs too:
    // a GIS layer given as --sources and as --out or --impacts, a sweep file called
    // members.csv in the folder of `stats --csv`, a flow called max_depth.tif in the
    // folder of `export --out-dir`, a sweep called hazard_regions.nc in the folder of
    // hazard_region.py.
    const Scene scene = read_scene(c.scene);
    const ScenePoint* fd = scene.find_point("FD");
    ASSERT_NE(fd, nullptr);
    gdal::init();
    const std::string gpkg = c.dir + "/sources.gpkg";
    {
        gdal::Dataset ds(GetGDALDriverManager()->GetDriverByName("GPKG")->Create(gpkg.c_str(), 0, 0, 0, GDT_Unknown, nullptr));
        OGRLayer* layer = ds->CreateLayer("sources", nullptr, wkbPoint, nullptr);
        OGRFieldDefn type("type", OFTString);
        layer->CreateField(&type);
        OGRFeature f(layer->GetLayerDefn());
        f.SetField("type", "paper_box");
        OGRPoint at(fd->x, fd->y);
        f.SetGeometry(&at);
        ASSERT_EQ(layer->CreateFeature(&f), OGRERR_NONE);
    }
    fs::create_directories(c.dir + "/tables");
    fs::create_directories(c.dir + "/gis");
    fs::create_directories(c.dir + "/hazard");
    copy_of(c.dir + "/sweep.nc", c.dir + "/tables/members.csv");
    copy_of(c.dir + "/flow.nc", c.dir + "/gis/max_depth.tif");
    copy_of(c.dir + "/sweep.nc", c.dir + "/hazard/hazard_regions.nc");
    const std::string debris = "debris --flow " + c.dir + "/flow.nc --scene " + c.scene + " --sources " + gpkg + " --quiet ";
    const std::vector<test::Case> into_folders = {
        {debris + "--out " + gpkg, gpkg},
        {debris + "--out " + c.dir + "/d.nc --impacts " + gpkg, gpkg},
        {"stats --sweep " + c.dir + "/tables/members.csv --out " + c.dir + "/s.nc --csv " + c.dir + "/tables",
         c.dir + "/tables/members.csv"},
        {"export --flow " + c.dir + "/gis/max_depth.tif --out-dir " + c.dir + "/gis", c.dir + "/gis/max_depth.tif"},
    };
    for (const auto& k : into_folders) {
        const std::string before = sha256_file(k.expect);
        EXPECT_EQ(test::run_cli(k.args, &out), 1) << k.args << "\n" << out;
        EXPECT_NE(out.find(k.expect + ": is the input given as "), std::string::npos) << k.args << "\n" << out;
        EXPECT_EQ(sha256_file(k.expect), before) << k.args;
    }
    const std::string hazard = c.dir + "/hazard/hazard_regions.nc", before = sha256_file(hazard);
    EXPECT_EQ(run_pipeline("hazard_region --sweep " + hazard + " --scene " + c.scene + " --out " + c.dir + "/hazard --no-charts", &out), 1)
        << out;
    EXPECT_NE(out.find("--out: " + hazard + ": is the input given as --sweep"), std::string::npos) << out;
    EXPECT_EQ(sha256_file(hazard), before);
    // The summary of a sweep is an output too: never the main output.
    EXPECT_NE(test::run_cli("sweep --spec " + spec + " --quiet --out " + c.dir + "/o.nc --summary " + c.dir + "/o.nc", &out), 0);
    EXPECT_NE(out.find("is also the output given as --out"), std::string::npos) << out;
    EXPECT_FALSE(fs::exists(c.dir + "/o.nc"));
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
    // Every other writing command on the full file system: named, exit 1, nothing that
    // looks finished (export said "no such table: gpkg_geometry_columns").
    const Outputs o = flow_and_sweep(c);
    ASSERT_EQ(test::run_cli("stats --sweep " + o.sweep + " --out " + c.dir + "/stats.nc", &out), 0) << out;
    (void)std::system(("dd if=/dev/zero of=" + mnt + "/filler2 bs=1k 2>/dev/null").c_str());  // until full
    const std::string debris = "debris --flow " + o.flow + " --scene " + c.scene + " --start FD --quiet ";
    const std::vector<std::pair<std::string, std::string>> commands = {
        {debris + "--out " + mnt + "/d.nc", mnt + "/d.nc"},
        {"sweep --spec " + o.spec + " --quiet --out " + mnt + "/w.nc", mnt + "/w.nc"},
        {"sweep merge " + o.sweep + " --out " + mnt + "/m.nc", mnt + "/m.nc"},
        {"stats --sweep " + o.sweep + " --out " + mnt + "/s.nc", mnt + "/s.nc"},
        {"stats --sweep " + o.sweep + " --out " + c.dir + "/s2.nc --csv " + mnt + "/tables", mnt + "/tables/members.csv"},
        {"export --stats " + c.dir + "/stats.nc --out-dir " + mnt + "/gis", mnt + "/gis/pass_probability_all.tif"},
        {"export --trajectories " + o.sweep + " --out-dir " + mnt + "/gis", mnt + "/gis/sweep_tracks.gpkg"},
        {"export --stats " + c.dir + "/stats.nc --scene " + c.scene + " --out-dir " + mnt + "/gis", mnt + "/gis/buildings.gpkg"},
        {"boundary generate --count 1 --duration 30 --out-dir " + mnt + "/bc", mnt + "/bc/wg1_r00.csv"},
        {"scene import --dem " + c.scene + " --resolution 0.32 --out " + mnt + "/i.nc", mnt + "/i.nc"},
    };
    for (const auto& [cmd, file] : commands) {
        EXPECT_EQ(test::run_cli(cmd, &out), 1) << cmd << "\n" << out;
        EXPECT_NE(out.find("No space left on device"), std::string::npos) << cmd << "\n" << out;
        EXPECT_FALSE(fs::exists(file)) << cmd;
    }
}
