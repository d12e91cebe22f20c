#include "geometry/primitive_meshes.hpp"

#include <cmath>
#include <utility>
#include <vector>

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

namespace {

// A closed surface of revolution about z: a pole at each end and rings (z, radius) between,
// from south to north.
TriangleMesh revolvedMesh(double south, double north_z,
                          const std::vector<std::pair<double, double>>& rings, int segments) {
  TriangleMesh mesh;
  mesh.vertices.emplace_back(0, 0, south);
  for (const auto& [z, ring] : rings) {
    for (int s = 0; s < segments; ++s) {
      const double angle = 2.0 * M_PI * s / segments;
      mesh.vertices.emplace_back(ring * std::cos(angle), ring * std::sin(angle), z);
    }
  }
  const auto north = static_cast<Index>(mesh.vertices.size());
  mesh.vertices.emplace_back(0, 0, north_z);
  const int count = static_cast<int>(rings.size());
  auto at = [&](int ring, int s) {
    return static_cast<Index>(1 + (ring - 1) * segments + (s % segments));
  };
  for (int s = 0; s < segments; ++s) {
    mesh.triangles.push_back({0, at(1, s + 1), at(1, s)});
    for (int r = 1; r < count; ++r)
      addQuad(mesh, at(r, s), at(r, s + 1), at(r + 1, s + 1), at(r + 1, s));
    mesh.triangles.push_back({north, at(count, s), at(count, s + 1)});
  }
  return mesh;
}

}  // namespace

TriangleMesh sphereMesh(double radius, int rings, int segments) {
  return capsuleMesh(radius, 0.0, rings, segments);
}

TriangleMesh capsuleMesh(double radius, double length, int rings, int segments) {
  const double half = 0.5 * length;
  std::vector<std::pair<double, double>> bands;
  for (int r = 1; r < rings; ++r) {
    const double polar = M_PI * r / rings;  // from the south pole
    const double z = -radius * std::cos(polar), ring = radius * std::sin(polar);
    // The equator splits into two rings `length` apart (none apart for a sphere).
    if (length > 0.0 && 2 * r == rings) {
      bands.emplace_back(-half, ring);
      bands.emplace_back(half, ring);
    } else {
      bands.emplace_back(z + (2 * r < rings ? -half : half), ring);
    }
  }
  return revolvedMesh(-radius - half, radius + half, bands, segments);
}

}  // namespace graspkit::geometry
