// SHA-256 (FIPS 180-4) of a file or a byte string, as lowercase hex. Used to record the
// exact boundary file behind a run, and for determinism hashes in tests.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>

namespace flotsam {

class Sha256 {
public:
    Sha256();
    void update(const void* data, std::size_t n);
    std::string hex();  // finishes the hash

private:
    void block(const std::uint8_t* p);
    std::uint32_t h_[8];
    std::uint8_t buf_[64];
    std::size_t fill_ = 0;
    std::uint64_t bytes_ = 0;
};

std::string sha256_hex(const std::string& bytes);
std::string sha256_file(const std::string& path);  // throws naming the file if unreadable

}  // namespace flotsam
