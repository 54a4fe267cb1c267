// Bodies from GIS debris sources (data/debris_sources.hpp): each feature's catalogue entry,
// its size and mass attributes over the entry's, and a yard's bodies laid out by
// debris/source_layout.hpp. Used by `flotsam debris --sources` and sweep specs' [[sources]].
#pragma once
#include <string>
#include <vector>

#include "debris/body.hpp"
#include "formats/scene.hpp"

namespace flotsam {

struct SourcedBody {
    debris::BodyDef def;  // name "layer/fid" for a point, "layer/fid/k" for the k-th body of a yard (k from 1)
    std::string source;   // "layer/fid": the feature it came from
    std::string type;     // its catalogue entry
};

// `model` gives every body's model settings (contact, collision, samples, step
// tolerance); the catalogue entry of each feature gives shape, mass and coefficients.
// Errors name the feature: an unknown type, a yard that holds fewer bodies than its count.
std::vector<SourcedBody> bodies_from_sources(const std::string& path, const std::vector<std::string>& layers,
                                             const Scene& scene, const debris::BodyDef& model);

}  // namespace flotsam
