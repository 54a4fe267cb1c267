// The CF conventions as flotsam writes them, in one place: the time axis, the x/y axes,
// and a variable with its units, standard name, coordinates and storage. Every writer
// (scene, flow, trajectory, sweep, statistics) labels its data through these, so xarray,
// ncview, cdo, QGIS and GDAL read all of them the same way.
#pragma once
#include <netcdf.h>

#include <cstddef>
#include <string>
#include <vector>

#include "common/netcdf.hpp"

namespace flotsam::cf {

inline constexpr const char* conventions = "CF-1.11";
// A flume run has no date; a fixed epoch lets CF tools decode the times anyway.
inline constexpr const char* time_units = "seconds since 2000-01-01 00:00:00";
// NetCDF's default fill value of doubles (NC_FILL_DOUBLE): "no value" in every file.
inline constexpr double fill_value = 9.969209968386869e36;

// One variable. Attributes are written in this order: standard_name, units, long_name,
// coordinates, then _FillValue; empty strings are left out.
struct VarDef {
    std::string name;
    nc_type type = NC_DOUBLE;
    std::vector<int> dims;
    std::string units;          // UDUNITS; "" for strings, indices and flags
    std::string standard_name;  // CF standard name; "" where none fits
    std::string long_name;
    std::string coordinates;          // auxiliary coordinates, e.g. "time y x"
    std::vector<std::size_t> chunks;  // empty: the library's default layout
    int deflate = 0;                  // 0 (off) .. 9, with the shuffle filter
    bool fill = false;                // missing values are stored as fill_value
};
int def_var(nc::File& f, const VarDef& v);

// A time coordinate variable (double, seconds since the epoch above) on `dim`; `axis`
// marks it as the file's T axis (a second time axis, such as gauge samples, leaves it out).
int def_time(nc::File& f, int dim, const std::string& name = "time", const std::string& long_name = "", bool axis = true);

// The x and y coordinate variables of a grid (double, m, east and north); `what` says
// which points they locate, e.g. "cell centre".
struct XYAxes {
    int x, y;
};
XYAxes def_xy(nc::File& f, int x_dim, int y_dim, const std::string& what);

// Global Conventions, and featureType when not empty.
void put_conventions(nc::File& f, const std::string& feature_type = "");

// NaN becomes fill_value (NetCDF readers then mask it).
std::vector<double> filled(std::vector<double> v);
std::vector<float> filled(std::vector<float> v);

}  // namespace flotsam::cf
