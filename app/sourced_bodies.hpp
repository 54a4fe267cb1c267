// Bodies from GIS debris sources (data/source_features.hpp): each feature's catalogue entry,
// its size and mass attributes over the entry's, and a yard's bodies laid out by
// debris/source_layout.hpp. Used by `flotsam debris --sources` and sweep specs' [[sources]].
#pragma once
#include <string>
#include <vector>

#include "debris/body.hpp"
#include "formats/scene.hpp"
#include "sweep/spec_file.hpp"

namespace flotsam {

struct SourcedBody {
    debris::BodyDef def;  // name "layer/fid" for a point, "layer/fid/k" for the k-th body of a yard (k from 1)
    std::string source;   // "layer/fid": the feature it came from
    std::string type;     // its catalogue entry
};

// `model` gives every body's model settings (contact, collision, samples, step
// tolerance); the catalogue entry of each feature gives shape, mass and coefficients.
// Errors name the feature: an unknown type, a yard that crosses itself, one whose layout
// passes the bound of a run (unless `allow_large_run`) or the machine's memory, one that
// holds fewer bodies than its count.
std::vector<SourcedBody> bodies_from_sources(const std::string& path, const std::vector<std::string>& layers,
                                             const Scene& scene, const debris::BodyDef& model, bool allow_large_run = false);

// A sourced body as a sweep's body (its heading exact, in radians).
sweep::BodySpec body_spec_of(const SourcedBody& s);

// The spec's [[sources]] as bodies after its [[body]] tables, named by their features, on
// `scene` (the spec's, as read_sweep_spec read it; it must be given when there are sources).
void expand_sources(sweep::SweepSpec& spec, const Scene* scene, bool allow_large_run = false);

}  // namespace flotsam
