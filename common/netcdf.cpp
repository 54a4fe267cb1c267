#include "common/netcdf.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

#include "common/checks.hpp"
#include "common/error.hpp"
#include "common/netcdf_probe.hpp"

namespace flotsam::nc {

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

std::string File::att_label(int var, const std::string& name) const {
    return (var == NC_GLOBAL ? std::string("global attribute '") : var_label(var) + " attribute '") + name + "'";
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

std::optional<nc_type> File::att_type(int var, const std::string& name, std::size_t* length) const {
    nc_type t{};
    std::size_t len = 0;
    const int st = nc_inq_att(id_, var, name.c_str(), &t, &len);
    if (st == NC_ENOTATT) return std::nullopt;
    // Unreadable (a damaged attribute message): an error, never "absent".
    if (st != NC_NOERR)
        fail(path_, att_label(var, name),
             std::string("cannot be read (") + nc_strerror(st) + "): the file's attributes are damaged");
    if (length) *length = len;
    return t;
}

bool File::att_is_text(int var, const std::string& name) const {
    const auto t = att_type(var, name);
    return t && (*t == NC_CHAR || *t == NC_STRING);
}

std::optional<std::string> File::att_text(int var, const std::string& name) const {
    std::size_t len = 0;
    const auto t = att_type(var, name, &len);
    if (!t) return std::nullopt;
    const std::string label = att_label(var, name);
    if (*t == NC_CHAR) {
        std::string s(len, '\0');
        check(nc_get_att_text(id_, var, name.c_str(), s.data()), label);
        while (!s.empty() && s.back() == '\0') s.pop_back();
        return s;
    }
    if (*t == NC_STRING && len == 1) {
        char* p = nullptr;
        check(nc_get_att_string(id_, var, name.c_str(), &p), label);
        std::string s = p ? p : "";
        nc_free_string(1, &p);
        return s;
    }
    fail(path_, label,
         *t == NC_STRING ? "holds " + std::to_string(len) + " strings, where one text is expected"
                         : "is a number, where text is expected");
}

std::optional<std::vector<double>> File::att_doubles(int var, const std::string& name) const {
    std::size_t len = 0;
    const auto t = att_type(var, name, &len);
    if (!t) return std::nullopt;
    const std::string label = att_label(var, name);
    if (*t == NC_CHAR || *t == NC_STRING) fail(path_, label, "is text, where a number is expected");
    std::vector<double> v(len);
    check(nc_get_att_double(id_, var, name.c_str(), v.data()), label);
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
