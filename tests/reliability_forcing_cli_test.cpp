// Forcing files (another run's outline driving a side, data/boundary_forcing.hpp) through
// the command line: checked for what the side needs before the run starts (docs/reliability.md).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "fuzz/bad_files.hpp"
#include "tests/reliability_cases.hpp"

using namespace flotsam;
using namespace flotsam::test;
namespace fs = std::filesystem;

// The small scene's run writes its outline along the scene's own edges; the same scene
// forced on its west side by it runs. Copies with a depth of -1 m along the whole side
// (used as it was: depths in the flow changed by up to 0.15 m), times shifted by 1e6 s
// (the side was left unforced), a level of 1e5 m (the run blew up blaming the scene's
// ground), a station at y = −1e30 m (left out of the side without a word) and 2000 times
// at 310 stations on a machine of 8 MB (out of memory without a word of the file) are each
// refused naming the file and what is wrong, before any step.
TEST(ReliabilityCli, ForcingFilesAreCheckedForWhatTheSideNeeds) {
    const SmallCase c = small_case("cli_forcing");
    std::string out;
    const std::string outline = c.dir + "/outline.nc";
    ASSERT_EQ(test::run_cli("hydro --scene " + c.scene + " --west level --west-series " + c.series + " --quiet" + whole_grid +
                                " --duration 2 --boundary-output " + outline +
                                " --boundary-box -12.36,8.1,-4,-0.01 --boundary-interval 0.1 --out " + c.dir + "/whole.nc",
                            &out),
              0)
        << out;
    const auto forced = [&](const std::string& file) {
        return "hydro --scene " + c.scene + " --west-forcing " + file + " --nest-ratio 1 --duration 2 --quiet --out " + c.dir + "/f.nc";
    };
    ASSERT_EQ(test::run_cli(forced(outline), &out), 0) << out;
    fs::remove(c.dir + "/f.nc");
    const std::string dry = copy_of(outline, c.dir + "/negative.nc"), late = copy_of(outline, c.dir + "/late.nc"),
                      high = copy_of(outline, c.dir + "/high.nc"), far = copy_of(outline, c.dir + "/far.nc"),
                      long_record = c.dir + "/long.nc";
    fuzz::set_all(dry, "depth", -1.0);
    fuzz::shift_values(late, "time", 1e6);
    fuzz::set_all(high, "eta", 1e5);
    fuzz::set_value(far, "y", 7, -1e30);
    fuzz::copy_with_dimension(outline, long_record, "time", 2000);
    expect_named_errors({
        {forced(dry), "negative.nc: variable 'depth': -1 at time index 0, station 0 is outside [0, 11000] (a water depth: never negative)"},
        {forced(late), "late.nc: time: covers 1e+06 to 1e+06 s, the run 0 to 2 s: they do not overlap"},
        {forced(high), "high.nc: variable 'eta': 100000 at time index 0, station 0 is outside [-11000.9, 10999.1] (a level within "
                       "11000 m of the scene's lowest bed"},
        {forced(far), "far.nc: variable 'y': value -1e+30 m is outside [-1e+08, 1e+08]"},
    });
    EXPECT_EQ(test::finish_cli(test::start_cli(forced(long_record), "FLOTSAM_MEMORY_LIMIT_MB=8"), &out), 1) << out;
    EXPECT_NE(out.find("--west-forcing " + long_record + ": 2000 times at 310 points would make 2.48e+06 values"), std::string::npos)
        << out;
    EXPECT_FALSE(fs::exists(c.dir + "/f.nc"));
    EXPECT_FALSE(fs::exists(c.dir + "/f.nc.part"));
}
