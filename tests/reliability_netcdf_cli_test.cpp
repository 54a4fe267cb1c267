// Scenes and flows through the command line: tables, values, units and attributes checked
// as they are read, and files that crash libhdf5 named instead (docs/reliability.md).
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
    fuzz::scale_values(feet, "z", 1.0 / 0.3048);
    fuzz::set_text_attribute(feet, "z", "units", "ft");
    const std::string km = copy_of(c.scene, c.dir + "/km.nc");
    for (const char* v : {"x", "y", "point_x", "point_y"}) fuzz::scale_values(km, v, 1e-3);
    fuzz::set_text_attribute(km, "x", "units", "km");
    fuzz::set_text_attribute(km, "y", "units", "km");
    const std::string down = copy_of(c.scene, c.dir + "/down.nc");
    fuzz::scale_values(down, "z", -1.0);
    fuzz::set_text_attribute(down, "z", "positive", "down");
    for (const std::string& scene : {feet, km, down}) {
        SCOPED_TRACE(scene);
        ASSERT_EQ(test::run_cli(debris(o.flow, scene, c.dir + "/t.nc"), &out), 0) << out;
        expect_same_tracks(c.dir + "/t.nc");
    }
    // The flow with time in hours, depth in cm, velocity in km/h.
    const std::string hours = copy_of(o.flow, c.dir + "/hours.nc");
    fuzz::scale_values(hours, "time", 1.0 / 3600.0);
    fuzz::set_text_attribute(hours, "time", "units", "hours since 2000-01-01 00:00:00");
    const std::string cm = copy_of(o.flow, c.dir + "/cm.nc");
    fuzz::scale_values(cm, "h", 100.0);
    fuzz::set_text_attribute(cm, "h", "units", "cm");
    const std::string kmh = copy_of(o.flow, c.dir + "/kmh.nc");
    for (const char* v : {"u", "v"}) {
        fuzz::scale_values(kmh, v, 3.6);
        fuzz::set_text_attribute(kmh, v, "units", "km h-1");
    }
    for (const std::string& flow : {hours, cm, kmh}) {
        SCOPED_TRACE(flow);
        ASSERT_EQ(test::run_cli(debris(flow, c.scene, c.dir + "/t.nc"), &out), 0) << out;
        expect_same_tracks(c.dir + "/t.nc");
    }
    // Units no converter knows: refused, naming the file, the variable and the unit.
    const std::string bananas = copy_of(o.flow, c.dir + "/bananas.nc");
    fuzz::set_text_attribute(bananas, "time", "units", "bananas");
    const std::string furlongs = copy_of(o.flow, c.dir + "/furlongs.nc");
    fuzz::set_text_attribute(furlongs, "u", "units", "furlongs per fortnight");
    const std::string sideways = copy_of(c.scene, c.dir + "/sideways.nc");
    fuzz::set_text_attribute(sideways, "z", "positive", "sideways");
    const std::string fathoms = copy_of(c.scene, c.dir + "/fathoms.nc");
    fuzz::set_text_attribute(fathoms, "z", "units", "fathoms");
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
    fuzz::set_string(kind, "point_kind", 0, "bogus");
    const std::string dup = copy_of(c.scene, c.dir + "/dup.nc");
    fuzz::set_string(dup, "point_name", 1, Scene(read_scene(c.scene)).points[0].name);
    const std::string empty = copy_of(c.scene, c.dir + "/empty.nc");
    fuzz::set_string(empty, "point_name", 1, "");
    const std::string section = copy_of(c.scene, c.dir + "/section.nc");
    fuzz::copy_with_value(c.scene, section, "section_y_min", 0, 5.0);
    const std::string all_building = copy_of(c.scene, c.dir + "/all_building.nc");
    fuzz::set_all(all_building, "building", 1.0);
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

// An attribute that is there but cannot be read is an error, never "absent": a scene whose
// attribute messages were damaged (ncdump fails on it: "Can't open HDF5 attribute") ran
// without its recommended nesting and window, other physics without a word; and one of
// the other kind (a number where text is read) is named too.
TEST(ReliabilityCli, AnAttributeThatCannotBeReadIsAnErrorNotAbsent) {
    const SmallCase c = small_case("cli_attributes");
    std::string bytes = test::read_text(c.scene);
    const std::size_t at = bytes.find("flotsam_hydro_defaults");
    ASSERT_NE(at, std::string::npos);
    bytes[at - 40] = char(0xff);  // the attribute message's header
    const std::string damaged = test::write_file(c.dir, "damaged.nc", bytes);
    const std::string number = copy_of(c.scene, c.dir + "/number.nc");
    fuzz::set_number_attribute(number, "global", "flotsam_hydro_defaults", 4.0);
    const std::string hydro = " --west wall --duration 0.2 --quiet --out " + c.dir + "/h.nc";
    expect_named_errors({
        {"hydro --scene " + damaged + hydro, "damaged.nc: global attribute '"},
        {"hydro --scene " + number + hydro, "number.nc: global attribute 'flotsam_hydro_defaults': is a number, where text is expected"},
    });
    std::string out;
    EXPECT_EQ(test::run_cli("hydro --scene " + damaged + hydro, &out), 1);
    EXPECT_NE(out.find("cannot be read (NetCDF: Can't open HDF5 attribute): the file's attributes are damaged"), std::string::npos) << out;
    EXPECT_FALSE(fs::exists(c.dir + "/h.nc"));
}
