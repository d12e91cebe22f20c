#pragma once
// The convex hull of a mesh's vertices (internal to the collision module), for certificates that
// two meshes cannot touch: if their hulls are apart, so are they.

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

// The index of the hull vertex farthest along d, the first of equals. A plain loop: an Eigen
// row-times-matrix product would allocate its temporary row at every call, and certificates ask
// this hundreds of thousands of times a second. A NaN direction gives vertex 0.
inline Eigen::Index farthestVertex(const ConvexHull& hull, const Vector3& d) {
  const double* v = hull.vertices.data();
  const Eigen::Index count = hull.vertices.cols();
  Eigen::Index farthest = 0;
  double extent = d.x() * v[0] + d.y() * v[1] + d.z() * v[2];
  for (Eigen::Index i = 1; i < count; ++i) {
    const double along = d.x() * v[3 * i] + d.y() * v[3 * i + 1] + d.z() * v[3 * i + 2];
    if (along > extent) extent = along, farthest = i;
  }
  return farthest;
}

// qhull's hull of the points; nullopt when it has no volume (a flat or degenerate mesh) or
// qhull fails.
std::optional<ConvexHull> convexHull(const std::vector<Vector3>& points);

}  // namespace graspkit::geometry
