#pragma once
// A triangle mesh in millimetres, in its body's frame. Meshes are immutable once loaded and
// shared between every world that uses them (std::shared_ptr<const TriangleMesh>).

#include <array>
#include <cstdint>
#include <vector>

#include "graspkit/math/transform.hpp"

namespace graspkit {

// A surface colour: red, green and blue in [0, 1], as Inventor files give them.
struct Colour {
  float r = 0.8f;
  float g = 0.8f;
  float b = 0.8f;
  friend bool operator==(const Colour&, const Colour&) = default;
};

struct TriangleMesh {
  std::vector<Vector3> vertices;                        // mm, body frame
  std::vector<std::array<std::uint32_t, 3>> triangles;  // counter-clockwise seen from outside
  // The diffuse colour of each triangle where the file gives colours (Inventor and VRML
  // materials); empty otherwise, and pictures then colour the body by its material. Geometry
  // queries never look at it.
  std::vector<Colour> triangleColours;

  std::size_t triangleCount() const { return triangles.size(); }
  bool empty() const { return triangles.empty(); }
};

// Applies p -> linear * p + translation to every vertex (scaling, then an offset transform).
void transformMesh(TriangleMesh& mesh, const Eigen::Affine3d& transform);

}  // namespace graspkit
