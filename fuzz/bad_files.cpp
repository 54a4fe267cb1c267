#include "fuzz/bad_files.hpp"

#include <netcdf.h>

#include <algorithm>
#include <functional>
#include <stdexcept>
#include <vector>

#include "fuzz/nc_model.hpp"

namespace flotsam::fuzz {

namespace {

void save_or_throw(const Model& m, const std::string& out) {
    if (!save_model(m, out)) throw std::runtime_error("cannot write " + out);
}

void ok(int status, const std::string& path, const std::string& what) {
    if (status != NC_NOERR) throw std::runtime_error(path + ": " + what + ": " + nc_strerror(status));
}

// Opens `path` for writing, runs edit(id, var) on `var` ("global": NC_GLOBAL), closes it.
void edit_in_place(const std::string& path, const std::string& var, const std::function<void(int, int)>& edit) {
    int id = -1, v = NC_GLOBAL;
    ok(nc_open(path.c_str(), NC_WRITE, &id), path, "open");
    if (var != "global") ok(nc_inq_varid(id, var.c_str(), &v), path, "variable " + var);
    edit(id, v);
    ok(nc_close(id), path, "close");
}

std::vector<double> values_of(int id, int v, const std::string& path) {
    int nd = 0, dims[NC_MAX_VAR_DIMS];
    ok(nc_inq_varndims(id, v, &nd), path, "dimensions");
    ok(nc_inq_vardimid(id, v, dims), path, "dimensions");
    std::size_t n = 1;
    for (int d = 0; d < nd; ++d) {
        std::size_t len = 0;
        ok(nc_inq_dimlen(id, dims[d], &len), path, "dimension");
        n *= len;
    }
    std::vector<double> values(n);
    if (n) ok(nc_get_var_double(id, v, values.data()), path, "values");
    return values;
}

void map_values(const std::string& path, const std::string& var, const std::function<void(std::vector<double>&)>& change) {
    edit_in_place(path, var, [&](int id, int v) {
        std::vector<double> values = values_of(id, v, path);
        change(values);
        if (!values.empty()) ok(nc_put_var_double(id, v, values.data()), path, "values of " + var);
    });
}

}  // namespace

void copy_with_short_column(const std::string& in, const std::string& out, const std::string& var, std::size_t length) {
    Model m = load_model(in);
    Var& v = var_named(m, var);
    m.dims.emplace_back(var + "_short", length);
    if (v.type == NC_CHAR && !v.dims.empty())
        v.dims = {int(m.dims.size() - 1), v.dims.back()};  // strings keep their length
    else
        v.dims.assign(1, int(m.dims.size() - 1));
    m.fit(v);
    save_or_throw(m, out);
}

void copy_with_dimension(const std::string& in, const std::string& out, const std::string& dim, std::size_t length) {
    Model m = load_model(in);
    for (auto& d : m.dims)
        if (d.first == dim) d.second = length;
    for (Var& v : m.vars) m.fit(v);
    save_or_throw(m, out);
}

void copy_with_transposed(const std::string& in, const std::string& out, const std::string& var) {
    Model m = load_model(in);
    Var& v = var_named(m, var);
    if (v.dims.size() != 2) throw std::runtime_error(in + ": variable '" + var + "' is not 2-D");
    std::swap(v.dims[0], v.dims[1]);
    m.fit(v);
    save_or_throw(m, out);
}

void copy_with_value(const std::string& in, const std::string& out, const std::string& var, std::size_t index, double value) {
    Model m = load_model(in);
    var_named(m, var).numbers.at(index) = value;
    save_or_throw(m, out);
}

void set_text_attribute(const std::string& path, const std::string& var, const std::string& name, const std::string& text) {
    edit_in_place(path, var, [&](int id, int v) {
        ok(nc_redef(id), path, "definition mode");
        ok(nc_put_att_text(id, v, name.c_str(), text.size(), text.c_str()), path, "attribute " + name);
    });
}

void set_number_attribute(const std::string& path, const std::string& var, const std::string& name, double value) {
    edit_in_place(path, var, [&](int id, int v) {
        ok(nc_redef(id), path, "definition mode");
        ok(nc_put_att_double(id, v, name.c_str(), NC_DOUBLE, 1, &value), path, "attribute " + name);
    });
}

void scale_values(const std::string& path, const std::string& var, double factor) {
    map_values(path, var, [&](std::vector<double>& v) {
        for (double& a : v) a *= factor;
    });
}

void set_all(const std::string& path, const std::string& var, double value) {
    map_values(path, var, [&](std::vector<double>& v) { std::fill(v.begin(), v.end(), value); });
}

void set_value(const std::string& path, const std::string& var, std::size_t index, double value) {
    map_values(path, var, [&](std::vector<double>& v) { v.at(index) = value; });
}

void shift_values(const std::string& path, const std::string& var, double offset) {
    map_values(path, var, [&](std::vector<double>& v) {
        for (double& a : v) a += offset;
    });
}

void set_string(const std::string& path, const std::string& var, std::size_t index, const std::string& text) {
    edit_in_place(path, var, [&](int id, int v) {
        int dims[2];
        std::size_t length = 0;
        ok(nc_inq_vardimid(id, v, dims), path, "dimensions of " + var);
        ok(nc_inq_dimlen(id, dims[1], &length), path, "string length of " + var);
        if (text.size() > length) throw std::runtime_error(path + ": '" + text + "' is longer than " + var + "'s strings");
        std::string padded = text;
        padded.resize(length, '\0');
        const std::size_t start[2] = {index, 0}, count[2] = {1, length};
        ok(nc_put_vara_text(id, v, start, count, padded.data()), path, "string of " + var);
    });
}

}  // namespace flotsam::fuzz
