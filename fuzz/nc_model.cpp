#include "fuzz/nc_model.hpp"

#include <algorithm>
#include <stdexcept>

namespace flotsam::fuzz {

namespace {

std::vector<Att> read_atts(int id, int var, int natts) {
    std::vector<Att> out;
    for (int a = 0; a < natts; ++a) {
        char name[NC_MAX_NAME + 1] = {0};
        nc_inq_attname(id, var, a, name);
        Att at;
        at.name = name;
        std::size_t len = 0;
        nc_inq_att(id, var, name, &at.type, &len);
        if (at.type == NC_CHAR) {
            at.text.resize(len);
            nc_get_att_text(id, var, name, at.text.data());
        } else if (at.type == NC_STRING) {
            std::vector<char*> p(len);
            nc_get_att_string(id, var, name, p.data());
            at.text = len && p[0] ? p[0] : "";
            nc_free_string(len, p.data());
        } else {
            at.numbers.resize(len);
            nc_get_att_double(id, var, name, at.numbers.data());
        }
        out.push_back(at);
    }
    return out;
}

void put_atts(int id, int var, const Var* v, const std::vector<Att>& atts) {
    for (const Att& a : atts) {
        if (a.name == "_FillValue") {
            if (v && !a.numbers.empty() && !v->is_text()) {
                const double f = a.numbers[0];
                nc_put_att_double(id, var, "_FillValue", v->type, 1, &f);
            }
            continue;
        }
        if (!a.name.empty() && a.name[0] == '_') continue;
        if (a.type == NC_CHAR || a.type == NC_STRING)
            nc_put_att_text(id, var, a.name.c_str(), a.text.size(), a.text.c_str());
        else
            nc_put_att_double(id, var, a.name.c_str(), a.type, a.numbers.size(), a.numbers.data());
    }
}

}  // namespace

Model load_model(const std::string& path) {
    Model m;
    int id = -1;
    if (nc_open(path.c_str(), NC_NOWRITE, &id) != NC_NOERR) throw std::runtime_error("cannot open " + path);
    int ndims = 0, nvars = 0, ngatts = 0, unlim = 0;
    nc_inq(id, &ndims, &nvars, &ngatts, &unlim);
    for (int d = 0; d < ndims; ++d) {
        char name[NC_MAX_NAME + 1] = {0};
        std::size_t len = 0;
        nc_inq_dim(id, d, name, &len);
        m.dims.emplace_back(name, len);
    }
    for (int v = 0; v < nvars; ++v) {
        char name[NC_MAX_NAME + 1] = {0};
        Var var;
        int nd = 0, natts = 0;
        int dimids[NC_MAX_VAR_DIMS];
        nc_inq_var(id, v, name, &var.type, &nd, dimids, &natts);
        var.name = name;
        var.dims.assign(dimids, dimids + nd);
        const std::size_t n = m.size_of(var);
        if (var.type == NC_STRING) {
            std::vector<char*> p(n);
            nc_get_var_string(id, v, p.data());
            for (auto* s : p) var.texts.emplace_back(s ? s : "");
            nc_free_string(n, p.data());
        } else if (var.type == NC_CHAR) {
            std::string all(n, '\0');
            if (n) nc_get_var_text(id, v, all.data());
            const std::size_t length = m.text_length(var);
            for (std::size_t k = 0; length && k + length <= all.size(); k += length) {
                std::string one = all.substr(k, length);
                one.erase(std::find(one.begin(), one.end(), '\0'), one.end());
                var.texts.push_back(one);
            }
            if (!length) var.texts.push_back(all);
        } else {
            var.numbers.resize(n);
            nc_get_var_double(id, v, var.numbers.data());
        }
        var.atts = read_atts(id, v, natts);
        m.vars.push_back(var);
    }
    m.atts = read_atts(id, NC_GLOBAL, ngatts);
    nc_close(id);
    return m;
}

bool save_model(const Model& m, const std::string& path) {
    int id = -1;
    if (nc_create(path.c_str(), NC_CLOBBER | NC_NETCDF4, &id) != NC_NOERR) return false;
    bool ok = true;
    std::vector<int> dimids;
    for (const auto& [name, len] : m.dims) {
        int d = -1;
        ok = ok && nc_def_dim(id, name.c_str(), len, &d) == NC_NOERR;
        dimids.push_back(d);
    }
    std::vector<int> varids;
    for (const Var& v : m.vars) {
        std::vector<int> dims;
        for (int d : v.dims) dims.push_back(dimids[std::size_t(d)]);
        int vid = -1;
        ok = ok && nc_def_var(id, v.name.c_str(), v.type, int(dims.size()), dims.data(), &vid) == NC_NOERR;
        if (ok) put_atts(id, vid, &v, v.atts);
        varids.push_back(vid);
    }
    if (ok) put_atts(id, NC_GLOBAL, nullptr, m.atts);
    ok = ok && nc_enddef(id) == NC_NOERR;
    for (std::size_t k = 0; ok && k < m.vars.size(); ++k) {
        const Var& v = m.vars[k];
        if (m.size_of(v) == 0) continue;
        if (v.type == NC_STRING) {
            std::vector<const char*> p;
            for (const auto& s : v.texts) p.push_back(s.c_str());
            nc_put_var_string(id, varids[k], p.data());
        } else if (v.type == NC_CHAR) {
            const std::size_t length = m.text_length(v);
            std::string all(m.size_of(v), '\0');
            for (std::size_t q = 0; q < v.texts.size() && length; ++q)
                std::copy_n(v.texts[q].begin(), std::min(v.texts[q].size(), length), all.begin() + std::ptrdiff_t(q * length));
            nc_put_var_text(id, varids[k], all.data());
        } else {
            nc_put_var_double(id, varids[k], v.numbers.data());  // out-of-range values stay fill
        }
    }
    nc_close(id);
    return ok;
}

Var& var_named(Model& m, const std::string& name) {
    for (Var& v : m.vars)
        if (v.name == name) return v;
    throw std::runtime_error("no variable " + name);
}

}  // namespace flotsam::fuzz
