#pragma once
// A triangle mesh in millimetres, in its body's frame. Meshes are immutable once loaded and
// shared between every world that uses them (std::shared_ptr<const TriangleMesh>).

#include <array>
#include <cstdint>
#include <vector>

#include "graspkit/transform.hpp"

namespace graspkit {

struct TriangleMesh {
  std::vector<Vector3> vertices;                        // mm, body frame
  std::vector<std::array<std::uint32_t, 3>> triangles;  // counter-clockwise seen from outside

  std::size_t triangleCount() const { return triangles.size(); }
  bool empty() const { return triangles.empty(); }
};

// Applies p -> linear * p + translation to every vertex (scaling, then an offset transform).
void transformMesh(TriangleMesh& mesh, const Eigen::Affine3d& transform);

}  // namespace graspkit
