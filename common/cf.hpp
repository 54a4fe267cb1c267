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
// A flume run has no date; a fixed epoch lets CF tools decode the times anyway. It stands
// for the start of the run, and every time variable says so (time_origin).
inline constexpr const char* time_units = "seconds since 2000-01-01 00:00:00";
inline constexpr const char* time_origin =
    "t = 0 is the start of the run (time 0 of its boundary records); the run has no calendar date, so the units' "
    "2000-01-01 00:00:00 stands for that start and a clock time (QGIS, ncview) reads as the time since it";
// NetCDF's default fill value of doubles (NC_FILL_DOUBLE): "no value" in every file.
inline constexpr double fill_value = 9.969209968386869e36;

// One variable. Attributes are written in this order: standard_name, units, long_name,
// coordinates, grid_mapping, then _FillValue; empty strings are left out.
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
    std::string grid_mapping;         // the grid-mapping variable locating x/y ("crs"); "": none
    std::size_t text_length = 0;      // NC_CHAR: the longest string [bytes] (nc::File::def_text_var)
};
// The length of the longest string (for VarDef::text_length).
std::size_t longest(const std::vector<std::string>& values);
int def_var(nc::File& f, const VarDef& v);

// A coordinate reference system as a CF grid-mapping variable: a scalar variable whose
// attributes describe the projection (grid_mapping_name, false_easting, ...) and carry
// the whole definition as OGC WKT in crs_wkt, which GDAL and QGIS read. Gridded
// variables point at it with their grid_mapping attribute; their x and y are then the
// projection coordinates of that CRS in metres. A scene in local metres (the flume)
// has none, and its files are written exactly as without this layer.
struct GridMapping {
    struct Attribute {
        std::string name;
        std::string text;             // a text attribute when `numbers` is empty
        std::vector<double> numbers;  // a numeric attribute (one value or several)
    };
    std::vector<Attribute> attributes;  // in writing order
    bool empty() const { return attributes.empty(); }
    const Attribute* find(const std::string& name) const;
    std::string wkt() const;   // crs_wkt, or "" when absent
    std::string name() const;  // a short label: the EPSG code when the WKT names one, else grid_mapping_name
};
// The name every flotsam file gives its grid-mapping variable.
inline constexpr const char* crs_variable = "crs";
// Defines the grid-mapping variable `crs` (int, no dimensions) with crs's attributes;
// returns its id, or -1 without defining anything when crs is empty.
int def_crs(nc::File& f, const GridMapping& crs);
// The grid-mapping variable named by `data_var`'s grid_mapping attribute (empty when the
// variable or the attribute is absent). Errors name the file when the attribute names a
// variable that is not there.
GridMapping read_crs(const nc::File& f, const std::string& data_var);
// Throws naming both files when their CRSs differ (one in local metres and one in a map
// projection, or two projections): their x and y would mean other places.
void check_same_crs(const std::string& a_path, const GridMapping& a, const std::string& b_path, const GridMapping& b);
// What to put in VarDef::grid_mapping for a file with this CRS.
inline std::string grid_mapping_of(const GridMapping& crs) { return crs.empty() ? std::string() : std::string(crs_variable); }

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

// ---- the kind of a flotsam file ----
//
// Every file flotsam writes says what it is in the global attribute flotsam_file_kind:
// "scene", "flow", "trajectories" (flotsam debris), "sweep", "stats". Readers check it
// before anything else, so a flow given as a scene is refused by name instead of read as
// one. Files written before the attribute existed are recognised by their variables.
inline constexpr const char* kind_attribute = "flotsam_file_kind";
void put_kind(nc::File& f, const std::string& kind);
// The file's kind: the attribute, else what its variables say ("" when none fits: a file
// from another program, read on its own terms).
std::string kind_of(const nc::File& f);
// Throws "<path>: is a flow file (written by `flotsam hydro`), not a scene ..." when the
// file's kind is known and is none of `accepted` (the first one names what was wanted).
void require_kind(const nc::File& f, const std::vector<std::string>& accepted, const std::string& option = "");

// NaN becomes fill_value (NetCDF readers then mask it).
std::vector<double> filled(std::vector<double> v);
std::vector<float> filled(std::vector<float> v);

}  // namespace flotsam::cf
