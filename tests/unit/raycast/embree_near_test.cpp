// EmbreeMesh::forEachTriangleNear against a scan of every triangle's box: the contact search
// relies on it visiting at least every triangle whose box comes within the radius (it then
// tests each pair exactly), so a triangle it misses is a contact lost.

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <set>
#include <vector>

#include <gtest/gtest.h>

#include "raycast/embree_mesh.hpp"
#include "test_meshes.hpp"

namespace graspkit::raycast {
namespace {

double boxDistance(const Eigen::AlignedBox3d& box, const Vector3& p) {
  return (p.cwiseMax(box.min()).cwiseMin(box.max()) - p).norm();
}

void expectEveryNearTriangleVisited(const std::shared_ptr<const TriangleMesh>& mesh,
                                    std::mt19937& random, double spread, double max_radius) {
  const EmbreeMesh surface(mesh);
  std::uniform_real_distribution<double> coordinate(-spread, spread), radius(0.0, max_radius);
  int visited_some = 0;
  for (int query = 0; query < 400; ++query) {
    const Vector3 center(coordinate(random), coordinate(random), coordinate(random));
    const double r = radius(random);
    std::set<unsigned> visited;
    surface.forEachTriangleNear(center, r, [&](unsigned t) { visited.insert(t); });
    for (unsigned t = 0; t < mesh->triangles.size(); ++t)
      if (boxDistance(surface.triangleBox(t), center) <= r)
        ASSERT_TRUE(visited.count(t))
            << "triangle " << t << " within " << r << " of " << center.transpose()
            << " not visited (query " << query << ")";
    visited_some += !visited.empty();
  }
  EXPECT_GT(visited_some, 100);
}

TEST(EmbreeNear, VisitsEveryTriangleWhoseBoxIsWithinTheRadius) {
  std::mt19937 random(17);
  // A dense sphere of 50 mm (thousands of small triangles), queried around its surface.
  expectEveryNearTriangleVisited(test::icosphere(50.0, 4), random, 60.0, 10.0);
  // A soup of triangles of every size, some long and thin, far from the origin as link meshes
  // placed in a world are.
  auto soup = std::make_shared<TriangleMesh>();
  std::uniform_real_distribution<double> place(900.0, 1100.0), size(-30.0, 30.0);
  for (int t = 0; t < 2000; ++t) {
    const Vector3 a(place(random), place(random), place(random));
    const auto first = static_cast<std::uint32_t>(soup->vertices.size());
    soup->vertices.push_back(a);
    soup->vertices.push_back(a + Vector3(size(random), size(random), size(random)));
    soup->vertices.push_back(a + 0.01 * Vector3(size(random), size(random), size(random)));
    soup->triangles.push_back({first, first + 1, first + 2});
  }
  std::mt19937 again(18);
  std::uniform_real_distribution<double> around(-120.0, 120.0);
  const EmbreeMesh surface(soup);
  int visited_some = 0;
  for (int query = 0; query < 400; ++query) {
    const Vector3 center =
        Vector3::Constant(1000.0) + Vector3(around(again), around(again), around(again));
    const double r = std::uniform_real_distribution<double>(0.0, 40.0)(again);
    std::set<unsigned> visited;
    surface.forEachTriangleNear(center, r, [&](unsigned t) { visited.insert(t); });
    for (unsigned t = 0; t < soup->triangles.size(); ++t)
      if (boxDistance(surface.triangleBox(t), center) <= r)
        ASSERT_TRUE(visited.count(t)) << "soup triangle " << t << ", query " << query;
    visited_some += !visited.empty();
  }
  EXPECT_GT(visited_some, 100);
}

}  // namespace
}  // namespace graspkit::raycast
