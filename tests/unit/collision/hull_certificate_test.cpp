// The convex-hull certificate that proves two meshes apart before FCL's hierarchy is asked:
// the hull of a cube with inner points is its 8 corners (closed form), two cubes a known gap apart
// are certified and touching ones never, and on GraspIt!'s Barrett around the mug the certificate
// never contradicts FCL's own triangle test (a second method) while it settles most near pairs.

#include <random>
#include <string>

#include <fcl/narrowphase/collision.h>
#include <gtest/gtest.h>

#include "collision/collision_geometry.hpp"
#include "geometry/convex_hull.hpp"
#include "graspkit/io/graspit/world_file.hpp"
#include "graspkit/model/body_ref.hpp"
#include "graspkit/model/world.hpp"
#include "random_hand.hpp"
#include "test_paths.hpp"

namespace graspkit {
namespace {

std::shared_ptr<TriangleMesh> cube(double s) {
  auto mesh = std::make_shared<TriangleMesh>();
  for (int i = 0; i < 8; ++i)
    mesh->vertices.emplace_back(s * (i & 1), s * (i >> 1 & 1), s * (i >> 2 & 1));
  mesh->triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                     {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  return mesh;
}

TEST(ConvexHull, OfACubeWithInnerPointsIsItsCorners) {
  std::vector<Vector3> points;
  for (int i = 0; i < 8; ++i) points.emplace_back(i & 1, i >> 1 & 1, i >> 2 & 1);
  points.emplace_back(0.5, 0.5, 0.5);
  points.emplace_back(0.2, 0.7, 0.1);
  const auto hull = geometry::convexHull(points);
  ASSERT_TRUE(hull);
  ASSERT_EQ(hull->vertices.cols(), 8);
  for (Eigen::Index i = 0; i < 8; ++i) {  // a corner: every coordinate 0 or 1
    const Vector3 v = hull->vertices.col(i);
    EXPECT_TRUE(((v.array() == 0.0) || (v.array() == 1.0)).all()) << v.transpose();
  }
  EXPECT_EQ(hull->shape->getFaceCount(), 12);  // triangulated: 2 per square face
}

TEST(ConvexHull, OfAFlatMeshIsNone) {
  EXPECT_FALSE(geometry::convexHull({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}}));
}

TEST(HullCertificate, CertifiesAGapAndNeverAContact) {
  const auto a = collisionGeometry(cube(10.0));
  ASSERT_TRUE(a && a->hull);
  const Transform at_origin = Transform::Identity();
  for (double gap : {1e-3, 0.05, 1.0}) {
    // Rotated about x so that the root boxes overlap along the other axes.
    Transform beside = Transform::Identity();
    beside.translation() = Vector3(10.0 + gap, 2.0, 3.0);
    EXPECT_TRUE(hullsApart(*a, at_origin, *a, beside)) << gap;
  }
  for (double overlap : {0.0, 1e-6, 0.5}) {
    Transform into = Transform::Identity();
    into.translation() = Vector3(10.0 - overlap, 2.0, 3.0);
    EXPECT_FALSE(hullsApart(*a, at_origin, *a, into)) << overlap;
  }
}

// Checks every link of the hand against the mug with the certificate and with FCL's triangles;
// counts the pairs FCL must descend (root volumes overlap, no contact) and those certified.
struct Tally {
  int near = 0;
  int certified = 0;
};

void compareLinks(const World& world, const CollisionGeometry& mug, const Transform& mug_pose,
                  Tally& tally, const std::string& where) {
  const Robot& hand = world.robot(0);
  for (int c = 0; c < static_cast<int>(hand.model().chains.size()); ++c)
    for (int l = 0; l < static_cast<int>(hand.model().chains[c].links.size()); ++l) {
      const BodyRef link = BodyRef::robotLink(0, {c, l});
      const auto geometry = collisionGeometry(bodyModel(world, link).mesh);
      const Transform pose = bodyPose(world, link);
      const bool apart = hullsApart(*geometry, pose, mug, mug_pose);
      const fcl::CollisionRequestd request(1, false);
      fcl::CollisionResultd result;
      const bool touching =
          fcl::collide(geometry->bvh.get(), pose, mug.bvh.get(), mug_pose, request, result) > 0;
      if (apart) EXPECT_FALSE(touching) << where << " link " << c << "," << l;
      const Transform relative = pose.inverse() * mug_pose;
      if (!touching && fcl::overlap(relative.linear(), relative.translation(),
                                    geometry->bvh->getBV(0).bv, mug.bvh->getBV(0).bv)) {
        ++tally.near;
        tally.certified += apart ? 1 : 0;
      }
    }
}

TEST(HullCertificate, NeverContradictsFclAroundGraspItsMug) {
  GRASPKIT_REQUIRE_SHARED();
  World world = loadWorldFile(*test::graspitDataDir() / "worlds" / "plannerMug.xml");
  const auto mug = collisionGeometry(bodyModel(world, BodyRef::body(0)).mesh);
  const Transform mug_pose = bodyPose(world, BodyRef::body(0));
  std::mt19937 random(5);
  Tally tally;
  for (int trial = 0; trial < 400; ++trial) {  // random hand poses and postures near the mug
    test::placeHandRandomlyNear(world, mug_pose.translation(), random);
    compareLinks(world, *mug, mug_pose, tally, "trial " + std::to_string(trial));
  }
  EXPECT_GT(tally.near, 100);
}

TEST(HullCertificate, SettlesMostNearPairsAlongAnApproach) {
  GRASPKIT_REQUIRE_SHARED();
  // The hand closing on the mug as autograsp does: small steps, the same pairs again and again.
  World world = loadWorldFile(*test::graspitDataDir() / "worlds" / "plannerMug.xml");
  const auto mug = collisionGeometry(bodyModel(world, BodyRef::body(0)).mesh);
  const Transform mug_pose = bodyPose(world, BodyRef::body(0));
  Tally tally;
  for (int step = 0; step <= 200; ++step) {
    const double closing = 1.0 * step / 200.0;
    world.setDofValues(0, std::vector<double>{0.0, closing, closing, closing});
    compareLinks(world, *mug, mug_pose, tally, "step " + std::to_string(step));
  }
  ASSERT_GT(tally.near, 100);
  EXPECT_GT(tally.certified, tally.near / 2) << tally.certified << " of " << tally.near;
}

}  // namespace
}  // namespace graspkit
