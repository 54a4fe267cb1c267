#include "common/netcdf.hpp"
#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define FLOTSAM_SANITIZED 1
#include <sanitizer/common_interface_defs.h>
#endif
#endif

#include <fcntl.h>
#include <malloc.h>
#include <hdf5.h>
#include <poll.h>
#include <sys/stat.h>
#include <sys/statvfs.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <set>
#include <utility>

#include "common/checks.hpp"
#include "common/error.hpp"

namespace flotsam::nc {

namespace {

// NetCDF reports a full disk as "HDF error": say what it is, with the file system's free
// space, when the file's file system is (nearly) full.
std::string disk_full_hint(const std::string& path) {
    std::error_code ec;
    auto dir = std::filesystem::absolute(path, ec).parent_path();
    struct statvfs st {};
    if (ec || ::statvfs(dir.c_str(), &st) != 0) return "";
    const double free_bytes = double(st.f_bavail) * double(st.f_frsize);
    const double total = double(st.f_blocks) * double(st.f_frsize);
    if (free_bytes > 4.0 * 1024 * 1024 && free_bytes > 0.001 * total) return "";
    char buf[160];
    std::snprintf(buf, sizeof buf, " (No space left on device: %.0f bytes free of %.0f on the file system of %s)", free_bytes,
                  total, dir.c_str());
    return buf;
}

}  // namespace

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
    std::fflush(nullptr);
    const pid_t child = ::fork();
    if (child < 0) {
        ::close(fds[0]);
        ::close(fds[1]);
        return;
    }
    if (child == 0) {
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
    ::close(fds[1]);
    ::fcntl(fds[0], F_SETFL, O_NONBLOCK);
    std::string text;  // what the child sent
    auto drain = [&] {
        char buf[4096];
        for (ssize_t n; (n = ::read(fds[0], buf, sizeof buf)) > 0;) {
            text.append(buf, std::size_t(n));
            if (text.size() > (1u << 20)) text.erase(0, text.size() - (1u << 16));  // only the last lines matter
        }
    };
    int status = 0;
    const auto started = std::chrono::steady_clock::now();
    const int timeout = probe_timeout_seconds(path);
    for (;;) {
        pollfd p{fds[0], POLLIN, 0};
        ::poll(&p, 1, 20);
        drain();
        const pid_t r = ::waitpid(child, &status, WNOHANG);
        if (r == child) break;
        if (r < 0) {
            ::close(fds[0]);
            return;
        }
        if (std::chrono::steady_clock::now() - started > std::chrono::seconds(timeout)) {
            ::kill(child, SIGKILL);
            ::waitpid(child, &status, 0);
            drain();
            ::close(fds[0]);
            fail(path, "",
                 "corrupted: libhdf5 did not finish " + last_stage(text) + " in " + std::to_string(timeout) +
                     " s; the file cannot be read");
        }
    }
    drain();
    ::close(fds[0]);
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

File File::open_read(const std::string& path) {
    check_input_file("", path);  // a FIFO or a device would block the probe or never end
    probe_structure(path);
    int id = -1;
    const int st = nc_open(path.c_str(), NC_NOWRITE, &id);
    if (st != NC_NOERR) fail(path, "", std::string("cannot open as NetCDF: ") + nc_strerror(st));
    return File(id, path);
}

File File::open_write(const std::string& path) {
    int id = -1;
    const int st = nc_open(path.c_str(), NC_WRITE, &id);
    if (st != NC_NOERR) fail(path, "", std::string("cannot open for writing: ") + nc_strerror(st) + disk_full_hint(path));
    return File(id, path);
}

File File::create(const std::string& path) {
    int id = -1;
    const int st = nc_create(path.c_str(), NC_CLOBBER | NC_NETCDF4, &id);
    if (st != NC_NOERR) fail(path, "", std::string("cannot create: ") + nc_strerror(st) + disk_full_hint(path));
    return File(id, path);
}

File::File(File&& o) noexcept : id_(std::exchange(o.id_, -1)), path_(std::move(o.path_)) {}

File& File::operator=(File&& o) noexcept {
    if (this != &o) {
        if (id_ >= 0) nc_close(id_);
        id_ = std::exchange(o.id_, -1);
        path_ = std::move(o.path_);
    }
    return *this;
}

File::~File() {
    if (id_ >= 0) nc_close(id_);  // errors cannot be reported from a destructor; close() reports them
}

void File::close() {
    if (id_ < 0) return;
    const int st = nc_close(id_);
    id_ = -1;
    check(st, "close");
}

void File::check(int status, const std::string& what) const {
    if (status != NC_NOERR) fail(path_, what, nc_strerror(status) + disk_full_hint(path_));
}

std::string File::var_label(int var) const {
    if (var == NC_GLOBAL) return "global attributes";
    char name[NC_MAX_NAME + 1] = {0};
    if (nc_inq_varname(id_, var, name) != NC_NOERR) return "variable #" + std::to_string(var);
    return std::string("variable '") + name + "'";
}

int File::def_dim(const std::string& name, std::size_t length) {
    int d = -1;
    check(nc_def_dim(id_, name.c_str(), length, &d), "dimension '" + name + "'");
    return d;
}

int File::def_var(const std::string& name, nc_type type, const std::vector<int>& dims) {
    int v = -1;
    check(nc_def_var(id_, name.c_str(), type, int(dims.size()), dims.data(), &v), "variable '" + name + "'");
    return v;
}

int File::def_text_var(const std::string& name, const std::vector<int>& dims, std::size_t length) {
    std::vector<int> all = dims;
    all.push_back(def_dim(name + "_strlen", std::max<std::size_t>(length, 1)));
    const int v = def_var(name, NC_CHAR, all);
    put_att(v, "_Encoding", std::string("utf-8"));  // netCDF4-python and xarray then give strings, not bytes
    return v;
}

void File::def_chunking(int var, const std::vector<std::size_t>& chunks) {
    check(nc_def_var_chunking(id_, var, NC_CHUNKED, chunks.data()), var_label(var) + " chunking");
}

void File::def_deflate(int var, int level, bool shuffle) {
    check(nc_def_var_deflate(id_, var, shuffle ? 1 : 0, level > 0 ? 1 : 0, level), var_label(var) + " deflate");
}

void File::def_fill(int var, double fill) {
    nc_type t{};
    check(nc_inq_vartype(id_, var, &t), var_label(var));
    if (t == NC_FLOAT) {
        const float f = float(fill);
        check(nc_def_var_fill(id_, var, 0, &f), var_label(var) + " _FillValue");
    } else if (t == NC_DOUBLE) {
        check(nc_def_var_fill(id_, var, 0, &fill), var_label(var) + " _FillValue");
    } else if (t == NC_INT) {
        const int i = int(fill);
        check(nc_def_var_fill(id_, var, 0, &i), var_label(var) + " _FillValue");
    } else if (t == NC_BYTE) {
        const signed char b = static_cast<signed char>(fill);
        check(nc_def_var_fill(id_, var, 0, &b), var_label(var) + " _FillValue");
    } else {
        fail(path_, var_label(var), "_FillValue for this type is not supported");
    }
}

void File::put_att(int var, const std::string& name, const std::string& value) {
    check(nc_put_att_text(id_, var, name.c_str(), value.size(), value.c_str()), var_label(var) + " attribute '" + name + "'");
}
void File::put_att(int var, const std::string& name, double value) {
    check(nc_put_att_double(id_, var, name.c_str(), NC_DOUBLE, 1, &value), var_label(var) + " attribute '" + name + "'");
}
void File::put_att(int var, const std::string& name, int value) {
    check(nc_put_att_int(id_, var, name.c_str(), NC_INT, 1, &value), var_label(var) + " attribute '" + name + "'");
}
void File::put_att(int var, const std::string& name, const std::vector<double>& values) {
    check(nc_put_att_double(id_, var, name.c_str(), NC_DOUBLE, values.size(), values.data()),
          var_label(var) + " attribute '" + name + "'");
}
void File::put_att(int var, const std::string& name, const std::vector<std::int8_t>& values) {
    check(nc_put_att_schar(id_, var, name.c_str(), NC_BYTE, values.size(), reinterpret_cast<const signed char*>(values.data())),
          var_label(var) + " attribute '" + name + "'");
}

void File::enddef() { check(nc_enddef(id_), "end of definitions"); }
void File::redef() { check(nc_redef(id_), "definition mode"); }
void File::sync() { check(nc_sync(id_), "sync"); }

void File::put(int var, const std::vector<double>& v) { check(nc_put_var_double(id_, var, v.data()), var_label(var)); }
void File::put(int var, const std::vector<float>& v) { check(nc_put_var_float(id_, var, v.data()), var_label(var)); }
void File::put(int var, const std::vector<int>& v) { check(nc_put_var_int(id_, var, v.data()), var_label(var)); }
void File::put(int var, const std::vector<std::int8_t>& v) {
    check(nc_put_var_schar(id_, var, reinterpret_cast<const signed char*>(v.data())), var_label(var));
}
void File::put(int var, const std::vector<std::string>& v) {
    nc_type t{};
    check(nc_inq_vartype(id_, var, &t), var_label(var));
    if (t == NC_CHAR) {
        const std::vector<std::size_t> s = shape(var);
        const std::size_t length = s.empty() ? 0 : s.back();
        std::string bytes(v.size() * length, '\0');
        for (std::size_t k = 0; k < v.size(); ++k) {
            if (v[k].size() > length)
                fail(path_, var_label(var),
                     "'" + v[k] + "' is longer than the variable's strings (" + std::to_string(length) + " bytes)");
            std::copy(v[k].begin(), v[k].end(), bytes.begin() + std::ptrdiff_t(k * length));
        }
        const std::vector<std::size_t> start(s.size(), 0);
        std::vector<std::size_t> count = s;
        if (!count.empty()) count.front() = v.size();
        if (length > 0 && !v.empty()) check(nc_put_vara_text(id_, var, start.data(), count.data(), bytes.data()), var_label(var));
        return;
    }
    std::vector<const char*> p;
    p.reserve(v.size());
    for (const auto& s : v) p.push_back(s.c_str());
    const std::size_t start = 0, count = v.size();
    check(nc_put_vara_string(id_, var, &start, &count, p.data()), var_label(var));
}

void File::put_slab(int var, const std::vector<std::size_t>& s, const std::vector<std::size_t>& c, const float* d) {
    check(nc_put_vara_float(id_, var, s.data(), c.data(), d), var_label(var));
}
void File::put_slab(int var, const std::vector<std::size_t>& s, const std::vector<std::size_t>& c, const double* d) {
    check(nc_put_vara_double(id_, var, s.data(), c.data(), d), var_label(var));
}
void File::put_slab(int var, const std::vector<std::size_t>& s, const std::vector<std::size_t>& c, const std::int8_t* d) {
    check(nc_put_vara_schar(id_, var, s.data(), c.data(), reinterpret_cast<const signed char*>(d)), var_label(var));
}

std::optional<int> File::find_var(const std::string& name) const {
    int v = -1;
    if (nc_inq_varid(id_, name.c_str(), &v) != NC_NOERR) return std::nullopt;
    return v;
}

bool File::has_var(const std::string& name) const { return find_var(name).has_value(); }

int File::var(const std::string& name) const {
    auto v = find_var(name);
    if (!v) fail(path_, "variable '" + name + "'", "missing");
    return *v;
}

std::optional<int> File::find_by_standard_name(const std::string& standard_name) const {
    int nvars = 0;
    check(nc_inq_nvars(id_, &nvars), "number of variables");
    for (int v = 0; v < nvars; ++v) {
        auto sn = att_text(v, "standard_name");
        if (sn && *sn == standard_name) return v;
    }
    return std::nullopt;
}

std::string File::var_name(int var) const {
    char name[NC_MAX_NAME + 1] = {0};
    check(nc_inq_varname(id_, var, name), "variable #" + std::to_string(var));
    return name;
}

std::vector<std::string> File::dim_names(int var) const {
    int nd = 0;
    check(nc_inq_varndims(id_, var, &nd), var_label(var));
    std::vector<int> dims(nd);
    check(nc_inq_vardimid(id_, var, dims.data()), var_label(var));
    std::vector<std::string> names;
    for (int d : dims) {
        char name[NC_MAX_NAME + 1] = {0};
        check(nc_inq_dimname(id_, d, name), var_label(var));
        names.emplace_back(name);
    }
    return names;
}

std::vector<std::size_t> File::shape(int var) const {
    int nd = 0;
    check(nc_inq_varndims(id_, var, &nd), var_label(var));
    std::vector<int> dims(nd);
    check(nc_inq_vardimid(id_, var, dims.data()), var_label(var));
    std::vector<std::size_t> s;
    for (int d : dims) {
        std::size_t len = 0;
        check(nc_inq_dimlen(id_, d, &len), var_label(var));
        s.push_back(len);
    }
    return s;
}

bool File::has_dim(const std::string& name) const {
    int d = -1;
    return nc_inq_dimid(id_, name.c_str(), &d) == NC_NOERR;
}

std::size_t File::dim_length(const std::string& name) const {
    int d = -1;
    check(nc_inq_dimid(id_, name.c_str(), &d), "dimension '" + name + "'");
    std::size_t len = 0;
    check(nc_inq_dimlen(id_, d, &len), "dimension '" + name + "'");
    return len;
}

namespace {
std::size_t product(const std::vector<std::size_t>& s) {
    std::size_t n = 1;
    for (auto k : s) n *= k;
    return n;
}
}  // namespace

// The values of a whole variable fit in memory, or a named error (a file declaring
// 2e5 x 1e5 cells): never std::bad_alloc.
static std::size_t checked_size(const File& f, int var, std::size_t bytes_each) {
    const std::vector<std::size_t> s = f.shape(var);
    double n = 1;
    std::string dims;
    for (auto k : s) {
        n *= double(k);
        dims += (dims.empty() ? "" : " x ") + std::to_string(k);
    }
    check_allocation("variable '" + f.var_name(var) + "'", dims.empty() ? "a scalar" : dims, n, double(bytes_each), "values",
                     f.path());
    return product(s);
}

std::vector<double> File::get_double(int var) const {
    std::vector<double> v(checked_size(*this, var, sizeof(double)));
    check(nc_get_var_double(id_, var, v.data()), var_label(var));
    return v;
}
std::vector<float> File::get_float(int var) const {
    std::vector<float> v(checked_size(*this, var, sizeof(float)));
    check(nc_get_var_float(id_, var, v.data()), var_label(var));
    return v;
}
std::vector<int> File::get_int(int var) const {
    std::vector<int> v(checked_size(*this, var, sizeof(int)));
    check(nc_get_var_int(id_, var, v.data()), var_label(var));
    return v;
}
std::vector<std::string> File::value_dims(int var) const {
    std::vector<std::string> d = dim_names(var);
    nc_type t{};
    check(nc_inq_vartype(id_, var, &t), var_label(var));
    if (t == NC_CHAR && !d.empty()) d.pop_back();
    return d;
}

std::vector<std::size_t> File::value_shape(int var) const {
    std::vector<std::size_t> s = shape(var);
    nc_type t{};
    check(nc_inq_vartype(id_, var, &t), var_label(var));
    if (t == NC_CHAR && !s.empty()) s.pop_back();
    return s;
}

std::vector<std::string> File::get_strings(int var) const {
    nc_type t{};
    check(nc_inq_vartype(id_, var, &t), var_label(var));
    if (t == NC_CHAR) {
        const std::vector<std::size_t> s = shape(var);
        const std::size_t length = s.empty() ? 1 : s.back(), bytes = checked_size(*this, var, 1);
        // As many strings as value_shape says, whatever the string length: a string
        // dimension of length 0 holds empty strings (a table's column then has its rows).
        if (length == 0) {
            const std::vector<std::size_t> rows(s.begin(), s.end() - 1);
            std::string dims;
            for (auto k : rows) dims += (dims.empty() ? "" : " x ") + std::to_string(k);
            check_allocation(var_label(var), dims.empty() ? "a scalar" : dims, double(product(rows)), double(sizeof(std::string)),
                             "strings", path_);
            return std::vector<std::string>(product(rows));
        }
        std::string all(bytes, '\0');
        if (bytes > 0) check(nc_get_var_text(id_, var, all.data()), var_label(var));
        std::vector<std::string> out;
        for (std::size_t k = 0; k + length <= all.size(); k += length) {
            std::string one = all.substr(k, length);
            one.erase(std::find(one.begin(), one.end(), '\0'), one.end());
            out.push_back(std::move(one));
        }
        return out;
    }
    if (t != NC_STRING) fail(path_, var_label(var), "must hold strings (a character array)");
    const std::size_t n = checked_size(*this, var, sizeof(char*) + sizeof(std::string));
    std::vector<char*> p(n, nullptr);
    check(nc_get_var_string(id_, var, p.data()), var_label(var));
    std::vector<std::string> out;
    for (auto* s : p) out.emplace_back(s ? s : "");
    nc_free_string(n, p.data());
    return out;
}

void File::get_slab(int var, const std::vector<std::size_t>& s, const std::vector<std::size_t>& c, float* out) const {
    check(nc_get_vara_float(id_, var, s.data(), c.data(), out), var_label(var));
}
void File::get_slab(int var, const std::vector<std::size_t>& s, const std::vector<std::size_t>& c, double* out) const {
    check(nc_get_vara_double(id_, var, s.data(), c.data(), out), var_label(var));
}

std::optional<std::string> File::att_text(int var, const std::string& name) const {
    nc_type t{};
    std::size_t len = 0;
    if (nc_inq_att(id_, var, name.c_str(), &t, &len) != NC_NOERR) return std::nullopt;
    if (t == NC_CHAR) {
        std::string s(len, '\0');
        check(nc_get_att_text(id_, var, name.c_str(), s.data()), var_label(var) + " attribute '" + name + "'");
        while (!s.empty() && s.back() == '\0') s.pop_back();
        return s;
    }
    if (t == NC_STRING && len == 1) {
        char* p = nullptr;
        check(nc_get_att_string(id_, var, name.c_str(), &p), var_label(var) + " attribute '" + name + "'");
        std::string s = p ? p : "";
        nc_free_string(1, &p);
        return s;
    }
    return std::nullopt;
}

std::optional<std::vector<double>> File::att_doubles(int var, const std::string& name) const {
    nc_type t{};
    std::size_t len = 0;
    if (nc_inq_att(id_, var, name.c_str(), &t, &len) != NC_NOERR) return std::nullopt;
    if (t == NC_CHAR || t == NC_STRING) return std::nullopt;
    std::vector<double> v(len);
    check(nc_get_att_double(id_, var, name.c_str(), v.data()), var_label(var) + " attribute '" + name + "'");
    return v;
}

std::vector<std::string> File::att_names(int var) const {
    int n = 0;
    check(var == NC_GLOBAL ? nc_inq_natts(id_, &n) : nc_inq_varnatts(id_, var, &n), var_label(var) + " attributes");
    std::vector<std::string> names;
    for (int k = 0; k < n; ++k) {
        char name[NC_MAX_NAME + 1] = {};
        check(nc_inq_attname(id_, var, k, name), var_label(var) + " attribute " + std::to_string(k));
        names.emplace_back(name);
    }
    return names;
}

std::optional<double> File::att_double(int var, const std::string& name) const {
    auto v = att_doubles(var, name);
    if (!v || v->empty()) return std::nullopt;
    return v->front();
}

std::vector<double> read_finite(const File& f, const std::string& name) {
    const int v = f.var(name);
    std::vector<double> values = f.get_double(v);
    std::optional<double> fill = f.att_double(v, "_FillValue");
    if (!fill) fill = f.att_double(v, "missing_value");
    for (std::size_t k = 0; k < values.size(); ++k) {
        // NetCDF's default fill value (9.97e36, as float or double) marks values never
        // written, with or without a _FillValue attribute.
        if (!std::isfinite(values[k]) || (fill && values[k] == *fill) || std::fabs(values[k]) >= 9.96e36)
            fail(f.path(), "variable '" + name + "'",
                 "value at flat index " + std::to_string(k) + " is " +
                     (std::isfinite(values[k]) ? "the fill value" : "NaN or infinite") + " (missing data is not allowed here)");
    }
    return values;
}

}  // namespace flotsam::nc
