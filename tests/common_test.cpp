#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "common/error.hpp"
#include "common/netcdf.hpp"
#include "common/sha256.hpp"
#include "common/timeseries.hpp"
#include "formats/scene.hpp"
#include "tests/test_support.hpp"

using namespace flotsam;
using test::error_of;
using test::write_file;

TEST(Sha256, KnownVectors) {
    EXPECT_EQ(sha256_hex(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
    EXPECT_EQ(sha256_hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
    EXPECT_EQ(sha256_hex(std::string(1000, 'a')), "41edece42d63e8d9bf515a9ba6932e1c20cbc9f5a5d134645adb5db1b9737ea3");
}

namespace {}  // namespace

TEST(TimeSeries, ReadsAndInterpolates) {
    const auto dir = test::scratch_dir("ts");
    const auto p = write_file(dir, "ok.csv", "time,eta\n0,0\n1,0.1\n# comment\n2,0.3\n");
    const TimeSeries s = read_time_series_csv(p);
    ASSERT_EQ(s.time.size(), 3u);
    EXPECT_DOUBLE_EQ(s.at(0.5), 0.05);
    EXPECT_DOUBLE_EQ(s.at(1.5), 0.2);
    EXPECT_NE(error_of([&] { require_coverage(s, 0, 3); }).find("covers [0"), std::string::npos);
}

TEST(TimeSeries, BadFilesNameFileAndLine) {
    const auto dir = test::scratch_dir("tsbad");
    auto msg = error_of([&] { read_time_series_csv(write_file(dir, "a.csv", "time,eta\n0,0\n1,0.1\n1,0.2\n")); });
    EXPECT_NE(msg.find("a.csv: line 4: time 1"), std::string::npos) << msg;
    msg = error_of([&] { read_time_series_csv(write_file(dir, "b.csv", "0,0\n1,nan\n")); });
    EXPECT_NE(msg.find("b.csv: line 2"), std::string::npos) << msg;
    msg = error_of([&] { read_time_series_csv(write_file(dir, "c.csv", "0,0\n1,x\n")); });
    EXPECT_NE(msg.find("c.csv: line 2: not a number"), std::string::npos) << msg;
    msg = error_of([&] { read_time_series_csv(write_file(dir, "d.csv", "0,0\n100,1\n"), 10.0); });
    EXPECT_NE(msg.find("d.csv: line 2: gap"), std::string::npos) << msg;
    msg = error_of([&] { read_time_series_csv(write_file(dir, "e.csv", "0,0,1\n")); });
    EXPECT_NE(msg.find("e.csv: line 1: expected 2"), std::string::npos) << msg;
}

TEST(Scene, RoundTripAndErrors) {
    const auto dir = test::scratch_dir("scene");
    Scene s;
    s.grid = Grid{4, 3, -1.0, 2.0, 0.5, 0.25};
    s.z = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11};
    s.manning_n.assign(12, 0.013);
    s.building.assign(12, 0);
    s.building[5] = 1;
    s.points.push_back({"WG1", "gauge", -0.5, 2.1, 0.0});
    s.sections.push_back({"S1", 0.0, 2.0, 2.5});
    s.regions.push_back({"box", {{-1, 2}, {0, 2}, {0, 3}, {-1, 3}}});
    s.title = "test";
    s.synthetic = true;
    write_scene(dir + "/s.nc", s, "test");
    const Scene r = read_scene(dir + "/s.nc");
    EXPECT_EQ(r.grid.nx, 4);
    EXPECT_EQ(r.grid.ny, 3);
    EXPECT_DOUBLE_EQ(r.grid.dy, 0.25);
    EXPECT_DOUBLE_EQ(r.z[7], 7.0);
    EXPECT_EQ(r.building[5], 1);
    ASSERT_EQ(r.points.size(), 1u);
    EXPECT_EQ(r.points[0].name, "WG1");
    ASSERT_EQ(r.regions.size(), 1u);
    EXPECT_TRUE(r.regions[0].contains(-0.5, 2.5));
    EXPECT_FALSE(r.regions[0].contains(0.5, 2.5));
    EXPECT_TRUE(r.synthetic);
    EXPECT_NE(error_of([&] { read_scene(dir + "/missing.nc"); }).find("missing.nc"), std::string::npos);
}

// A file whose structure passed the probe is not probed again while unchanged (and still
// for more than 2 s), but one just written or replaced at the same path is: here by a copy
// that makes libhdf5 itself crash (docs/reliability.md), which must still come back as a
// named error, never a crash.
TEST(NetcdfProbe, AFileReplacedAfterItsProbeIsProbedAgain) {
    const auto dir = test::scratch_dir("nc_probe");
    Scene s;
    s.grid = Grid{4, 3, 0.0, 0.0, 1.0, 1.0};
    s.z.assign(12, 0.0);
    const std::string path = dir + "/f.nc";
    write_scene(path, s, "test");
    for (int k = 0; k < 2; ++k) EXPECT_EQ(read_scene(path).grid.nx, 4);  // just written: probed each time
    std::filesystem::copy_file(std::string(FLOTSAM_SOURCE_DIR) + "/tests/data/corrupt/flow_libhdf5_segfault.nc", path,
                               std::filesystem::copy_options::overwrite_existing);
    const std::string msg = error_of([&] { nc::File::open_read(path); });
    EXPECT_NE(msg.find("f.nc: corrupted: libhdf5 crashed "), std::string::npos) << msg;
}

// A character array whose string dimension has length 0 still holds one (empty) string per
// row: a table's column then has as many entries as the table (the scene fuzzer found a
// point_kind of 0 characters read as no kinds at all, and point k's kind read past the end).
TEST(Netcdf, ACharacterArrayOfEmptyStringsHasItsRows) {
    const auto dir = test::scratch_dir("nc_empty_strings");
    const std::string path = dir + "/e.nc";
    {
        nc::File f = nc::File::create(path);
        const int dp = f.def_dim("point", 3), ds = f.def_dim("point_kind_strlen", 0);
        f.def_var("point_kind", NC_CHAR, {dp, ds});
        f.enddef();
        f.close();
    }
    const nc::File f = nc::File::open_read(path);
    const std::vector<std::string> kinds = f.get_strings(f.var("point_kind"));
    ASSERT_EQ(kinds.size(), 3u);
    for (const auto& k : kinds) EXPECT_EQ(k, "");
}
