// Options, settings files and the work they ask for, through the command line: finite
// numbers in range or a named error, every run bounded before it starts (docs/reliability.md).
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
    // A factorial at the limit of sets (1000 x 1000) whose work passes the bound: refused by
    // its count, before its million members are built (that took 27 s and 3.2 GB).
    std::string small_levels;  // 0.01 ... 10: within the coefficients' ranges
    for (int k = 1; k <= 1000; ++k) small_levels += (k > 1 ? "," : "") + std::to_string(0.01 * k);
    const std::string million = test::write_file(c.dir, "million.toml",
                                                 "[sweep]\nscene = \"" + c.scene + "\"\ndt-max = 1e-4\n[flows]\npaths = [\"" + o.flow +
                                                     "\"]\n[[body]]\nstart = \"FD\"\n[parameters]\ndesign = \"factorial\"\ncd1 = [" +
                                                     small_levels + "]\ncd2 = [" + small_levels + "]\n");
    EXPECT_EQ(test::run_cli("sweep --spec " + million + " --quiet --out " + c.dir + "/w.nc", &out), 1);
    EXPECT_NE(out.find("for 1e+06 bodies would make 4e+10 body steps, more than the 1e+10"), std::string::npos) << out;
    // Thousands of threads: capped at the processors (the run finishes, no .part left).
    ASSERT_EQ(test::run_cli("hydro --scene " + c.scene + " --west wall --duration 0.5 --threads 4096 --out " + c.dir + "/t.nc", &out),
              0)
        << out;
    EXPECT_NE(out.find("--threads 4096: capped at "), std::string::npos) << out;
    EXPECT_TRUE(fs::exists(c.dir + "/t.nc"));
    EXPECT_FALSE(fs::exists(c.dir + "/t.nc.part"));
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
    fuzz::set_text_attribute(defaults, "global", "flotsam_hydro_defaults", "max-dt = -1");
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
