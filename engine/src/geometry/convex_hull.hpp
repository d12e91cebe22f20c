#pragma once
// The convex hull of a set of points (internal to the engine): for certificates that two meshes
// cannot touch (if their hulls are apart, so are they), for generated objects, and for MJCF mesh
// geoms, which MuJoCo collides as their hulls.

#include <memory>
#include <optional>
#include <vector>

#include <fcl/geometry/shape/convex.h>

#include "graspkit/geometry/mesh.hpp"

namespace graspkit::geometry {

struct ConvexHull {
  Eigen::Matrix3Xd vertices;  // body frame, one per column: some of the mesh's vertices, exactly
  std::shared_ptr<const fcl::Convexd> shape;  // the same polytope, with its faces, as FCL's shape
};

// qhull's hull of the points; nullopt when it has no volume (a flat or degenerate mesh) or
// qhull fails.
std::optional<ConvexHull> convexHull(const std::vector<Vector3>& points);

// The same hull as a closed triangle mesh, every triangle facing out; nullopt as above.
std::optional<TriangleMesh> convexHullMesh(const std::vector<Vector3>& points);

}  // namespace graspkit::geometry
