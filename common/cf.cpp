#include "common/cf.hpp"

#include <cmath>

namespace flotsam::cf {

int def_var(nc::File& f, const VarDef& v) {
    const int id = f.def_var(v.name, v.type, v.dims);
    if (!v.chunks.empty()) f.def_chunking(id, v.chunks);
    if (v.deflate > 0) f.def_deflate(id, v.deflate, true);
    if (!v.standard_name.empty()) f.put_att(id, "standard_name", v.standard_name);
    if (!v.units.empty()) f.put_att(id, "units", v.units);
    if (!v.long_name.empty()) f.put_att(id, "long_name", v.long_name);
    if (!v.coordinates.empty()) f.put_att(id, "coordinates", v.coordinates);
    if (v.fill) f.def_fill(id, fill_value);
    return id;
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
