// A NetCDF file held in memory (dimensions, variables with their values, attributes),
// edited and written back: what the fuzz targets mutate and the bad-file builders
// (fuzz/bad_files.hpp) change one thing in.
#pragma once
#include <netcdf.h>

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace flotsam::fuzz {

struct Att {
    std::string name;
    nc_type type = NC_CHAR;
    std::string text;
    std::vector<double> numbers;
};
struct Var {
    std::string name;
    nc_type type = NC_DOUBLE;
    std::vector<int> dims;  // indices into Model::dims
    std::vector<double> numbers;
    std::vector<std::string> texts;  // NC_STRING, or NC_CHAR (its last dimension the string length)
    bool is_text() const { return type == NC_STRING || type == NC_CHAR; }
    std::vector<Att> atts;
};
struct Model {
    std::vector<std::pair<std::string, std::size_t>> dims;
    std::vector<Var> vars;
    std::vector<Att> atts;
    std::size_t size_of(const Var& v) const {
        std::size_t n = 1;
        for (int d : v.dims) n *= dims[std::size_t(d)].second;
        return n;
    }
    // The strings of a character array: all its dimensions but the last.
    std::size_t strings_of(const Var& v) const {
        if (v.type != NC_CHAR) return size_of(v);
        std::size_t n = 1;
        for (std::size_t k = 0; k + 1 < v.dims.size(); ++k) n *= dims[std::size_t(v.dims[k])].second;
        return v.dims.empty() ? 1 : n;
    }
    std::size_t text_length(const Var& v) const {
        return v.type == NC_CHAR && !v.dims.empty() ? dims[std::size_t(v.dims.back())].second : 0;
    }
    void fit(Var& v) const {
        const std::size_t n = strings_of(v);
        if (v.is_text())
            v.texts.resize(n);
        else
            v.numbers.resize(n, v.numbers.empty() ? 0.0 : v.numbers.back());
    }
};

// The whole file (throws std::runtime_error when NetCDF cannot open it).
Model load_model(const std::string& path);
// Writes the model; false when NetCDF refuses it (an edit made it inconsistent).
bool save_model(const Model& m, const std::string& path);
// The variable called `name` (throws std::runtime_error when there is none).
Var& var_named(Model& m, const std::string& name);

}  // namespace flotsam::fuzz
