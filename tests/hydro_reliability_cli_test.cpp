// Hydro runs that go wrong, through the command line as a user runs them: a damaged
// checkpoint, a disk that fills while checkpoints are written, and outputs too large to
// start. Each test runs the built `flotsam` binary on a small generated scene.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <vector>

#include "common/netcdf.hpp"
#include "common/sha256.hpp"
#include "tests/test_support.hpp"

using namespace flotsam;
namespace fs = std::filesystem;

namespace {

using test::SmallCase;
using test::small_case;

std::string hydro_args(const SmallCase& c, const std::string& out, const std::string& more = "") {
    return "hydro --scene " + c.scene + " --west level --west-series " + c.series + " --duration 6 --output-interval 0.5 --quiet " +
           more + " --out " + out;
}

std::vector<char> bytes_of(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}

void write_bytes(const std::string& path, const std::vector<char>& b) {
    std::ofstream f(path, std::ios::binary | std::ios::trunc);
    f.write(b.data(), std::streamsize(b.size()));
}

// A tmpfs of `kb` kilobytes at `dir`, unmounted when it goes; none where mounting is not
// permitted (not root).
struct TinyDisk {
    std::string dir;
    bool mounted = false;
    TinyDisk(const std::string& d, int kb) : dir(d) {
        fs::create_directories(dir);
        mounted = std::system(("mount -t tmpfs -o size=" + std::to_string(kb) + "k tmpfs " + dir + " 2>/dev/null").c_str()) == 0;
    }
    bool grow(int kb) const { return std::system(("mount -o remount,size=" + std::to_string(kb) + "k " + dir).c_str()) == 0; }
    ~TinyDisk() {
        if (mounted) (void)std::system(("umount " + dir).c_str());
    }
};

}  // namespace

// A checkpoint changed after it was written (one value of the state, or any byte of the
// file) is refused by name, or, where the change hit bytes that hold nothing, continues
// to the bytes of an uninterrupted run; the partial output and the checkpoint are kept.
TEST(HydroCheckpoint, ADamagedCheckpointIsRefusedByNameOrContinuesToTheSameBytes) {
    const SmallCase c = small_case("hydro_damaged_checkpoint");
    std::string out;
    const std::string ref = c.dir + "/ref.nc", f = c.dir + "/f.nc", ckpt = f + ".checkpoint.nc";
    ASSERT_EQ(test::run_cli(hydro_args(c, ref), &out), 0) << out;
    ASSERT_EQ(test::run_cli(hydro_args(c, f, "--checkpoint-interval 1 --stop-after 2.5"), &out), 0) << out;
    const std::vector<char> good_ckpt = bytes_of(ckpt), good_part = bytes_of(f + ".part");
    auto restart = [&](const std::vector<char>& checkpoint) {
        fs::remove(f);
        write_bytes(ckpt, checkpoint);
        write_bytes(f + ".part", good_part);
        return test::run_cli(hydro_args(c, f, "--restart"), &out);
    };
    // One depth of the state, rewritten through the NetCDF library (a valid file).
    {
        std::vector<char> copy = good_ckpt;
        write_bytes(c.dir + "/edit.nc", copy);
        nc::File e = nc::File::open_write(c.dir + "/edit.nc");
        const int v = e.var("state_0");
        std::vector<double> h = e.get_double(v);
        h[h.size() / 2] += 1e-3;
        e.put(v, h);
        e.close();
        EXPECT_EQ(restart(bytes_of(c.dir + "/edit.nc")), 1) << out;
        EXPECT_NE(out.find(ckpt + ": attribute 'state_sha256': does not match what the checkpoint holds: the file is damaged"),
                  std::string::npos)
            << out;
        EXPECT_NE(out.find("remove " + ckpt + " and " + f + ".part to start afresh"), std::string::npos) << out;
        EXPECT_TRUE(fs::exists(f + ".part"));
        EXPECT_TRUE(fs::exists(ckpt));
        EXPECT_FALSE(fs::exists(f));
    }
    // Bytes spread over the file, one at a time: a named error naming the checkpoint, or
    // (padding, unused space) the uninterrupted run's bytes. Never rc 0 with other bytes.
    int refused = 0;
    for (int k = 1; k <= 30; ++k) {
        std::vector<char> bad = good_ckpt;
        const std::size_t at = bad.size() * std::size_t(k) / 31;
        bad[at] = char(bad[at] ^ 0x5a);
        const int rc = restart(bad);
        if (rc == 0) {
            EXPECT_EQ(sha256_file(f), sha256_file(ref)) << "byte " << at << " changed, the restart gave other bytes";
        } else {
            ++refused;
            EXPECT_EQ(rc, 1) << "byte " << at << ": " << out;
            EXPECT_NE(out.find(ckpt), std::string::npos) << "byte " << at << ": " << out;
        }
    }
    EXPECT_GT(refused, 10);
    // The intact checkpoint still continues to the same bytes.
    ASSERT_EQ(restart(good_ckpt), 0) << out;
    EXPECT_EQ(sha256_file(f), sha256_file(ref));
}

// The values of every variable of a flow file, by name.
std::vector<std::vector<double>> values_of(const std::string& path) {
    const nc::File f = nc::File::open_read(path);
    std::vector<std::vector<double>> v;
    for (const char* name : {"h", "u", "v", "max_depth", "max_speed", "arrival_time", "gauge_eta", "gauge_u", "flooded"})
        v.push_back(f.get_double(f.var(name)));
    return v;
}

// A disk that fills after the first checkpoints (at a frame, or while a checkpoint is
// written): the run ends with a named error that says the disk is full and what is kept;
// the checkpoint and the partial output it continues stay, and once there is room
// --restart finishes the run to the values of one that never stopped (HDF5 lays the file
// out a few kB larger after a write that failed).
TEST(HydroCheckpoint, AFullDiskKeepsTheCheckpointAndItsPartialOutputForRestart) {
    const SmallCase c = small_case("hydro_full_disk_checkpoint");
    std::string out;
    const std::string more = "--checkpoint-interval 1 --deflate 0";
    const std::string ref = c.dir + "/ref.nc";
    ASSERT_EQ(test::run_cli(hydro_args(c, ref, more), &out), 0) << out;
    const auto reference = values_of(ref);
    const TinyDisk disk(c.dir + "/tiny", 400);
    if (!disk.mounted) GTEST_SKIP() << "mounting a tmpfs is not permitted here (needs root)";
    const std::string f = disk.dir + "/f.nc", ckpt = f + ".checkpoint.nc";
    // Fillers that leave room for the first frames and checkpoint: the disk fills at a
    // later checkpoint (110 kB) or at a frame (170 kB).
    for (const char* filler_kb : {"110", "170"}) {
        ASSERT_TRUE(disk.grow(400));
        EXPECT_EQ(std::system(("dd if=/dev/zero of=" + disk.dir + "/filler bs=1k count=" + filler_kb + " 2>/dev/null").c_str()), 0);
        EXPECT_EQ(test::run_cli(hydro_args(c, f, more), &out), 1) << out;
        EXPECT_NE(out.find("No space left on device"), std::string::npos) << out;
        EXPECT_NE(out.find(" s is kept in " + ckpt + " and " + f + ".part: continue it with the same command and --restart"),
                  std::string::npos)
            << filler_kb << ": " << out;
        ASSERT_TRUE(fs::exists(ckpt)) << out;
        ASSERT_TRUE(fs::exists(f + ".part"));
        EXPECT_FALSE(fs::exists(f));
        // Room again: the restart finishes it.
        fs::remove(disk.dir + "/filler");
        ASSERT_TRUE(disk.grow(2048));
        ASSERT_EQ(test::run_cli(hydro_args(c, f, more + " --restart"), &out), 0) << out;
        EXPECT_EQ(values_of(f), reference) << filler_kb;
        EXPECT_FALSE(fs::exists(ckpt));
        fs::remove(f);
    }
}

// What a run writes is estimated before it starts: frames every microsecond, a boundary
// outline every nanosecond, every 1e-7 s over 30 s or every 1e-5 s over 420 s are refused
// naming the option and the estimate, and --allow-large-run starts them.
TEST(HydroWorkEstimate, OutputAndBoundaryIntervalsAreEstimatedBeforeTheRunStarts) {
    const SmallCase c = small_case("hydro_output_estimate");
    const std::string run = "hydro --scene " + c.scene + " --west level --west-series " + c.series + " --quiet --out " + c.dir + "/h.nc ";
    const std::string outline = " --boundary-output " + c.dir + "/b.nc --boundary-box 0,4,-3,-1";
    struct Case {
        std::string args, message;
    };
    for (const Case& k : std::vector<Case>{
             {run + "--duration 4 --output-interval 1e-6",
              "--output-interval: 4e+06 frames of 1425 cells over 4 s would make 6.84e+10 bytes written"},
             {run + "--duration 4" + outline + " --boundary-interval 1e-9", "--boundary-interval: "},
             {run + "--duration 30" + outline + " --boundary-interval 1e-7", "--boundary-interval: "},
             {run + "--duration 420 --west-series-end transmissive" + outline + " --boundary-interval 1e-5",
              "--boundary-interval: 79 outline stations every 1e-05 s over 420 s would make 6.64e+10 bytes written"},
         }) {
        std::string out;
        EXPECT_EQ(test::run_cli(k.args, &out), 1) << k.args;
        EXPECT_NE(out.find(k.message), std::string::npos) << out;
        EXPECT_NE(out.find("pass --allow-large-run to run it anyway"), std::string::npos) << out;
        EXPECT_FALSE(fs::exists(c.dir + "/h.nc.part"));
        EXPECT_FALSE(fs::exists(c.dir + "/b.nc.part"));
    }
    // The override: the same run starts (and is stopped here after 2 s).
    std::string out;
    EXPECT_EQ(test::finish_cli(test::start_cli(run + "--duration 4 --output-interval 1e-6 --allow-large-run --threads 1", "timeout 2"),
                               &out),
              124)
        << out;
    EXPECT_EQ(out.find("would make"), std::string::npos) << out;
}
