#include "data/gdal_support.hpp"

#include <cpl_conv.h>
#include <cpl_error.h>

#include <fstream>
#include <mutex>
#include <sstream>

#include "common/checks.hpp"
#include "common/error.hpp"

namespace flotsam::gdal {

namespace {

thread_local std::string g_last_error;

void CPL_STDCALL record_error(CPLErr level, CPLErrorNum, const char* message) {
    if (level >= CE_Failure) g_last_error = message ? message : "";
}

}  // namespace

void init() {
    static std::once_flag once;
    std::call_once(once, [] {
        GDALAllRegister();
        CPLSetErrorHandler(record_error);
    });
}

bool error_pending() { return !g_last_error.empty(); }

std::string last_error() {
    std::string e = g_last_error;
    g_last_error.clear();
    return e.empty() ? std::string("(GDAL gave no reason)") : e;
}

Dataset open_raster(const std::string& path) {
    check_gis_input("", path);  // a FIFO beside or in its place would block GDAL for ever
    init();
    g_last_error.clear();
    GDALDataset* d =
        GDALDataset::FromHandle(GDALOpenEx(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY, nullptr, nullptr, nullptr));
    if (!d) fail(path, "", "GDAL cannot read it as a raster: " + last_error());
    return Dataset(d);
}

Dataset open_vector(const std::string& path) {
    check_gis_input("", path);  // a FIFO beside or in its place would block GDAL for ever
    init();
    g_last_error.clear();
    GDALDataset* d =
        GDALDataset::FromHandle(GDALOpenEx(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY, nullptr, nullptr, nullptr));
    if (!d) fail(path, "", "GDAL cannot read it as a vector file: " + last_error());
    return Dataset(d);
}

const OGRSpatialReference* layer_crs(OGRLayer& layer) {
    const OGRSpatialReference* crs = layer.GetSpatialRef();
    const std::string name = crs && crs->GetName() ? crs->GetName() : "";
    return name == "Undefined geographic SRS" || name == "Undefined Cartesian SRS" ? nullptr : crs;
}

OGRSpatialReference crs_from_text(const std::string& text, const std::string& what) {
    init();
    OGRSpatialReference s;
    s.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    std::string definition = text;
    if (text.find('[') == std::string::npos) check_input_file(what, text);  // a FIFO named as a .prj would never end
    if (std::ifstream in(text); in && text.find('[') == std::string::npos) {  // a .prj or a file holding WKT
        std::stringstream ss;
        ss << in.rdbuf();
        definition = ss.str();
    }
    g_last_error.clear();
    if (s.SetFromUserInput(definition.c_str()) != OGRERR_NONE)
        fail(what, "'" + text + "'", "not a coordinate reference system GDAL knows (EPSG:n, WKT or PROJ): " + last_error());
    return s;
}

std::string label(const OGRSpatialReference& crs) {
    const char* auth = crs.GetAuthorityName(nullptr);
    const char* code = crs.GetAuthorityCode(nullptr);
    if (auth && code) return std::string(auth) + ":" + code;
    const char* name = crs.GetName();
    return name ? name : "unnamed CRS";
}

namespace {

std::string wkt_of(const OGRSpatialReference& crs, const char* format) {
    char* p = nullptr;
    const char* options[] = {format, nullptr};
    const OGRErr err = crs.exportToWkt(&p, options);
    std::string s = (err == OGRERR_NONE && p) ? p : "";
    CPLFree(p);
    return s;
}

}  // namespace

cf::GridMapping grid_mapping(const OGRSpatialReference& crs) {
    cf::GridMapping g;
    auto text = [&](const char* name, const std::string& value) { g.attributes.push_back({name, value, {}}); };
    auto number = [&](const char* name, std::vector<double> v) { g.attributes.push_back({name, "", std::move(v)}); };
    auto parm = [&](const char* p) { return crs.GetNormProjParm(p, 0.0); };
    const char* method = crs.IsProjected() ? crs.GetAttrValue("PROJECTION") : nullptr;
    const std::string m = method ? method : "";
    auto false_origin = [&] {
        number("false_easting", {parm(SRS_PP_FALSE_EASTING)});
        number("false_northing", {parm(SRS_PP_FALSE_NORTHING)});
    };
    if (m == SRS_PT_TRANSVERSE_MERCATOR) {
        text("grid_mapping_name", "transverse_mercator");
        number("scale_factor_at_central_meridian", {parm(SRS_PP_SCALE_FACTOR)});
        number("longitude_of_central_meridian", {parm(SRS_PP_CENTRAL_MERIDIAN)});
        number("latitude_of_projection_origin", {parm(SRS_PP_LATITUDE_OF_ORIGIN)});
        false_origin();
    } else if (m == SRS_PT_LAMBERT_CONFORMAL_CONIC_2SP) {
        text("grid_mapping_name", "lambert_conformal_conic");
        number("standard_parallel", {parm(SRS_PP_STANDARD_PARALLEL_1), parm(SRS_PP_STANDARD_PARALLEL_2)});
        number("longitude_of_central_meridian", {parm(SRS_PP_CENTRAL_MERIDIAN)});
        number("latitude_of_projection_origin", {parm(SRS_PP_LATITUDE_OF_ORIGIN)});
        false_origin();
    } else if (m == SRS_PT_MERCATOR_1SP) {
        text("grid_mapping_name", "mercator");
        number("longitude_of_projection_origin", {parm(SRS_PP_CENTRAL_MERIDIAN)});
        number("scale_factor_at_projection_origin", {parm(SRS_PP_SCALE_FACTOR)});
        false_origin();
    } else if (m == SRS_PT_ALBERS_CONIC_EQUAL_AREA) {
        text("grid_mapping_name", "albers_conical_equal_area");
        number("standard_parallel", {parm(SRS_PP_STANDARD_PARALLEL_1), parm(SRS_PP_STANDARD_PARALLEL_2)});
        number("longitude_of_central_meridian", {parm(SRS_PP_LONGITUDE_OF_CENTER)});
        number("latitude_of_projection_origin", {parm(SRS_PP_LATITUDE_OF_CENTER)});
        false_origin();
    } else if (m == SRS_PT_LAMBERT_AZIMUTHAL_EQUAL_AREA) {
        text("grid_mapping_name", "lambert_azimuthal_equal_area");
        number("longitude_of_projection_origin", {parm(SRS_PP_LONGITUDE_OF_CENTER)});
        number("latitude_of_projection_origin", {parm(SRS_PP_LATITUDE_OF_CENTER)});
        false_origin();
    }
    // Other projections: crs_wkt alone, which GDAL and QGIS read.
    if (crs.IsProjected() || crs.IsGeographic()) {
        number("semi_major_axis", {crs.GetSemiMajor()});
        number("inverse_flattening", {crs.GetInvFlattening()});
        number("longitude_of_prime_meridian", {crs.GetPrimeMeridian()});
    }
    std::string wkt = wkt_of(crs, "FORMAT=WKT1_GDAL");
    if (wkt.empty()) wkt = wkt_of(crs, "FORMAT=WKT2_2019");
    text("crs_wkt", wkt);
    text("spatial_ref", wkt);
    return g;
}

OGRSpatialReference spatial_ref(const cf::GridMapping& crs, const std::string& what) {
    init();
    const std::string wkt = crs.wkt();
    if (wkt.empty()) fail(what, "variable 'crs'", "has no crs_wkt attribute (the CRS cannot be rebuilt from it)");
    OGRSpatialReference s;
    s.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    if (s.importFromWkt(wkt.c_str()) != OGRERR_NONE) fail(what, "variable 'crs' attribute 'crs_wkt'", "not WKT that GDAL reads");
    return s;
}

void geotransform(const Grid& g, double gt[6]) {
    gt[0] = g.x_min_edge();
    gt[1] = g.dx;
    gt[2] = 0.0;
    gt[3] = g.y_max_edge();
    gt[4] = 0.0;
    gt[5] = -g.dy;
}

}  // namespace flotsam::gdal
