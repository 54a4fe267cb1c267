// The check of a NetCDF file in a child process (common/netcdf_probe.hpp).
#include "common/netcdf_probe.hpp"
#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define FLOTSAM_SANITIZED 1
#include <sanitizer/common_interface_defs.h>
#endif
#endif

#include <fcntl.h>
#include <hdf5.h>
#include <malloc.h>
#include <netcdf.h>
#include <poll.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "common/error.hpp"

namespace flotsam::nc {

namespace {

// ---- the check of a file in a child process ----
//
// libhdf5 can crash, or loop, on a corrupted file, and not only while it parses the
// structure: a damaged global heap (where NetCDF-4 keeps variable-length strings) makes
// it segfault when the strings are read, and a damaged metadata entry that a read loaded
// makes it abort in free() when the file is closed. So the child does everything a
// reader may do with the file, in the same library: it walks the structure, reads every
// attribute, every string and every variable of up to `full_read_bytes`, reads one value
// of the larger ones, closes the file, and then walks the chunk index of every dataset
// through libhdf5 itself (each stored chunk must lie inside the file). The main process
// touches the file only once the child has done all that without crashing.

constexpr std::size_t full_read_bytes = std::size_t(16) << 20;  // a variable read whole when no larger

// What the child tells the parent, one line each on a pipe: "@what it is reading" before
// each step (so a crash names what it was reading), "!a problem" for a named error,
// "#done" or "#cannot open" at its end. Only "#done" with exit status 0 passes the file:
// a child that dies otherwise (AddressSanitizer, in the fuzz build, exits with status 1)
// has not proved it.
class Report {
public:
    explicit Report(int fd) : fd_(fd) {}
    void stage(const std::string& what) { send('@' + what); }
    void problem(const std::string& what) { send('!' + what); }
    void outcome(const char* what) { send(std::string("#") + what); }  // "#done", "#cannot open"

private:
    void send(const std::string& line) {
        const std::string s = line + "\n";
        for (std::size_t done = 0; done < s.size();) {
            const ssize_t n = ::write(fd_, s.data() + done, s.size() - done);
            if (n <= 0) return;
            done += std::size_t(n);
        }
    }
    int fd_;
};

std::string quoted_var(int id, int v) {
    if (v == NC_GLOBAL) return "the global attributes";
    char name[NC_MAX_NAME + 1] = {0};
    nc_inq_varname(id, v, name);
    return std::string("variable '") + name + "'";
}

// Every attribute of `v` (NC_GLOBAL: the file's), its value read.
void read_attributes(int id, int v, int natts, Report& report) {
    for (int a = 0; a < natts; ++a) {
        char name[NC_MAX_NAME + 1] = {0};
        nc_type t{};
        std::size_t len = 0;
        if (nc_inq_attname(id, v, a, name) != NC_NOERR || nc_inq_att(id, v, name, &t, &len) != NC_NOERR) continue;
        report.stage(quoted_var(id, v) + ", attribute '" + name + "'");
        if (len > (std::size_t(1) << 24)) continue;  // no attribute of a flotsam reader is that long
        if (t == NC_STRING) {
            std::vector<char*> p(len + 1, nullptr);
            if (nc_get_att_string(id, v, name, p.data()) == NC_NOERR) nc_free_string(len, p.data());
        } else {
            std::vector<double> buf(len + 1);  // 8 bytes a value holds every type but strings
            nc_get_att(id, v, name, buf.data());
        }
    }
}

// Every value of a variable that is no larger than full_read_bytes (strings all), else
// its first and last value.
void read_variable(int id, int v, Report& report) {
    int nd = 0;
    nc_type t{};
    int dims[NC_MAX_VAR_DIMS];
    if (nc_inq_varndims(id, v, &nd) != NC_NOERR || nd > NC_MAX_VAR_DIMS || nc_inq_vartype(id, v, &t) != NC_NOERR ||
        nc_inq_vardimid(id, v, dims) != NC_NOERR)
        return;
    std::vector<std::size_t> shape(std::size_t(nd), 0);
    double count = 1;
    for (int d = 0; d < nd; ++d) {
        if (nc_inq_dimlen(id, dims[d], &shape[std::size_t(d)]) != NC_NOERR) return;
        count *= double(shape[std::size_t(d)]);
    }
    if (count == 0) return;
    std::size_t size = 0;
    if (nc_inq_type(id, t, nullptr, &size) != NC_NOERR || size == 0) return;
    report.stage("reading " + quoted_var(id, v));
    if (t == NC_STRING) {
        if (count > 1e8) return;  // a file of that many strings is no flotsam file; its reader says so
        std::vector<char*> p(std::size_t(count), nullptr);
        if (nc_get_var_string(id, v, p.data()) == NC_NOERR) nc_free_string(p.size(), p.data());
        return;
    }
    if (count * double(size) <= double(full_read_bytes)) {
        std::vector<double> buf(std::size_t(count * double(size)) / sizeof(double) + 1);
        nc_get_var(id, v, buf.data());
        return;
    }
    std::vector<std::size_t> index(std::size_t(nd), 0);
    double value[4];
    nc_get_var1(id, v, index.data(), value);
    for (int d = 0; d < nd; ++d) index[std::size_t(d)] = shape[std::size_t(d)] - 1;
    nc_get_var1(id, v, index.data(), value);
}

// The storage of every dataset in the root group, through libhdf5: every node of every
// chunk index is visited (H5Dget_num_chunks walks it once), which the readers may reach
// later (a replay reads frame after frame); a contiguous dataset's data must lie inside
// the file.
// (Looking each chunk up by its coordinates, to check its address too, took minutes on a
// whole 1 cm flow: libhdf5 1.10 finds a chunk by walking the index from its start. A
// chunk past the end of the file is an ordinary read error of libhdf5's.)
struct ChunkWalk {
    Report* report;
    hsize_t file_size = 0;
    std::string problem;
};

herr_t walk_dataset(hid_t group, const char* name, const H5L_info_t*, void* data) {
    auto& w = *static_cast<ChunkWalk*>(data);
    const hid_t ds = H5Dopen2(group, name, H5P_DEFAULT);
    if (ds < 0) return 0;  // not a dataset (or unreadable: the NetCDF pass said so)
    w.report->stage(std::string("the storage of variable '") + name + "'");
    const hid_t plist = H5Dget_create_plist(ds);
    const H5D_layout_t layout = plist >= 0 ? H5Pget_layout(plist) : H5D_LAYOUT_ERROR;
    if (layout == H5D_CONTIGUOUS) {
        const haddr_t addr = H5Dget_offset(ds);
        const hsize_t bytes = H5Dget_storage_size(ds);
        if (addr != HADDR_UNDEF && (addr > w.file_size || bytes > w.file_size - addr))
            w.problem = std::string("variable '") + name + "': its data at byte " + std::to_string(addr) + " (" +
                        std::to_string(bytes) + " bytes) lie past the end of the file (" + std::to_string(w.file_size) + " bytes)";
    } else if (layout == H5D_CHUNKED) {
        hsize_t chunks = 0;
        H5Dget_num_chunks(ds, H5S_ALL, &chunks);
    }
    if (plist >= 0) H5Pclose(plist);
    H5Dclose(ds);
    return w.problem.empty() ? 0 : 1;
}

// The child's work. Exit status: 0 read through ("#done" sent); 1 NetCDF cannot open it
// ("#cannot open" sent: the parent opens it itself and reports NetCDF's message); 3 a
// problem sent on the pipe. Any other end (a signal, or status 1 without "#cannot open",
// as AddressSanitizer exits) is a corrupted file.
int check_in_child(const char* path, Report& report) {
    report.stage("opening the file");
    int id = -1;
    if (nc_open(path, NC_NOWRITE, &id) != NC_NOERR) {
        report.outcome("cannot open");
        return 1;
    }
    int nvars = 0, ndims = 0, natts = 0, unlimited = 0;
    report.stage("the file's structure");
    if (nc_inq(id, &ndims, &nvars, &natts, &unlimited) == NC_NOERR) {
        read_attributes(id, NC_GLOBAL, natts, report);
        for (int v = 0; v < nvars; ++v) {
            char name[NC_MAX_NAME + 1];
            nc_type t{};
            int nd = 0, dims[NC_MAX_VAR_DIMS], vatts = 0;
            if (nc_inq_var(id, v, name, &t, &nd, dims, &vatts) != NC_NOERR) continue;
            report.stage(std::string("variable '") + name + "'");
            std::size_t chunks[NC_MAX_VAR_DIMS];
            int storage = 0;
            nc_inq_var_chunking(id, v, &storage, chunks);
            read_attributes(id, v, vatts, report);
        }
        for (int v = 0; v < nvars; ++v) read_variable(id, v, report);
    }
    // Only flows are read through libhdf5 (formats/tile_decoder): a file that says it is
    // another kind (a scene, a sweep) is not walked again, nor opened a second time.
    char kind[64] = {0};
    std::size_t kind_length = 0;
    const bool other_kind = nc_inq_attlen(id, NC_GLOBAL, "flotsam_file_kind", &kind_length) == NC_NOERR &&
                            kind_length < sizeof kind && nc_get_att_text(id, NC_GLOBAL, "flotsam_file_kind", kind) == NC_NOERR &&
                            std::string(kind, kind_length) != "flow";
    report.stage("closing the file");
    nc_close(id);
    // The same file through libhdf5, as formats/tile_decoder reads it.
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
    ChunkWalk walk{&report, 0, ""};
    if (!other_kind) report.stage("opening the file through libhdf5");
    const hid_t file = other_kind ? hid_t(-1) : H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
    if (file >= 0) {  // else not HDF5 (netCDF-3, say): nothing more to walk
        H5Fget_filesize(file, &walk.file_size);
        hsize_t index = 0;
        H5Literate(file, H5_INDEX_NAME, H5_ITER_NATIVE, &index, walk_dataset, &walk);
        report.stage("closing the file through libhdf5");
        H5Fclose(file);
    }
    // A damaged heap can make libhdf5 write past its own allocations without crashing
    // yet: the process then dies later, in libhdf5's free lists or glibc's bins (at exit,
    // "double free or corruption"). Free the lists and consolidate the heap here, where
    // that shows as a crash of the child.
    report.stage("freeing what it read");
    H5garbage_collect();
    ::malloc_trim(0);
    if (!walk.problem.empty()) {
        report.problem(walk.problem);
        return 3;
    }
    report.outcome("done");
    return 0;
}

// How long the child may take before its file counts as one libhdf5 loops on: 10 s and
// 60 s per GB (a whole 1 cm flow, 1 GB, is read through in a few seconds; a loop is a loop).
int probe_timeout_seconds(const std::string& path) {
    struct stat st {};
    const double gb = ::stat(path.c_str(), &st) == 0 ? double(st.st_size) / 1e9 : 0.0;
    return int(10.0 + 60.0 * gb);
}

// "reading variable 'z'" from the child's last "@..." line.
std::string last_stage(const std::string& text) {
    std::string last = "the file's structure";
    std::size_t at = 0;
    while (at < text.size()) {
        const std::size_t end = text.find('\n', at);
        if (end == std::string::npos) break;
        if (text[at] == '@') last = text.substr(at + 1, end - at - 1);
        at = end + 1;
    }
    for (const char* verb : {"reading ", "opening ", "closing ", "freeing "})
        if (last.rfind(verb, 0) == 0) return last;
    return "reading " + last;
}

std::string problem_of(const std::string& text) {
    const std::size_t at = text.rfind("\n!");
    if (at != std::string::npos) return text.substr(at + 2, text.find('\n', at + 2) - at - 2);
    if (text.rfind('!', 0) == 0) return text.substr(1, text.find('\n') - 1);
    return "the file's storage is damaged";
}

}  // namespace

namespace {

// A file as it is on disk now: its identity and its last change. An empty key: stat failed,
// or the file changed in the last 2 s. File times tick with the kernel's coarse clock
// (milliseconds), so a file rewritten at once with the same size can keep its times: only
// a file that has been still for longer is recognised by them (as git does with "racily
// clean" files). A sweep's flows are old; a file just written is probed each time.
std::string file_version_key(const std::string& path) {
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0) return "";
    timespec now{};
    ::clock_gettime(CLOCK_REALTIME, &now);
    const auto seconds = [](const timespec& t) { return double(t.tv_sec) + 1e-9 * double(t.tv_nsec); };
    const double age = seconds(now) - std::max(seconds(st.st_mtim), seconds(st.st_ctim));
    if (!(age > 2.0)) return "";
    return std::to_string(st.st_dev) + ":" + std::to_string(st.st_ino) + ":" + std::to_string(st.st_size) + ":" +
           std::to_string(st.st_mtim.tv_sec) + "." + std::to_string(st.st_mtim.tv_nsec) + ":" + std::to_string(st.st_ctim.tv_sec) +
           "." + std::to_string(st.st_ctim.tv_nsec);
}

int probe_setting() {
    const char* e = std::getenv("FLOTSAM_NO_PROBE");
    return e && *e && std::string(e) != "0" ? 0 : 1;
}
std::atomic<int> probe_on{-1};  // -1: from FLOTSAM_NO_PROBE

}  // namespace

void set_probe_enabled(bool on) { probe_on = on ? 1 : 0; }

bool probe_enabled() {
    int on = probe_on.load();
    if (on < 0) probe_on = on = probe_setting();
    return on == 1;
}

namespace {

// Forks the child that reads `path` (check_in_child), writing its report to `fd`; -1 when
// no child could be started.
pid_t start_child(const std::string& path, int fds[2]) {
    std::fflush(nullptr);
    const pid_t child = ::fork();
    if (child != 0) return child;
    ::close(fds[0]);
    // The child dies of what libhdf5 does, and the parent reports it: no handler the
    // parent installed runs here (libFuzzer's, in the fuzz build, wrote the child's
    // crash as a crash of the target, and a crash-* file into the working directory).
    for (const int sig : {SIGSEGV, SIGBUS, SIGABRT, SIGFPE, SIGILL}) ::signal(sig, SIG_DFL);
#if FLOTSAM_SANITIZED
    __sanitizer_set_death_callback(nullptr);  // a sanitizer's report: the child just exits
#endif
    // What libhdf5 and glibc print as they fail ("free(): invalid size", HDF5's error
    // stack) is not for the user: the parent names the file and what was being read.
    if (const int null = ::open("/dev/null", O_WRONLY); null >= 0) ::dup2(null, 2);
    Report report(fds[1]);
    ::_exit(check_in_child(path.c_str(), report));
}

// Collects what the child sends on `fd` into `text` until it ends; its wait status, or
// nullopt when it cannot be waited for. A child that runs past the timeout is killed and
// the file named.
std::optional<int> wait_for_child(pid_t child, int fd, const std::string& path, std::string& text) {
    ::fcntl(fd, F_SETFL, O_NONBLOCK);
    auto drain = [&] {
        char buf[4096];
        for (ssize_t n; (n = ::read(fd, buf, sizeof buf)) > 0;) {
            text.append(buf, std::size_t(n));
            if (text.size() > (1u << 20)) text.erase(0, text.size() - (1u << 16));  // only the last lines matter
        }
    };
    int status = 0;
    const auto started = std::chrono::steady_clock::now();
    const int timeout = probe_timeout_seconds(path);
    for (;;) {
        pollfd p{fd, POLLIN, 0};
        ::poll(&p, 1, 20);
        drain();
        const pid_t r = ::waitpid(child, &status, WNOHANG);
        if (r == child) break;
        if (r < 0) return std::nullopt;
        if (std::chrono::steady_clock::now() - started > std::chrono::seconds(timeout)) {
            ::kill(child, SIGKILL);
            ::waitpid(child, &status, 0);
            drain();
            ::close(fd);
            fail(path, "",
                 "corrupted: libhdf5 did not finish " + last_stage(text) + " in " + std::to_string(timeout) +
                     " s; the file cannot be read");
        }
    }
    drain();
    return status;
}

}  // namespace

// libhdf5 can crash or hang on a corrupted file (docs/reliability.md). The file is
// therefore read first in a child process (check_in_child): a crash or a hang there is
// reported as a corrupted file, naming what the child was reading, and never takes
// flotsam down. FLOTSAM_NO_PROBE=1 skips it. A file that passed is not probed again while
// it is unchanged (same device, inode, size, mtime and ctime): a sweep opens each flow
// several times, and each probe forks the whole process.
void probe_structure(const std::string& path) {
    if (!probe_enabled()) return;
    static std::mutex passed_mutex;
    static std::set<std::string> passed;
    const std::string key = file_version_key(path);
    {
        const std::lock_guard<std::mutex> lock(passed_mutex);
        if (!key.empty() && passed.count(key)) return;
    }
    int fds[2];
    if (::pipe2(fds, O_CLOEXEC) != 0) return;  // cannot probe: read as usual
    const pid_t child = start_child(path, fds);
    ::close(fds[1]);
    std::string text;  // what the child sent
    const std::optional<int> waited = child < 0 ? std::nullopt : wait_for_child(child, fds[0], path, text);
    ::close(fds[0]);
    if (!waited) return;  // no child: read as usual
    const int status = *waited;
    if (WIFSIGNALED(status))
        fail(path, "",
             std::string("corrupted: libhdf5 crashed ") + last_stage(text) + " (" + ::strsignal(WTERMSIG(status)) +
                 "); the file cannot be read");
    const int code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    if (code == 3) fail(path, "", "corrupted: " + problem_of(text) + "; the file cannot be read");
    const auto said = [&](const std::string& line) { return text.find("#" + line + "\n") != std::string::npos; };
    if (code == 1 && said("cannot open")) return;  // NetCDF's own message, from the parent's open
    if (code != 0 || !said("done"))
        fail(path, "",
             "corrupted: libhdf5 failed " + last_stage(text) + " (the check exited with status " + std::to_string(code) +
                 "); the file cannot be read");
    if (!key.empty()) {
        const std::lock_guard<std::mutex> lock(passed_mutex);
        passed.insert(key);
    }
}

}  // namespace flotsam::nc
