#include "geometry/primitive_meshes.hpp"

#include <cmath>

namespace graspkit::geometry {

namespace {

using Index = std::uint32_t;

void addQuad(TriangleMesh& mesh, Index a, Index b, Index c, Index d) {
  mesh.triangles.push_back({a, b, c});
  mesh.triangles.push_back({a, c, d});
}

}  // namespace

TriangleMesh boxMesh(const Vector3& size) {
  TriangleMesh mesh;
  const Vector3 h = 0.5 * size;
  for (int corner = 0; corner < 8; ++corner) {
    mesh.vertices.emplace_back(corner & 1 ? h.x() : -h.x(), corner & 2 ? h.y() : -h.y(),
                               corner & 4 ? h.z() : -h.z());
  }
  // Corner index bits: x = 1, y = 2, z = 4. Each face listed counter-clockwise from outside.
  addQuad(mesh, 0, 2, 3, 1);  // z-
  addQuad(mesh, 4, 5, 7, 6);  // z+
  addQuad(mesh, 0, 1, 5, 4);  // y-
  addQuad(mesh, 2, 6, 7, 3);  // y+
  addQuad(mesh, 0, 4, 6, 2);  // x-
  addQuad(mesh, 1, 3, 7, 5);  // x+
  return mesh;
}

TriangleMesh cylinderMesh(double radius, double length, int segments) {
  TriangleMesh mesh;
  const double h = 0.5 * length;
  for (int s = 0; s < segments; ++s) {
    const double angle = 2.0 * M_PI * s / segments;
    const double x = radius * std::cos(angle), y = radius * std::sin(angle);
    mesh.vertices.emplace_back(x, y, -h);
    mesh.vertices.emplace_back(x, y, h);
  }
  const auto bottom_centre = static_cast<Index>(mesh.vertices.size());
  mesh.vertices.emplace_back(0, 0, -h);
  mesh.vertices.emplace_back(0, 0, h);
  const Index top_centre = bottom_centre + 1;
  for (int s = 0; s < segments; ++s) {
    const auto b0 = static_cast<Index>(2 * s), t0 = b0 + 1;
    const auto b1 = static_cast<Index>(2 * ((s + 1) % segments)), t1 = b1 + 1;
    addQuad(mesh, b0, b1, t1, t0);
    mesh.triangles.push_back({bottom_centre, b1, b0});
    mesh.triangles.push_back({top_centre, t0, t1});
  }
  return mesh;
}

TriangleMesh sphereMesh(double radius, int rings, int segments) {
  TriangleMesh mesh;
  mesh.vertices.emplace_back(0, 0, -radius);  // south pole
  for (int r = 1; r < rings; ++r) {
    const double polar = M_PI * r / rings;  // from the south pole
    const double z = -radius * std::cos(polar), ring = radius * std::sin(polar);
    for (int s = 0; s < segments; ++s) {
      const double angle = 2.0 * M_PI * s / segments;
      mesh.vertices.emplace_back(ring * std::cos(angle), ring * std::sin(angle), z);
    }
  }
  const auto north = static_cast<Index>(mesh.vertices.size());
  mesh.vertices.emplace_back(0, 0, radius);
  auto at = [&](int ring, int s) {
    return static_cast<Index>(1 + (ring - 1) * segments + (s % segments));
  };
  for (int s = 0; s < segments; ++s) {
    mesh.triangles.push_back({0, at(1, s + 1), at(1, s)});
    for (int r = 1; r + 1 < rings; ++r)
      addQuad(mesh, at(r, s), at(r, s + 1), at(r + 1, s + 1), at(r + 1, s));
    mesh.triangles.push_back({north, at(rings - 1, s), at(rings - 1, s + 1)});
  }
  return mesh;
}

}  // namespace graspkit::geometry
