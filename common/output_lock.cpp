#include "common/output_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <map>
#include <mutex>

#include "common/atomic_file.hpp"
#include "common/checks.hpp"
#include "common/error.hpp"

namespace flotsam {

namespace {

struct Held {
    int fd = -1;
    int count = 0;
    std::string lock_path;
};

std::mutex& registry_mutex() {
    static std::mutex m;
    return m;
}
std::map<std::string, Held>& registry() {
    static std::map<std::string, Held> r;
    return r;
}

// The output path resolved (symbolic links in the existing part, "..", relative), so two
// spellings of one output share a lock.
std::string resolved(const std::string& path) {
    std::error_code ec;
    auto p = std::filesystem::weakly_canonical(std::filesystem::absolute(path, ec), ec);
    return ec ? path : p.string();
}

std::string holder_of(int fd) {
    char buf[256] = {0};
    const ssize_t n = ::pread(fd, buf, sizeof buf - 1, 0);
    std::string s = n > 0 ? std::string(buf, std::size_t(n)) : std::string();
    while (!s.empty() && (s.back() == '\n' || s.back() == '\0')) s.pop_back();
    return s.empty() ? "pid unknown" : s;
}

}  // namespace

OutputLock::OutputLock(const std::string& out_path) : key_(resolved(out_path)) {
    std::lock_guard<std::mutex> guard(registry_mutex());
    auto& reg = registry();
    if (auto it = reg.find(key_); it != reg.end()) {
        ++it->second.count;
        return;
    }
    ensure_parent_dir(key_);
    const std::string lock_path = key_ + ".lock";
    for (int attempt = 0;; ++attempt) {
        const int fd = ::open(lock_path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
        if (fd < 0) fail(lock_path, "", std::string("cannot create the lock file of ") + out_path + ": " + std::strerror(errno));
        if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
            const int err = errno;
            const std::string who = err == EWOULDBLOCK ? holder_of(fd) : std::string();
            ::close(fd);
            if (err == EWOULDBLOCK)
                fail("", "", "another run is writing " + out_path + " (" + who + "); wait for it, or give another --out");
            fail(lock_path, "", std::string("cannot lock: ") + std::strerror(err));
        }
        // The file may have been removed (by its last holder, on release) between open and
        // flock: then this lock is on an orphan, and another run may lock a new file.
        struct stat held {
        }, now{};
        if (::fstat(fd, &held) == 0 && ::stat(lock_path.c_str(), &now) == 0 && held.st_dev == now.st_dev &&
            held.st_ino == now.st_ino) {
            char host[128] = {0};
            ::gethostname(host, sizeof host - 1);
            const std::string who = "pid " + std::to_string(::getpid()) + " on " + host + "\n";
            if (::ftruncate(fd, 0) != 0 || ::pwrite(fd, who.data(), who.size(), 0) != ssize_t(who.size())) {
                const int err = errno;
                ::close(fd);
                fail(lock_path, "", std::string("cannot write the lock file: ") + std::strerror(err));
            }
            reg[key_] = Held{fd, 1, lock_path};
            return;
        }
        ::close(fd);
        if (attempt > 100) fail(lock_path, "", "the lock file keeps being replaced; is another run starting and stopping?");
    }
}

OutputLock::OutputLock(OutputLock&& other) noexcept : key_(std::move(other.key_)) { other.key_.clear(); }

OutputLock::~OutputLock() {
    if (key_.empty()) return;
    std::lock_guard<std::mutex> guard(registry_mutex());
    auto& reg = registry();
    auto it = reg.find(key_);
    if (it == reg.end() || --it->second.count > 0) return;
    ::unlink(it->second.lock_path.c_str());  // while still holding it (see the constructor)
    ::close(it->second.fd);
    reg.erase(it);
}

OutputGuard::OutputGuard(const std::vector<NamedPath>& outputs, const std::vector<NamedPath>& inputs) {
    for (const NamedPath& in : inputs) {
        if (in.gis)
            check_gis_input(in.option, in.path);
        else
            check_input_file(in.option, in.path);
    }
    for (const NamedPath& out : outputs) check_output_file(out.option, out.path);
    for (std::size_t k = 0; k < outputs.size(); ++k) {
        const NamedPath& out = outputs[k];
        if (out.path.empty()) continue;
        for (const NamedPath& in : inputs) {
            if (in.path.empty()) continue;
            if (same_file(out.path, in.path))
                fail(out.option, out.path,
                     "is the input given as " + in.option + " (" + in.path +
                         "): an output never overwrites an input; choose another " + out.option);
            if (same_file(out.path + ".part", in.path))
                fail(out.option, out.path,
                     "its temporary file " + out.path + ".part is the input given as " + in.option + "; choose another " +
                         out.option);
        }
        for (std::size_t q = 0; q < k; ++q)
            if (!outputs[q].path.empty() &&
                (same_file(out.path, outputs[q].path) || resolved(out.path) == resolved(outputs[q].path)))
                fail(out.option, out.path, "is also the output given as " + outputs[q].option + "; give two different files");
    }
    for (const NamedPath& out : outputs)
        if (!out.path.empty()) locks_.emplace_back(out.path);
}

}  // namespace flotsam
