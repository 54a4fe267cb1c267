#include "common/atomic_file.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "common/checks.hpp"
#include "common/error.hpp"

namespace flotsam {

namespace {
// Never rename over a device, a FIFO or a directory (checked before the lock is taken).
std::string checked_output(std::string path) {
    check_output_file("output", path);
    return path;
}
}  // namespace

AtomicOutput::AtomicOutput(std::string final_path)
    : final_(checked_output(std::move(final_path))), temp_(final_ + ".part"), lock_(final_) {
    ensure_parent_dir(final_);
    std::error_code ec;
    temp_existed_ = std::filesystem::exists(temp_, ec) || std::filesystem::is_symlink(temp_, ec);
}

AtomicOutput::~AtomicOutput() {
    if (!done_ && !keep_ && !temp_existed_) std::remove(temp_.c_str());
}

void AtomicOutput::commit() {
    if (std::rename(temp_.c_str(), final_.c_str()) != 0)
        fail(final_, "", std::string("cannot rename finished output from ") + temp_ + ": " + std::strerror(errno));
    done_ = true;
}

void write_text_atomic(const std::string& path, const std::string& text) {
    AtomicOutput out(path);
    {
        errno = 0;
        std::ofstream f(out.temp_path(), std::ios::binary);
        if (!f) fail(out.temp_path(), "", std::string("cannot open for writing: ") + std::strerror(errno));
        f << text;
        f.close();  // the data reach the file system here: a full disk shows now
        if (f.fail()) fail(out.temp_path(), "", std::string("write failed: ") + std::strerror(errno ? errno : EIO));
    }
    out.commit();
}

void ensure_parent_dir(const std::string& path) {
    const auto parent = std::filesystem::path(path).parent_path();
    if (parent.empty()) return;
    std::error_code ec;
    std::filesystem::create_directories(parent, ec);
    if (ec) fail(parent.string(), "", "cannot create directory: " + ec.message());
}

}  // namespace flotsam
