// libFuzzer entry of one target: FLOTSAM_FUZZ_TARGET names the function of targets.hpp.
#include <cstddef>
#include <cstdint>

#include "fuzz/targets.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    flotsam::fuzz::FLOTSAM_FUZZ_TARGET(data, size);
    return 0;
}
