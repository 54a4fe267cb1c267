#include "hydro/physics.hpp"

namespace flotsam::hydro {

PhysicsDef default_physics_def() {
    PhysicsDef d;
    d.west.kind = BoundaryKind::level;
    d.east.kind = BoundaryKind::transmissive;
    d.south.kind = BoundaryKind::wall;
    d.north.kind = BoundaryKind::wall;
    return d;
}

}  // namespace flotsam::hydro
