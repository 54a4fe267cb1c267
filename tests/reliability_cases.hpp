// What the command-line reliability tests share (tests/reliability_*_cli_test.cpp): a
// small scene with a boundary record, a flow and a sweep on it, copies of files to make
// bad, and the check that a command fails with a named error.
#pragma once
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "common/netcdf.hpp"
#include "tests/test_support.hpp"

namespace flotsam::test {

// The scene's whole grid, stored, on one uniform grid (not the Kainan scene's recommended
// window and nesting), so that flow cells are scene cells.
inline const std::string whole_grid = " --nest-ratio 1 --output-window -100,100,-100,100";

inline std::string hydro_args(const SmallCase& c, const std::string& out) {
    return "hydro --scene " + c.scene + " --west level --west-series " + c.series +
           " --duration 6 --output-interval 0.5 --quiet --out " + out;
}

// A flow and a sweep (with the spec) on the small case.
struct Outputs {
    std::string flow, sweep, spec;
};
inline Outputs flow_and_sweep(const SmallCase& c) {
    Outputs o{c.dir + "/flow.nc", c.dir + "/sweep.nc", c.dir + "/spec.toml"};
    std::string out;
    EXPECT_EQ(run_cli("hydro --scene " + c.scene + " --west level --west-series " + c.series + " --duration 4 --quiet" +
                          whole_grid + " --out " + o.flow,
                      &out),
              0)
        << out;
    const std::string spec = write_file(c.dir, "spec.toml",
                                        "[sweep]\nscene = \"" + c.scene + "\"\n[flows]\npaths = [\"" + o.flow +
                                            "\"]\n[[body]]\nstart = \"FD\"\n[[body]]\nstart = \"LD\"\n"
                                            "[variants]\nnames = [\"CC+SC\", \"LC+MC\"]\n");
    EXPECT_EQ(run_cli("sweep --spec " + spec + " --quiet --out " + o.sweep, &out), 0) << out;
    return o;
}

// A copy of a file, to make bad (fuzz/bad_files.hpp edits it in place).
inline std::string copy_of(const std::string& from, const std::string& to) {
    std::filesystem::copy_file(from, to, std::filesystem::copy_options::overwrite_existing);
    return to;
}

inline std::vector<double> all_values(const std::string& path, const std::string& var) {
    const nc::File f = nc::File::open_read(path);
    return f.get_double(f.var(var));
}

// The pid a run wrote into the lock file of its output ("pid N on HOST"), once written;
// 0 if none appears within `seconds`.
inline pid_t lock_holder(const std::string& out, double seconds) {
    for (int k = 0; k < int(seconds * 100); ++k) {
        std::ifstream in(out + ".lock");
        std::string word;
        long pid = 0;
        if (in >> word >> pid && word == "pid" && pid > 0) return pid_t(pid);
        ::usleep(10000);
    }
    return 0;
}

// Runs a pipeline module (`/usr/bin/python3 -m pipelines.<module> <args>` in the source
// tree); its exit status, stdout+stderr in *output.
inline int run_pipeline(const std::string& module_and_args, std::string* output = nullptr) {
    FILE* p = ::popen(("cd " FLOTSAM_SOURCE_DIR " && /usr/bin/python3 -m pipelines." + module_and_args + " 2>&1").c_str(), "r");
    return finish_cli(p, output);
}

struct Case {
    std::string args, expect;
};

// Each command fails (exit 1, not a crash) with `expect` in its output, never an internal error.
inline void expect_named_errors(const std::vector<Case>& cases) {
    std::string out;
    for (const auto& k : cases) {
        const int rc = run_cli(k.args, &out);
        EXPECT_TRUE(rc == 1 || rc == 105) << "rc " << rc << ": " << k.args << "\n" << out;  // 105: CLI11's parse errors
        EXPECT_NE(out.find(k.expect), std::string::npos) << k.args << "\n" << out;
        EXPECT_EQ(out.find("internal error"), std::string::npos) << out;
    }
}

}  // namespace flotsam::test
