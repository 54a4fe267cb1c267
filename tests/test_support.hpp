// Helpers shared by the tests: scratch directories, the shared data folder, the CLI.
#pragma once
#include <cstdio>
#include <functional>
#include <string>

namespace flotsam::test {

// A fresh, empty directory under the build tree's scratch area, named after the test.
std::string scratch_dir(const std::string& name);
// ../shared/data/<file> beside the source tree (or $FLOTSAM_SHARED/data/<file>); empty
// string when it is not there.
std::string shared_data(const std::string& file);
// Runs the flotsam binary with `args`; returns its exit status; stdout+stderr in *output.
int run_cli(const std::string& args, std::string* output = nullptr);
// The same in two halves: starts it in the background (with `env`, "NAME=value ...",
// before the command), then waits for it.
FILE* start_cli(const std::string& args, const std::string& env = "");
int finish_cli(FILE* running, std::string* output = nullptr);
// The message of the flotsam::Error that f throws, or "(no error)".
std::string error_of(const std::function<void()>& f);
// Writes `text` to dir/name and returns the path.
std::string write_file(const std::string& dir, const std::string& name, const std::string& text);
// The whole of a file's bytes ("" when it cannot be read).
std::string read_text(const std::string& path);
// Overwrites 16 bytes in the middle of the stored chunk of (time, y, x) variable `var`
// that holds frame `frame`, cells from (0, 0): its data no longer decode, the file's
// structure still reads.
void damage_chunk(const std::string& path, const std::string& var, std::size_t frame);

// A generated scene at 0.16 m (128 x 25 cells) and a 30 s boundary record in a fresh
// scratch directory: a hydro run of a few seconds on it takes well under a second.
struct SmallCase {
    std::string dir, scene, series;  // the directory, dir/scene.nc, dir/bc/wg1_r00.csv
};
SmallCase small_case(const std::string& name);

}  // namespace flotsam::test
