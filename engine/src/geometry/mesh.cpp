#include "graspkit/geometry/mesh.hpp"

namespace graspkit {

void transformMesh(TriangleMesh& mesh, const Eigen::Affine3d& transform) {
  for (Vector3& v : mesh.vertices) v = transform * v;
  // A reflection (negative determinant) would turn the mesh inside out; keep outward winding.
  if (transform.linear().determinant() < 0) {
    for (auto& tri : mesh.triangles) std::swap(tri[1], tri[2]);
  }
}

}  // namespace graspkit
