// GIS data into a scene: a DEM from any raster GDAL reads, with its CRS,
// vertical datum and nodata; building footprints from a vector file, burnt into the
// building mask and, with heights, into z; Manning n from a land-use raster or from
// polygons. dem_import.cpp calls these; the flume's own NetCDF and ESRI ASCII grids in
// local metres still go through its own readers, byte for byte as before.
#pragma once
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "common/cf.hpp"
#include "common/grid.hpp"
#include "formats/scene.hpp"

namespace flotsam {

struct Dem;

// Everything about an import that concerns GIS data. All optional.
struct GisImportDef {
    // The DEM's CRS when its file carries none ("EPSG:32653", WKT, PROJ, or a .prj file),
    // or "local" for local metres; a CRS in the file is replaced (and said so).
    std::string assign_crs;
    // Reproject the DEM to this projected CRS (metres) at the scene's --resolution; needed
    // for a DEM in geographic coordinates (degrees). Vector files follow the scene's CRS.
    std::string target_crs;
    // The DEM's value at still water, in its own vertical datum (e.g. 0.8 for a DEM above
    // T.P. when the still water stands 0.8 m above it): z = DEM value - this [m].
    double still_water_level = 0.0;
    // Keep only cells whose centres lie in x_min, x_max, y_min, y_max [m, scene CRS].
    std::optional<std::array<double, 4>> extent;
    // Elevation for the DEM's nodata cells [m above still water]; without it a nodata
    // cell inside the (cropped) domain is an error.
    std::optional<double> nodata_fill;

    std::string buildings;                  // footprint polygons (GeoJSON, shapefile, GeoPackage, ...)
    std::string buildings_layer;            // layer name; "": the first
    std::string building_height_field;      // attribute with the height above ground [m]; "": none
    std::optional<double> building_height;  // [m] for footprints without a height value

    std::string manning_raster;       // land-use classes (with manning_classes) or n values
    std::string manning_classes;      // CSV "class,n" mapping land-use codes to n [s m^-1/3]
    std::string manning_polygons;     // polygons with an n attribute; they win over the raster
    std::string manning_field = "n";  // that attribute

    // True when the DEM must go through GDAL (reprojection, cropping or filling).
    bool needs_gdal_raster() const { return !target_crs.empty() || extent.has_value() || nodata_fill.has_value(); }
};

// Reads any raster GDAL reads as a DEM on its own grid (rows south first), with the CRS
// checks, reprojection, datum offset, cropping and nodata rules of `gis`. `resolution` is
// the grid spacing a reprojection warps to [m]. Errors name the file and what is wrong:
// no CRS, geographic coordinates without --target-crs, units that are not metres, a
// rotated or irregular grid, nodata inside the domain.
Dem read_gis_dem(const std::string& path, const GisImportDef& gis, double resolution);

// The CRS of an ESRI ASCII grid's .prj beside it, or of --crs; empty when neither.
cf::GridMapping sidecar_or_assigned_crs(const std::string& dem_path, const GisImportDef& gis);

// Crops a DEM to gis.extent and applies the datum offset (for the DEMs read without GDAL).
void apply_extent_and_datum(Dem& dem, const GisImportDef& gis);

// Burns gis.buildings into s.building (replacing the mask) and s.building_id (each cell the
// number of its footprint: its place in the layer, from 1) and, where a footprint has a
// height, raises z to the footprint's lowest ground plus that height. Returns a line
// for the user (what was burnt, any reprojection).
std::string burn_building_footprints(Scene& s, const GisImportDef& gis);

// Manning n on the scene grid: `base` (from the rules; may be empty), overridden by the
// land-use raster where it has data and by the polygons where they lie. Errors name the
// file: a class missing from the table, a value outside [0, 1), cells left without n.
std::vector<double> manning_from_gis(const Scene& s, const GisImportDef& gis, std::vector<double> base, std::string& note);

}  // namespace flotsam
