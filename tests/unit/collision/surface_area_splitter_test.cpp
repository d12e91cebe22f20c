// The surface-area split rule for FCL's hierarchy builder. The hierarchy it builds must be a
// hierarchy (every triangle in exactly one leaf, every node's volume around its triangles), must
// cut where the heuristic says (two clusters of triangles are split between them, a closed form,
// whether the node box's axes or only the mesh frame's run across the gap),
// and must give FCL's answers: collide and distance on random poses of two meshes against the
// same meshes in hierarchies of FCL's own rule (a second method).

#include <random>
#include <set>

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>
#include <gtest/gtest.h>

#include "collision/surface_area_splitter.hpp"

namespace graspkit {
namespace {

using Tree = fcl::BVHModel<BoundingVolume>;

struct Soup {
  std::vector<Vector3> vertices;
  std::vector<fcl::Triangle> triangles;
};

// A bumpy sphere of `rows` x `cols` quads, radius about `radius`: uneven triangles, near-touching
// poses with plenty of triangle pairs for FCL to descend.
Soup bumpySphere(int rows, int cols, double radius, std::mt19937& random) {
  std::uniform_real_distribution<double> bump(0.9, 1.1);
  Soup soup;
  for (int r = 0; r <= rows; ++r)
    for (int c = 0; c < cols; ++c) {
      const double theta = M_PI * r / rows, phi = 2 * M_PI * c / cols;
      soup.vertices.push_back(radius * bump(random) *
                              Vector3(std::sin(theta) * std::cos(phi),
                                      std::sin(theta) * std::sin(phi), std::cos(theta)));
    }
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) {
      const int a = r * cols + c, b = r * cols + (c + 1) % cols;
      soup.triangles.emplace_back(a, b, a + cols);
      soup.triangles.emplace_back(b, b + cols, a + cols);
    }
  return soup;
}

std::shared_ptr<Tree> build(const Soup& soup, bool surface_area) {
  auto tree = std::make_shared<Tree>();
  if (surface_area) tree->bv_splitter = std::make_shared<collision::SurfaceAreaSplitter>();
  tree->beginModel();
  tree->addSubModel(soup.vertices, soup.triangles);
  tree->endModel();
  return tree;
}

// The triangles below node `n`, checked to lie in its box (to rounding) on the way up.
std::vector<int> trianglesBelow(const Tree& tree, int n) {
  const fcl::BVNode<BoundingVolume>& node = tree.getBV(n);
  std::vector<int> below;
  if (node.isLeaf()) {
    below.push_back(node.primitiveId());
  } else {
    below = trianglesBelow(tree, node.leftChild());
    const std::vector<int> right = trianglesBelow(tree, node.rightChild());
    below.insert(below.end(), right.begin(), right.end());
  }
  for (int t : below)
    for (int k = 0; k < 3; ++k) {
      const Vector3 local =
          node.bv.obb.axis.transpose() * (tree.vertices[tree.tri_indices[t][k]] - node.bv.obb.To);
      EXPECT_TRUE((local.cwiseAbs().array() <= node.bv.obb.extent.array() + 1e-9).all())
          << "node " << n << " misses a vertex of triangle " << t;
    }
  return below;
}

// Every triangle in exactly one leaf, each node's box around its triangles.
void expectHierarchy(const Tree& tree, const Soup& soup) {
  const std::vector<int> leaves = trianglesBelow(tree, 0);
  const std::multiset<int> counted(leaves.begin(), leaves.end());
  ASSERT_EQ(leaves.size(), soup.triangles.size());
  for (int t = 0; t < static_cast<int>(soup.triangles.size()); ++t)
    EXPECT_EQ(counted.count(t), 1u) << "triangle " << t;
}

TEST(SurfaceAreaSplitter, BuildsAHierarchy) {
  std::mt19937 random(3);
  const Soup soup = bumpySphere(12, 20, 30.0, random);
  expectHierarchy(*build(soup, true), soup);
}

// Two clusters of small triangles far apart along y, one of them long along x, both symmetric
// about x = 0 so that the root box's axes are x, y and z: the longest axis is x, where FCL's rules
// cut, but the cheapest cut by far is the gap in y (cut in x, each child's box spans both rows).
// Each child must be one cluster.
TEST(SurfaceAreaSplitter, CutsBetweenClusters) {
  Soup soup;
  auto add = [&](const Vector3& at) {
    const int base = static_cast<int>(soup.vertices.size());
    soup.vertices.push_back(at + Vector3(-0.5, 0, 0));
    soup.vertices.push_back(at + Vector3(0.5, 0, 0));
    soup.vertices.push_back(at + Vector3(0, 1, 0.5));
    soup.triangles.emplace_back(base, base + 1, base + 2);
  };
  for (int i = 0; i < 40; ++i) add({(i - 19.5) * 10.0, 0.0, 0.0});  // a row 400 long at y = 0
  for (int i = 0; i < 10; ++i) add({(i - 4.5) * 2.0, 100.0, 0.0});  // a row 20 long at y = 100
  const auto tree = build(soup, true);
  expectHierarchy(*tree, soup);
  const fcl::BVNode<BoundingVolume>& root = tree->getBV(0);
  ASSERT_FALSE(root.isLeaf());
  std::set<int> sizes;
  for (int child : {root.leftChild(), root.rightChild()})
    sizes.insert(tree->getBV(child).num_primitives);
  EXPECT_EQ(sizes, (std::set<int>{10, 40}));
}

// The same two rows, both starting at x = 0: the root box's axes now follow the spread of all
// the triangles and run obliquely across the gap, where no cut separates the rows cheaply. The
// mesh frame's y still does.
TEST(SurfaceAreaSplitter, CutsBetweenClustersAcrossAnObliqueBox) {
  Soup soup;
  auto add = [&](const Vector3& at) {
    const int base = static_cast<int>(soup.vertices.size());
    soup.vertices.push_back(at);
    soup.vertices.push_back(at + Vector3(1, 0, 0));
    soup.vertices.push_back(at + Vector3(0, 1, 0.5));
    soup.triangles.emplace_back(base, base + 1, base + 2);
  };
  for (int i = 0; i < 40; ++i) add({i * 10.0, 0.0, 0.0});
  for (int i = 0; i < 10; ++i) add({i * 2.0, 100.0, 0.0});
  const auto tree = build(soup, true);
  expectHierarchy(*tree, soup);
  const fcl::BVNode<BoundingVolume>& root = tree->getBV(0);
  ASSERT_FALSE(root.isLeaf());
  EXPECT_LT(std::abs(root.bv.obb.axis.col(0).dot(Vector3::UnitY())), 0.99);  // oblique
  EXPECT_GT(std::abs(root.bv.obb.axis.col(0).dot(Vector3::UnitY())), 0.01);
  std::set<int> sizes;
  for (int child : {root.leftChild(), root.rightChild()})
    sizes.insert(tree->getBV(child).num_primitives);
  EXPECT_EQ(sizes, (std::set<int>{10, 40}));
}

// Random poses of one bumpy sphere against another, many within a millimetre of touching:
// collide and the distance must be FCL's with its own split rule.
TEST(SurfaceAreaSplitter, GivesFclsAnswers) {
  std::mt19937 random(7);
  const Soup a = bumpySphere(16, 24, 20.0, random), b = bumpySphere(10, 14, 12.0, random);
  const auto a_sah = build(a, true), b_sah = build(b, true);
  const auto a_fcl = build(a, false), b_fcl = build(b, false);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), gap(-2.0, 2.0);
  int colliding = 0, free = 0;
  for (int i = 0; i < 400; ++i) {
    Transform pose = Transform::Identity();
    pose.linear() =
        Eigen::Quaterniond(
            Eigen::Vector4d(unit(random), unit(random), unit(random), unit(random)).normalized())
            .toRotationMatrix();
    const Vector3 direction = Vector3(unit(random), unit(random), unit(random)).normalized();
    pose.translation() = (34.0 + gap(random)) * direction;  // about the radii's sum apart
    const Transform identity = Transform::Identity();
    const fcl::CollisionRequestd request(1, false);
    fcl::CollisionResultd with_sah, with_fcl;
    const bool hit = fcl::collide(a_sah.get(), identity, b_sah.get(), pose, request, with_sah) > 0;
    EXPECT_EQ(hit, fcl::collide(a_fcl.get(), identity, b_fcl.get(), pose, request, with_fcl) > 0)
        << "pose " << i;
    (hit ? colliding : free)++;
    if (hit) continue;
    fcl::DistanceRequestd distance_request(true);
    fcl::DistanceResultd d_sah, d_fcl;
    fcl::distance(a_sah.get(), identity, b_sah.get(), pose, distance_request, d_sah);
    fcl::distance(a_fcl.get(), identity, b_fcl.get(), pose, distance_request, d_fcl);
    EXPECT_NEAR(d_sah.min_distance, d_fcl.min_distance, 1e-9) << "pose " << i;
  }
  // Both answers were asked for often enough to matter.
  EXPECT_GT(colliding, 40);
  EXPECT_GT(free, 40);
}

}  // namespace
}  // namespace graspkit
