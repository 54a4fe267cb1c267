// The little of GDAL that flotsam uses, wrapped: opening rasters and vector files with
// errors that name the file, coordinate reference systems from user text, and the CF
// grid mapping (common/cf.hpp) of a CRS and back. Only data/ (import) and export/ (GIS
// output) include this: hydro, debris and the file formats never need GDAL.
#pragma once
#include <gdal_priv.h>
#include <ogr_spatialref.h>
#include <ogrsf_frmts.h>

#include <memory>
#include <string>

#include "common/cf.hpp"
#include "common/grid.hpp"

namespace flotsam::gdal {

// Registers GDAL's drivers (once) and routes GDAL's own error messages into the Error
// that flotsam throws, instead of GDAL printing them.
void init();

// The text of GDAL's last error since the call began (for messages), then cleared.
std::string last_error();
// Whether GDAL reported a failure since last_error() was last read (a close that could
// not flush its data says so only this way).
bool error_pending();

struct DatasetClose {
    void operator()(GDALDataset* d) const { GDALClose(GDALDataset::ToHandle(d)); }
};
using Dataset = std::unique_ptr<GDALDataset, DatasetClose>;

// Opens read-only; errors name the file and what GDAL said.
Dataset open_raster(const std::string& path);
Dataset open_vector(const std::string& path);

// A vector layer's CRS; null when it has none, a GeoPackage's placeholders for none
// ("Undefined geographic SRS", "Undefined Cartesian SRS") included.
const OGRSpatialReference* layer_crs(OGRLayer& layer);

// A CRS from what a user types: "EPSG:32653", WKT, a PROJ string, or a file holding one
// (a .prj). `what` names the option or file for the error.
OGRSpatialReference crs_from_text(const std::string& text, const std::string& what);

// The CF grid mapping of a CRS: crs_wkt (WKT1 as GDAL writes it, which GDAL, QGIS and
// the netCDF-Java tools all read), spatial_ref (the same; older GDAL looks there), and
// the CF projection parameters for the projections with a CF name (transverse Mercator,
// hence UTM; Lambert conformal conic; Mercator; polar stereographic; Albers; oblique
// stereographic; Lambert azimuthal equal area) with the ellipsoid.
cf::GridMapping grid_mapping(const OGRSpatialReference& crs);
// The CRS of a grid mapping (from crs_wkt); `what` names the file for the error.
OGRSpatialReference spatial_ref(const cf::GridMapping& crs, const std::string& what);

// A short label: "EPSG:32653" or the CRS's name.
std::string label(const OGRSpatialReference& crs);

// The GDAL geotransform of a flotsam grid, north-up (row 0 is the northern row).
void geotransform(const Grid& g, double gt[6]);

}  // namespace flotsam::gdal
