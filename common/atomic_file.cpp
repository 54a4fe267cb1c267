#include "common/atomic_file.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "common/error.hpp"

namespace flotsam {

AtomicOutput::AtomicOutput(std::string final_path) : final_(std::move(final_path)), temp_(final_ + ".part") {
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
        std::ofstream f(out.temp_path(), std::ios::binary);
        if (!f) fail(out.temp_path(), "", "cannot open for writing");
        f << text;
        f.flush();
        if (!f) fail(out.temp_path(), "", "write failed");
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
