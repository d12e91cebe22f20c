#pragma once
// Meshes built in tests, whose geometry has closed forms: icospheres, cylinders and flat
// slabs. Faces are wound counter-clockwise seen from outside.

#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <memory>
#include <numbers>
#include <utility>
#include <vector>

#include "graspkit/geometry/mesh.hpp"

namespace graspkit::test {

// An icosphere of radius `radius` about the origin: an icosahedron subdivided `levels` times,
// every vertex projected onto the sphere, faces wound counter-clockwise seen from outside.
inline std::shared_ptr<TriangleMesh> icosphere(double radius, int levels) {
  auto mesh = std::make_shared<TriangleMesh>();
  const double g = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Vector3> v = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0},
                            {0, -1, g}, {0, 1, g}, {0, -1, -g}, {0, 1, -g},
                            {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
  std::vector<std::array<std::uint32_t, 3>> f = {
      {0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
      {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
      {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (auto& p : v) p.normalize();
  for (int level = 0; level < levels; ++level) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> middles;
    auto middle = [&](std::uint32_t a, std::uint32_t b) {
      auto key = std::minmax(a, b);
      auto it = middles.find(key);
      if (it != middles.end()) return it->second;
      v.push_back((v[a] + v[b]).normalized());
      const auto index = static_cast<std::uint32_t>(v.size() - 1);
      middles[key] = index;
      return index;
    };
    std::vector<std::array<std::uint32_t, 3>> next;
    for (const auto& t : f) {
      const auto ab = middle(t[0], t[1]), bc = middle(t[1], t[2]), ca = middle(t[2], t[0]);
      next.push_back({t[0], ab, ca});
      next.push_back({t[1], bc, ab});
      next.push_back({t[2], ca, bc});
      next.push_back({ab, bc, ca});
    }
    f = std::move(next);
  }
  for (auto& t : f) {
    // Outward by construction: the face normal points away from the centre.
    if ((v[t[1]] - v[t[0]]).cross(v[t[2]] - v[t[0]]).dot(v[t[0]]) < 0) std::swap(t[1], t[2]);
  }
  for (auto& p : v) p *= radius;
  mesh->vertices = std::move(v);
  mesh->triangles = std::move(f);
  return mesh;
}

// A cylinder of radius `radius` along z from -length/2 to length/2, `segments` facets around,
// closed by two fans unless `caps` is false (an open tube); every vertex of the side lies on the
// cylinder, and the side faces span the whole length.
inline std::shared_ptr<TriangleMesh> cylinder(double radius, double length, int segments,
                                              bool caps = true) {
  auto mesh = std::make_shared<TriangleMesh>();
  const double half = length / 2.0;
  for (int i = 0; i < segments; ++i) {
    const double t = 2.0 * std::numbers::pi * i / segments;
    mesh->vertices.emplace_back(radius * std::cos(t), radius * std::sin(t), -half);
    mesh->vertices.emplace_back(radius * std::cos(t), radius * std::sin(t), half);
  }
  const auto bottom = static_cast<std::uint32_t>(mesh->vertices.size());
  mesh->vertices.emplace_back(0.0, 0.0, -half);
  mesh->vertices.emplace_back(0.0, 0.0, half);
  const auto top = bottom + 1;
  const auto n = static_cast<std::uint32_t>(segments);
  for (std::uint32_t i = 0; i < n; ++i) {
    const std::uint32_t j = (i + 1) % n;
    mesh->triangles.push_back({2 * i, 2 * j, 2 * j + 1});
    mesh->triangles.push_back({2 * i, 2 * j + 1, 2 * i + 1});
    if (!caps) continue;
    mesh->triangles.push_back({bottom, 2 * j, 2 * i});
    mesh->triangles.push_back({top, 2 * i + 1, 2 * j + 1});
  }
  return mesh;
}

// A box from `low` to `high`, two triangles per face.
inline std::shared_ptr<TriangleMesh> box(const Vector3& low, const Vector3& high) {
  auto mesh = std::make_shared<TriangleMesh>();
  for (int i = 0; i < 8; ++i)
    mesh->vertices.emplace_back(i & 1 ? high.x() : low.x(), i & 2 ? high.y() : low.y(),
                                i & 4 ? high.z() : low.z());
  mesh->triangles = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
                     {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
  return mesh;
}

}  // namespace graspkit::test
