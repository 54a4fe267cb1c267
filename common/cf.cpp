#include "common/cf.hpp"

#include <cctype>
#include <cmath>
#include <string>

#include "common/error.hpp"

namespace flotsam::cf {

int def_var(nc::File& f, const VarDef& v) {
    const int id = f.def_var(v.name, v.type, v.dims);
    if (!v.chunks.empty()) f.def_chunking(id, v.chunks);
    if (v.deflate > 0) f.def_deflate(id, v.deflate, true);
    if (!v.standard_name.empty()) f.put_att(id, "standard_name", v.standard_name);
    if (!v.units.empty()) f.put_att(id, "units", v.units);
    if (!v.long_name.empty()) f.put_att(id, "long_name", v.long_name);
    if (!v.coordinates.empty()) f.put_att(id, "coordinates", v.coordinates);
    if (!v.grid_mapping.empty()) f.put_att(id, "grid_mapping", v.grid_mapping);
    if (v.fill) f.def_fill(id, fill_value);
    return id;
}

const GridMapping::Attribute* GridMapping::find(const std::string& name) const {
    for (const auto& a : attributes)
        if (a.name == name) return &a;
    return nullptr;
}

std::string GridMapping::wkt() const {
    const Attribute* a = find("crs_wkt");
    return a ? a->text : std::string();
}

std::string GridMapping::name() const {
    // The last AUTHORITY["EPSG","n"] (WKT1) or ID["EPSG",n] (WKT2) is the CRS's own.
    const std::string w = wkt();
    for (const char* key : {"AUTHORITY[\"EPSG\",\"", "ID[\"EPSG\","}) {
        const auto at = w.rfind(key);
        if (at == std::string::npos) continue;
        std::string code;
        for (std::size_t k = at + std::char_traits<char>::length(key); k < w.size() && std::isdigit((unsigned char)w[k]); ++k)
            code += w[k];
        if (!code.empty()) return "EPSG:" + code;
    }
    const Attribute* g = find("grid_mapping_name");
    return g ? g->text : std::string(empty() ? "" : "custom");
}

int def_crs(nc::File& f, const GridMapping& crs) {
    if (crs.empty()) return -1;
    const int id = f.def_var(crs_variable, NC_INT, {});
    for (const auto& a : crs.attributes) {
        if (a.numbers.empty())
            f.put_att(id, a.name, a.text);
        else
            f.put_att(id, a.name, a.numbers);
    }
    return id;
}

GridMapping read_crs(const nc::File& f, const std::string& data_var) {
    GridMapping crs;
    const auto v = f.find_var(data_var);
    if (!v) return crs;
    const auto name = f.att_text(*v, "grid_mapping");
    if (!name) return crs;
    const auto g = f.find_var(*name);
    if (!g)
        fail(f.path(), "variable '" + data_var + "' attribute 'grid_mapping'", "names '" + *name + "', which is not in the file");
    for (const auto& att : f.att_names(*g)) {
        GridMapping::Attribute a{att, {}, {}};
        if (auto text = f.att_text(*g, att))
            a.text = *text;
        else if (auto numbers = f.att_doubles(*g, att))
            a.numbers = *numbers;
        crs.attributes.push_back(std::move(a));
    }
    return crs;
}

int def_time(nc::File& f, int dim, const std::string& name, const std::string& long_name, bool axis) {
    const int id = f.def_var(name, NC_DOUBLE, {dim});
    f.put_att(id, "standard_name", std::string("time"));
    f.put_att(id, "units", std::string(time_units));
    f.put_att(id, "calendar", std::string("standard"));
    if (axis) f.put_att(id, "axis", std::string("T"));
    if (!long_name.empty()) f.put_att(id, "long_name", long_name);
    return id;
}

XYAxes def_xy(nc::File& f, int x_dim, int y_dim, const std::string& what) {
    auto axis = [&](const char* name, int dim, const char* standard_name, const char* axis_name, const std::string& long_name) {
        const int id = f.def_var(name, NC_DOUBLE, {dim});
        f.put_att(id, "standard_name", std::string(standard_name));
        f.put_att(id, "units", std::string("m"));
        f.put_att(id, "axis", std::string(axis_name));
        f.put_att(id, "long_name", long_name);
        return id;
    };
    const int x = axis("x", x_dim, "projection_x_coordinate", "X", "x of " + what + " (east)");
    const int y = axis("y", y_dim, "projection_y_coordinate", "Y", "y of " + what + " (north)");
    return {x, y};
}

void put_conventions(nc::File& f, const std::string& feature_type) {
    f.put_att(NC_GLOBAL, "Conventions", std::string(conventions));
    if (!feature_type.empty()) f.put_att(NC_GLOBAL, "featureType", feature_type);
}

std::vector<double> filled(std::vector<double> v) {
    for (double& a : v)
        if (std::isnan(a)) a = fill_value;
    return v;
}

std::vector<float> filled(std::vector<float> v) {
    for (float& a : v)
        if (std::isnan(a)) a = float(fill_value);
    return v;
}

}  // namespace flotsam::cf
