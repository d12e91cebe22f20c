#pragma once
// Internal: the solid primitives URDF and MJCF describe (box, cylinder, sphere, capsule) as closed
// triangle meshes centred on their frame's origin, counter-clockwise seen from outside.

#include "graspkit/geometry/mesh.hpp"

namespace graspkit::geometry {

// Edge lengths along x, y, z.
TriangleMesh boxMesh(const Vector3& size);

// Axis along z, `segments` facets round (the circle's corners lie on it).
TriangleMesh cylinderMesh(double radius, double length, int segments = 32);

// `rings` bands from pole to pole, `segments` round (the corners lie on the sphere).
TriangleMesh sphereMesh(double radius, int rings = 16, int segments = 32);

// A cylinder of `length` along z capped by hemispheres (MJCF's capsule); `rings` even. Its
// corners lie on the surface.
TriangleMesh capsuleMesh(double radius, double length, int rings = 16, int segments = 32);

}  // namespace graspkit::geometry
