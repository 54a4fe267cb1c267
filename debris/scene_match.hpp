// Checks before a replay: a flow is replayed with the scene it was computed
// on, and every body starts inside the domain, out of the buildings, and smaller than
// the domain. Errors name the flow and scene files, or the body and its position.
#pragma once
#include <string>

#include "debris/body.hpp"
#include "debris/flow_reader.hpp"
#include "formats/scene.hpp"

namespace flotsam::debris {

// The flow's grid must be a window of the scene's (same spacing, cell centres on the
// scene's), inside it, with the same bed elevation (buildings included) to float
// precision, and in the same CRS. A flow whose `scene_sha256` attribute names other
// bytes than the scene file passes if its bed matches (a scene rewritten with another
// history, say); the error, when there is one, gives both checksums. A flow that records
// its scene's building mask (scene_buildings_sha256, formats/scene.hpp) must have this
// scene's: the same bed with another building mask is refused.
void check_flow_matches_scene(const FlowReader& flow, const Scene& scene);

// The body's centre must lie in the flow's grid, its footprint off the scene's building
// cells (when `scene` is given), and its diagonal shorter than the grid.
void check_body_start(const BodyDef& body, const FlowReader& flow, const Scene* scene);
// The same on any grid; `domain` names it in messages ("flow F", "scene S").
void check_body_start(const BodyDef& body, const Grid& grid, const std::string& domain, const Scene* scene);

}  // namespace flotsam::debris
