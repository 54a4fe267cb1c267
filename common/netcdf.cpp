#include "common/netcdf.hpp"

#include <sys/stat.h>
#include <sys/statvfs.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <set>
#include <utility>

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

// Opens `path` and walks every group's dimensions, variables and attributes: what
// libhdf5 parses when a reader inquires.
int walk_structure(const char* path) {
    int id = -1;
    if (nc_open(path, NC_NOWRITE, &id) != NC_NOERR) return 1;  // the parent reports it
    int nvars = 0, ndims = 0, natts = 0, unlimited = 0;
    if (nc_inq(id, &ndims, &nvars, &natts, &unlimited) != NC_NOERR) return 1;
    for (int v = -1; v < nvars; ++v) {
        int vatts = natts;
        if (v >= 0) {
            char name[NC_MAX_NAME + 1];
            nc_type t{};
            int nd = 0, dims[NC_MAX_VAR_DIMS];
            if (nc_inq_var(id, v, name, &t, &nd, dims, &vatts) != NC_NOERR) return 1;
            std::size_t chunks[NC_MAX_VAR_DIMS];
            int storage = 0;
            nc_inq_var_chunking(id, v, &storage, chunks);
        }
        for (int a = 0; a < vatts; ++a) {
            char name[NC_MAX_NAME + 1];
            nc_type t{};
            std::size_t len = 0;
            if (nc_inq_attname(id, v < 0 ? NC_GLOBAL : v, a, name) != NC_NOERR) return 1;
            nc_inq_att(id, v < 0 ? NC_GLOBAL : v, name, &t, &len);
        }
    }
    nc_close(id);
    return 0;
}

}  // namespace

namespace {

// A file as it is on disk now: its identity and its last change. An empty key: stat failed.
std::string file_version_key(const std::string& path) {
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0) return "";
    return std::to_string(st.st_dev) + ":" + std::to_string(st.st_ino) + ":" + std::to_string(st.st_size) + ":" +
           std::to_string(st.st_mtim.tv_sec) + "." + std::to_string(st.st_mtim.tv_nsec) + ":" + std::to_string(st.st_ctim.tv_sec) +
           "." + std::to_string(st.st_ctim.tv_nsec);
}

}  // namespace

// libhdf5 can crash or hang on a corrupted file (docs/reliability.md). Its structure is
// therefore walked first in a child process: a crash or a hang there is reported as a
// corrupted file, never takes flotsam down. FLOTSAM_NO_PROBE=1 skips it. A file that
// passed is not probed again while it is unchanged (same device, inode, size, mtime and
// ctime): a sweep opens each flow several times, and each probe forks the whole process.
void probe_structure(const std::string& path) {
    static const bool off = [] {
        const char* e = std::getenv("FLOTSAM_NO_PROBE");
        return e && *e && std::string(e) != "0";
    }();
    if (off) return;
    static std::mutex passed_mutex;
    static std::set<std::string> passed;
    const std::string key = file_version_key(path);
    {
        const std::lock_guard<std::mutex> lock(passed_mutex);
        if (!key.empty() && passed.count(key)) return;
    }
    std::fflush(nullptr);
    const pid_t child = ::fork();
    if (child < 0) return;  // cannot probe: read as usual
    if (child == 0) ::_exit(walk_structure(path.c_str()));
    int status = 0;
    for (int waited_ms = 0;; waited_ms += 5) {
        const pid_t r = ::waitpid(child, &status, WNOHANG);
        if (r == child) break;
        if (r < 0) return;
        if (waited_ms > 60000) {
            ::kill(child, SIGKILL);
            ::waitpid(child, &status, 0);
            fail(path, "", "corrupted: libhdf5 did not finish reading the file's structure in 60 s");
        }
        ::usleep(waited_ms < 100 ? 200 : 5000);
    }
    if (WIFSIGNALED(status))
        fail(path, "",
             std::string("corrupted: libhdf5 crashed reading the file's structure (") + ::strsignal(WTERMSIG(status)) +
                 "); the file cannot be read");
    if (WIFEXITED(status) && WEXITSTATUS(status) == 0 && !key.empty()) {
        const std::lock_guard<std::mutex> lock(passed_mutex);
        passed.insert(key);
    }
}

File File::open_read(const std::string& path) {
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

std::vector<double> File::get_double(int var) const {
    std::vector<double> v(product(shape(var)));
    check(nc_get_var_double(id_, var, v.data()), var_label(var));
    return v;
}
std::vector<float> File::get_float(int var) const {
    std::vector<float> v(product(shape(var)));
    check(nc_get_var_float(id_, var, v.data()), var_label(var));
    return v;
}
std::vector<int> File::get_int(int var) const {
    std::vector<int> v(product(shape(var)));
    check(nc_get_var_int(id_, var, v.data()), var_label(var));
    return v;
}
std::vector<std::string> File::get_strings(int var) const {
    const std::size_t n = product(shape(var));
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
        if (!std::isfinite(values[k]) || (fill && values[k] == *fill))
            fail(f.path(), "variable '" + name + "'",
                 "value at flat index " + std::to_string(k) + " is " +
                     (std::isfinite(values[k]) ? "the fill value" : "NaN or infinite") + " (missing data is not allowed here)");
    }
    return values;
}

}  // namespace flotsam::nc
