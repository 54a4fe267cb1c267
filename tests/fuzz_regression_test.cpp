// Every input the fuzzers found that crashed or hung a reader (tests/data/fuzz/<target>/,
// one file per input, named after what it caught), replayed through the same target
// functions; plus 25 deterministic pseudo-random inputs per target, so a
// reader that crashes on easy cases fails here before anyone runs `make fuzz`.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>

#include "fuzz/targets.hpp"
#include "sweep/spec_file.hpp"

using namespace flotsam;

// The committed inputs, counted per target: a folder gone missing or emptied (a checkout
// without tests/data) fails here instead of replaying nothing; a new input is counted in.
TEST(FuzzRegression, CommittedInputsGiveNamedErrorsOrResults) {
    const std::filesystem::path root = std::filesystem::path(FLOTSAM_SOURCE_DIR) / "tests" / "data" / "fuzz";
    const std::map<std::string, int> committed = {{"flow", 1}, {"scene", 3}, {"sweep", 1}};
    std::map<std::string, int> replayed;
    for (const auto& t : fuzz::targets()) {
        const auto dir = root / t.name;
        if (!std::filesystem::exists(dir)) continue;
        for (const auto& e : std::filesystem::directory_iterator(dir)) {
            std::ifstream f(e.path(), std::ios::binary);
            const std::string bytes((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
            SCOPED_TRACE(e.path().string());
            t.run(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
            ++replayed[t.name];
        }
    }
    EXPECT_EQ(replayed, committed);
    for (const auto& e : std::filesystem::directory_iterator(root))  // every folder is a target's
        EXPECT_TRUE(committed.count(e.path().filename().string())) << e.path();
}

TEST(FuzzRegression, PseudoRandomInputsGiveNamedErrorsOrResults) {
    sweep::Rng rng(18);
    for (const auto& t : fuzz::targets()) {
        for (int k = 0; k < 25; ++k) {
            std::vector<std::uint8_t> bytes(1 + rng.next() % 64);
            for (auto& b : bytes) b = std::uint8_t(rng.next());
            t.run(bytes.data(), bytes.size());
        }
    }
}
