#include "data/source_features.hpp"

#include "common/checks.hpp"
#include "common/error.hpp"
#include "data/vector_layer.hpp"

namespace flotsam {

namespace {

using FeaturePtr = std::unique_ptr<OGRFeature, void (*)(OGRFeature*)>;

// A number attribute, NaN when absent or null; refused when not finite or not > 0 (when `positive`).
double number_field(const VectorLayer& v, const OGRFeature& f, const std::string& where, const char* name, bool positive) {
    const int k = v.field_index(name);
    if (k < 0 || !f.IsFieldSetAndNotNull(k)) return std::nan("");
    const OGRFieldType t = f.GetFieldDefnRef(k)->GetType();
    if (t != OFTInteger && t != OFTInteger64 && t != OFTReal) fail(where, std::string("attribute '") + name + "'", "is not a number");
    const double value = f.GetFieldAsDouble(k);
    if (!std::isfinite(value) || (positive && !(value > 0)))
        fail(where, std::string("attribute '") + name + "' = " + number_text(value), positive ? "must be a positive number" : "must be finite");
    return value;
}

std::vector<std::array<double, 2>> ring_points(const OGRLinearRing& r) {
    std::vector<std::array<double, 2>> out;
    for (int i = 0; i < r.getNumPoints(); ++i) out.push_back({r.getX(i), r.getY(i)});
    if (out.size() > 1 && out.front() == out.back()) out.pop_back();
    return out;
}

SourceFeature read_feature(const VectorLayer& v, const OGRFeature& f) {
    SourceFeature s;
    s.layer = v.layer->GetName();
    s.fid = f.GetFID();
    s.where = v.where + " feature " + std::to_string(s.fid);
    const std::unique_ptr<OGRGeometry> g = v.geometry_in_scene(f);
    if (!g || g->IsEmpty()) fail(s.where, "geometry", "none: give a point (one body) or a polygon (a yard)");
    const OGRwkbGeometryType type = wkbFlatten(g->getGeometryType());
    const OGRGeometry* single = g.get();
    if ((type == wkbMultiPoint || type == wkbMultiPolygon) && g->toGeometryCollection()->getNumGeometries() == 1)
        single = g->toGeometryCollection()->getGeometryRef(0);
    const OGRwkbGeometryType t1 = wkbFlatten(single->getGeometryType());
    if (t1 == wkbPoint) {
        s.x = single->toPoint()->getX();
        s.y = single->toPoint()->getY();
    } else if (t1 == wkbPolygon) {
        s.is_yard = true;
        const OGRPolygon* p = single->toPolygon();
        s.rings.push_back(ring_points(*p->getExteriorRing()));
        for (int k = 0; k < p->getNumInteriorRings(); ++k) s.rings.push_back(ring_points(*p->getInteriorRing(k)));
        if (s.rings.front().size() < 3) fail(s.where, "polygon", "its outline has fewer than three points");
    } else {
        fail(s.where, std::string("geometry ") + OGRGeometryTypeToName(g->getGeometryType()),
             type == wkbMultiPoint || type == wkbMultiPolygon
                 ? "has several parts: give each point or yard as its own feature"
                 : "is neither a point (one body) nor a polygon (a yard)");
    }
    const int kt = v.field_index("type");
    if (kt < 0) fail(v.where, "attribute 'type'", "missing: each feature names its debris catalogue entry (fields: " + v.field_names() + ")");
    s.type = f.IsFieldSetAndNotNull(kt) ? f.GetFieldAsString(kt) : "";
    if (s.type.empty()) fail(s.where, "attribute 'type'", "empty: name a debris catalogue entry");
    const double heading = number_field(v, f, s.where, "heading", false), bearing = number_field(v, f, s.where, "bearing", false);
    for (const auto& [name, angle] : {std::pair{"heading", heading}, std::pair{"bearing", bearing}})
        if (!std::isnan(angle)) check_range(std::string("attribute '") + name + "'", angle, Range::closed(-360.0, 360.0, "degree"), s.where);
    if (!std::isnan(heading) && !std::isnan(bearing))
        fail(s.where, "attributes 'heading' and 'bearing'", "both given: give one (heading from east counter-clockwise, bearing from north clockwise)");
    s.heading_deg = std::isnan(bearing) ? heading : 90.0 - bearing;
    s.mass = number_field(v, f, s.where, "mass", true);
    s.length = number_field(v, f, s.where, "length", true);
    s.width = number_field(v, f, s.where, "width", true);
    s.height = number_field(v, f, s.where, "height", true);
    const double count = number_field(v, f, s.where, "count", false), gap = number_field(v, f, s.where, "gap", false);
    if (!s.is_yard && (!std::isnan(count) || !std::isnan(gap)))
        fail(s.where, std::string("attribute '") + (std::isnan(count) ? "gap" : "count") + "'", "given on a point: a point is one body (count and gap are for yards)");
    if (!std::isnan(count) && !(count >= 1 && count <= 1e6 && count == std::floor(count)))
        fail(s.where, "attribute 'count' = " + number_text(count), "must be a whole number from 1 to 1e6");
    if (!std::isnan(gap) && !(gap >= 0)) fail(s.where, "attribute 'gap' = " + number_text(gap), "must be 0 or more [m]");
    if (s.is_yard && std::isnan(count) && std::isnan(gap))
        fail(s.where, "attributes 'count' and 'gap'", "neither given: a yard needs how many bodies (count) or how far apart (gap, m)");
    s.count = std::isnan(count) ? 0 : int(count);
    s.gap = gap;
    return s;
}

}  // namespace

std::vector<SourceFeature> read_source_features(const std::string& path, const std::vector<std::string>& layers,
                                               const Scene& scene) {
    std::vector<SourceFeature> out;
    const std::vector<std::string> names = layers.empty() ? vector_layer_names(path) : layers;
    for (const auto& name : names) {
        const VectorLayer v = open_vector_layer(path, name, scene);
        const std::size_t before = out.size();
        for (OGRFeature* raw; (raw = v.layer->GetNextFeature()) != nullptr;) {
            const FeaturePtr f(raw, OGRFeature::DestroyFeature);
            out.push_back(read_feature(v, *f));
        }
        if (out.size() == before && !layers.empty()) fail(v.where, "features", "none in the layer");
    }
    if (out.empty()) fail(path, "features", "no debris sources in the file");
    return out;
}

}  // namespace flotsam
