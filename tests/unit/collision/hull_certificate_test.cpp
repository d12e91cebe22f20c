// The convex-hull certificate that proves two meshes apart before FCL's hierarchy is asked:
// the hull of a cube with inner points is its 8 corners (closed form), two cubes a known gap apart
// are certified and touching ones never, and on GraspIt!'s Barrett around the mug the certificate
// never contradicts FCL's own triangle test (a second method) while it settles most near pairs.

#include <cmath>
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

// Cubes of side s at the given corners, one mesh: a closed part each.
std::shared_ptr<TriangleMesh> cubes(double s, const std::vector<Vector3>& corners) {
  auto mesh = std::make_shared<TriangleMesh>();
  const auto one = cube(s);
  for (const Vector3& corner : corners) {
    const auto first = static_cast<std::uint32_t>(mesh->vertices.size());
    for (const Vector3& v : one->vertices) mesh->vertices.push_back(v + corner);
    for (const auto& t : one->triangles)
      mesh->triangles.push_back({t[0] + first, t[1] + first, t[2] + first});
  }
  return mesh;
}

Transform at(double x, double y, double z) {
  Transform t = Transform::Identity();
  t.translation() = Vector3(x, y, z);
  return t;
}

// Two 10 mm cubes 20 mm apart (x from 0 to 10 and from 30 to 40) make one mesh whose whole hull
// spans the gap. A 4 mm cube in the gap, 2 mm from the first (x from 12 to 16), lies inside that
// hull, yet each part's hull is apart from it: 2 mm from one, 14 mm from the other.
TEST(HullCertificate, PartsProveAMeshApartAcrossTheGapsOfItsHull) {
  const auto pair = collisionGeometry(cubes(10.0, {{0, 0, 0}, {30, 0, 0}}));
  const auto probe = collisionGeometry(cube(4.0));
  ASSERT_TRUE(pair && pair->hull && probe && probe->hull);
  ASSERT_EQ(pair->parts.size(), 2u);
  EXPECT_TRUE(probe->parts.empty());
  const Transform origin = Transform::Identity();
  const Transform in_gap = at(12.0, 3.0, 3.0);
  EXPECT_TRUE(hullsApart(*pair, origin, *probe, in_gap));
  EXPECT_TRUE(hullsApart(*probe, in_gap, *pair, origin));
  EXPECT_TRUE(hullsApart(*pair, origin, *probe, in_gap, 1.9));  // by less than the 2 mm
  EXPECT_FALSE(hullsApart(*pair, origin, *probe, in_gap, 2.1));
  // Touching or crossing the first cube: never apart, and FCL's triangles agree.
  for (double x : {10.0, 9.5}) {
    EXPECT_FALSE(hullsApart(*pair, origin, *probe, at(x, 3.0, 3.0))) << x;
    const fcl::CollisionRequestd request(1, false);
    fcl::CollisionResultd result;
    EXPECT_GT(
        fcl::collide(pair->bvh.get(), origin, probe->bvh.get(), at(x, 3.0, 3.0), request, result),
        0u)
        << x;
  }
  // Two meshes with parts: the pair against itself, turned a quarter about z and set in the gap
  // so that the parts interleave without touching (closed form: 5 mm between nearest faces).
  Transform turned = at(20.0 + 5.0, -15.0, 0.0);
  turned.linear() = Eigen::AngleAxisd(M_PI / 2, Vector3::UnitZ()).toRotationMatrix();
  // Turned, its cubes span x from 15 to 25 and y from -15 to 25 with a gap for y in [-5, 15].
  EXPECT_TRUE(hullsApart(*pair, origin, *pair, turned));
  // More than kMaxHullParts parts: none kept.
  std::vector<Vector3> many;
  for (int k = 0; k <= kMaxHullParts; ++k) many.emplace_back(20.0 * k, 0.0, 0.0);
  EXPECT_TRUE(collisionGeometry(cubes(1.0, many))->parts.empty());
}

// Random placements of a 4 mm cube around three separate cubes: whatever the parts certify,
// FCL's triangle test finds apart (a second method), and they certify most placements inside the
// whole hull that do not touch.
TEST(HullCertificate, PartsNeverContradictFcl) {
  const auto three = collisionGeometry(cubes(10.0, {{0, 0, 0}, {25, 0, 0}, {0, 25, 5}}));
  const auto probe = collisionGeometry(cube(4.0));
  ASSERT_EQ(three->parts.size(), 3u);
  std::mt19937 random(11);
  std::uniform_real_distribution<double> coordinate(-5.0, 35.0), angle(-M_PI, M_PI);
  int free_inside = 0, certified = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    Transform pose = at(coordinate(random), coordinate(random), coordinate(random) * 0.5);
    pose.linear() = (Eigen::AngleAxisd(angle(random), Vector3::UnitZ()) *
                     Eigen::AngleAxisd(angle(random), Vector3::UnitX()))
                        .toRotationMatrix();
    const bool apart = hullsApart(*three, Transform::Identity(), *probe, pose);
    const fcl::CollisionRequestd request(1, false);
    fcl::CollisionResultd result;
    const bool touching = fcl::collide(three->bvh.get(), Transform::Identity(), probe->bvh.get(),
                                       pose, request, result) > 0;
    if (apart) EXPECT_FALSE(touching) << trial;
    // Inside the whole hull's box, clear of every cube by more than the probe's reach (3.5 mm).
    const Vector3 c = pose * Vector3(2, 2, 2);
    const bool clear = (c - Vector3(5, 5, 5)).cwiseAbs().maxCoeff() > 8.5 &&
                       (c - Vector3(30, 5, 5)).cwiseAbs().maxCoeff() > 8.5 &&
                       (c - Vector3(5, 30, 10)).cwiseAbs().maxCoeff() > 8.5;
    if (!touching && clear && c.x() > 10 && c.x() < 25 && c.y() > 0 && c.y() < 25) {
      ++free_inside;
      certified += apart;
    }
  }
  ASSERT_GT(free_inside, 50);
  EXPECT_GT(certified, free_inside * 9 / 10) << certified << " of " << free_inside;
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
