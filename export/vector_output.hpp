// Writing GIS vector files from export/: layers written under a temporary name and renamed
// when complete (shapefile sidecars with them), with their QGIS styles; fields; grids of
// ids as polygons; and GDAL's failures named with the file and, on a full disk, the free
// space.
#pragma once
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "common/cf.hpp"
#include "common/grid.hpp"
#include "data/gdal_support.hpp"
#include "export/qgis_style.hpp"

namespace flotsam::gis {

// <stem>.part<ext>: a temporary name that keeps the extension (GDAL's vector drivers go
// by it). Shapefile sidecars (.shx, .dbf, .prj, .cpg) follow the .shp.
std::string partial_name(const std::string& path);
void remove_with_sidecars(const std::string& path);
void rename_with_sidecars(const std::string& from, const std::string& to);

// Throws "<path>: <what>: GDAL could not <doing>: <GDAL's message>", with the free space
// when the disk is full (GDAL then says "no such table" or nothing at all).
[[noreturn]] void fail_writing(const std::string& path, const std::string& what, const std::string& doing);

void add_field(OGRLayer& layer, const std::string& out_path, const std::string& name, OGRFieldType type);

// One layer to write: its name, geometry, styles (the first the default) and writer, which
// returns the features written.
struct VectorLayerDef {
    std::string name;
    OGRwkbGeometryType geometry = wkbUnknown;
    std::vector<qgis::NamedStyle> styles;
    std::function<std::size_t(OGRLayer&)> write;
};

// Layers in `crs` (read from `crs_file` for messages), each written by its `write`, into a
// file of GDAL's `driver_name` under a temporary name: renamed (with shapefile sidecars)
// when complete and closed without an error, removed when a writer throws. A GeoPackage
// keeps the styles in its layer_styles table; another format gets the default style as
// <stem>.qml beside it (QGIS loads it with the file). The GeoPackage's dates are fixed:
// the same inputs give the same bytes. Returns the features written.
std::size_t write_vector_layers(const std::string& out_path, const char* driver_name, const cf::GridMapping& crs,
                                const std::string& crs_file, const std::vector<VectorLayerDef>& defs);

// The pieces (4-connected cells of one value) of every positive id of a grid of ids
// (row-major, southern row first; 0: none), as polygons in the grid's coordinates.
std::map<int, OGRMultiPolygon> polygons_of(const Grid& g, const std::vector<std::int32_t>& ids, const std::string& out_path);

}  // namespace flotsam::gis
