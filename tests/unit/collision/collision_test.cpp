// Collision queries and the collision filter against independent truths: unit cubes placed by
// hand (overlap, closed-form distances, touching), degenerate meshes, GraspIt!'s pair rules on
// this repository's bh8 hand and on small robots written here, shared BVHs across clones, and
// the BVH cache under two threads.

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "collision/broad_phase.hpp"
#include "graspkit/base/error.hpp"
#include "graspkit/collision/collision.hpp"
#include "graspkit/io/graspit/robot_file.hpp"
#include "graspkit/io/graspit/world_file.hpp"
#include "graspkit/model/collision_filter.hpp"
#include "graspkit/model/world.hpp"
#include "test_paths.hpp"

namespace graspkit {
namespace {

namespace fs = std::filesystem;

constexpr double kTol = 1e-9;

// ---------------------------------------------------------------------------------------------
// Bodies built by hand

// The cube [0, s]^3, twelve outward-facing triangles.
std::shared_ptr<TriangleMesh> cubeMesh(double s = 1.0) {
  auto mesh = std::make_shared<TriangleMesh>();
  for (int i = 0; i < 8; ++i)
    mesh->vertices.emplace_back(s * (i & 1), s * ((i >> 1) & 1), s * (i >> 2));
  // Each face as two triangles, counter-clockwise seen from outside.
  mesh->triangles = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
                     {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
  return mesh;
}

std::shared_ptr<const BodyModel> modelOf(std::shared_ptr<const TriangleMesh> mesh,
                                         const std::string& name) {
  auto model = std::make_shared<BodyModel>();
  model->name = name;
  model->mesh = std::move(mesh);
  return model;
}

Transform translation(double x, double y, double z) {
  Transform t = Transform::Identity();
  t.translation() = Vector3(x, y, z);
  return t;
}

Transform rotZ(double angle) {
  Transform t = Transform::Identity();
  t.rotate(Eigen::AngleAxisd(angle, Vector3::UnitZ()));
  return t;
}

int addBody(World& world, std::shared_ptr<const TriangleMesh> mesh, const Transform& pose,
            BodyKind kind = BodyKind::Graspable, const std::string& name = "cube") {
  Body body;
  body.model = modelOf(std::move(mesh), name);
  body.kind = kind;
  body.name = name;
  body.pose = pose;
  return world.addBody(body);
}

// Two unit cubes, the first at the origin, the second at `pose`.
World twoCubes(const Transform& pose) {
  World world;
  addBody(world, cubeMesh(), Transform::Identity());
  addBody(world, cubeMesh(), pose);
  return world;
}

const BodyRef kA = BodyRef::body(0);
const BodyRef kB = BodyRef::body(1);

// ---------------------------------------------------------------------------------------------
// Cubes

TEST(Collision, OverlappingCubesCollide) {
  const World world = twoCubes(translation(0.5, 0.3, 0.2));
  EXPECT_TRUE(collide(world, kA, kB));
  EXPECT_TRUE(collide(world, kB, kA));
  const DistanceResult d = distance(world, kA, kB);
  EXPECT_EQ(d.distance, 0.0);
  EXPECT_TRUE(d.pointOnA.isApprox(d.pointOnB));
  const auto report = collisionReport(world);
  ASSERT_EQ(report.size(), 1u);
  EXPECT_EQ(report[0].first, kA);
  EXPECT_EQ(report[0].second, kB);
}

TEST(Collision, CubesFiveMillimetresApartAlongX) {
  const World world = twoCubes(translation(6, 0, 0));  // faces x = 1 and x = 6
  EXPECT_FALSE(collide(world, kA, kB));
  EXPECT_TRUE(collisionReport(world).empty());
  const DistanceResult d = distance(world, kA, kB);
  EXPECT_NEAR(d.distance, 5.0, kTol);
  // The nearest points lie on the facing faces, straight across from each other.
  EXPECT_NEAR(d.pointOnA.x(), 1.0, kTol);
  EXPECT_NEAR(d.pointOnB.x(), 6.0, kTol);
  EXPECT_NEAR(d.pointOnA.y(), d.pointOnB.y(), kTol);
  EXPECT_NEAR(d.pointOnA.z(), d.pointOnB.z(), kTol);
  for (const Vector3& p : {d.pointOnA, d.pointOnB}) {
    EXPECT_GE(p.y(), -kTol);
    EXPECT_LE(p.y(), 1 + kTol);
    EXPECT_GE(p.z(), -kTol);
    EXPECT_LE(p.z(), 1 + kTol);
  }
  // Symmetric.
  const DistanceResult back = distance(world, kB, kA);
  EXPECT_NEAR(back.distance, 5.0, kTol);
  EXPECT_NEAR(back.pointOnA.x(), 6.0, kTol);
}

TEST(Collision, WithinDistanceOfCubesFiveMillimetresApart) {
  const World world = twoCubes(translation(6, 0, 0));
  EXPECT_TRUE(withinDistance(world, kA, kB, 5.0 + 1e-9));
  EXPECT_FALSE(withinDistance(world, kA, kB, 5.0 - 1e-9));
  EXPECT_FALSE(withinDistance(world, kA, kB, 0.1));
  EXPECT_TRUE(withinDistance(twoCubes(translation(0.5, 0.3, 0.2)), kA, kB, 1e-6));  // crossing
  EXPECT_FALSE(withinDistance(world, kA, kB, 0.0));
}

// The octahedron |x| + |y| + |z| <= 1: its bounding boxes reach well beyond it, so near poses
// go past FCL's root test to the hull certificates.
std::shared_ptr<TriangleMesh> octahedronMesh() {
  auto mesh = std::make_shared<TriangleMesh>();
  mesh->vertices = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  mesh->triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                     {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  return mesh;
}

// A certificate that the octahedra were apart must not survive a turn that brings them
// together: B's left corner hangs 0.04 mm over the middle of A's face x + y + z = 1, and turning
// B by 0.1 rad about z round its own centre swings that corner (1 - cos - sin)/sqrt(3) = 0.055 mm
// towards the face, through it.
TEST(Collision, ACertificateAllowsForTurning) {
  const Vector3 n = Vector3(1, 1, 1).normalized();
  const Vector3 corner = Vector3(1, 1, 1) / 3.0 + 0.04 * n;
  World world;
  addBody(world, octahedronMesh(), Transform::Identity());
  addBody(world, octahedronMesh(), translation(corner.x() + 1, corner.y(), corner.z()));
  ASSERT_FALSE(collide(world, kA, kB));  // proved apart, and remembered
  Transform turned = world.bodies()[1].pose;
  turned.rotate(Eigen::AngleAxisd(0.1, Vector3::UnitZ()));
  world.bodies()[1].pose = turned;
  EXPECT_TRUE(collide(world, kA, kB));
  EXPECT_EQ(distance(world, kA, kB).distance, 0.0);
}

// withinDistance against FCL's full distance, and collide (whose separation certificates are
// remembered between queries) against FCL's own collide inside distance(), along a random walk
// of a turned octahedron round a fixed one: many nearby poses, some crossing, some a hair apart.
TEST(Collision, CertificatesAndThresholdsAgreeWithFullQueriesOnARandomWalk) {
  World world;
  addBody(world, octahedronMesh(), Transform::Identity());
  addBody(world, octahedronMesh(), translation(1.5, 0.2, 0.1));
  std::mt19937 random(7);
  std::normal_distribution<double> jitter(0.0, 0.05);
  std::uniform_real_distribution<double> threshold(0.0, 0.3);
  Vector3 at(1.5, 0.2, 0.1);
  double angle = 0.3;
  int crossing = 0, near = 0;
  for (int step = 0; step < 4000; ++step) {
    // Every other step only turns, about the centre: a certificate must allow for turning too.
    if (step % 2) at += Vector3(jitter(random), jitter(random), jitter(random));
    at = at.cwiseMax(Vector3(-2.5, -2.5, -2.5)).cwiseMin(Vector3(2.5, 2.5, 2.5));
    angle += jitter(random);
    Transform pose = translation(at.x(), at.y(), at.z());
    pose.rotate(Eigen::AngleAxisd(angle, Vector3(1, 2, 3).normalized()));
    world.bodies()[1].pose = pose;
    const double full = distance(world, kA, kB).distance;
    const double t = threshold(random);
    ASSERT_EQ(collide(world, kA, kB), full == 0.0) << "step " << step << " distance " << full;
    if (std::abs(full - t) > 1e-9)
      ASSERT_EQ(withinDistance(world, kA, kB, t), full < t) << "step " << step << " t " << t;
    crossing += full == 0.0;
    near += full > 0.0 && full < 0.3;
  }
  EXPECT_GT(crossing, 100);  // the walk did visit both sides
  EXPECT_GT(near, 100);
}

TEST(Collision, CubeRotated45DegreesAboutZ) {
  // The second cube turned 45 degrees about its own vertical axis, its centre at (cx, .5, .5):
  // its nearest feature is the vertical edge at x = cx - sqrt(2)/2, facing the face x = 1.
  for (double cx : {2.5, 5.0, 40.0}) {
    SCOPED_TRACE(cx);
    const Transform pose =
        translation(cx, 0.5, 0.5) * rotZ(M_PI / 4) * translation(-0.5, -0.5, -0.5);
    const World world = twoCubes(pose);
    const double expected = cx - std::sqrt(0.5) - 1.0;
    const DistanceResult d = distance(world, kA, kB);
    EXPECT_NEAR(d.distance, expected, kTol);
    EXPECT_NEAR(d.pointOnA.x(), 1.0, kTol);
    EXPECT_NEAR(d.pointOnB.x(), cx - std::sqrt(0.5), kTol);
    EXPECT_NEAR(d.pointOnB.y(), 0.5, kTol);
    EXPECT_FALSE(collide(world, kA, kB));
  }
  // Close enough that the edge cuts into the first cube: cx - sqrt(2)/2 < 1.
  EXPECT_TRUE(
      collide(twoCubes(translation(1.6, 0.5, 0.5) * rotZ(M_PI / 4) * translation(-0.5, -0.5, -0.5)),
              kA, kB));
}

TEST(Collision, TouchingAndNearlyTouchingCubes) {
  // A micrometre apart: separate, and the distance says by how much.
  {
    const World world = twoCubes(translation(1 + 1e-3, 0, 0));
    EXPECT_FALSE(collide(world, kA, kB));
    EXPECT_NEAR(distance(world, kA, kB).distance, 1e-3, kTol);
  }
  // Overlapping by a micrometre, the second cube shifted in y and z so that faces cross.
  EXPECT_TRUE(collide(twoCubes(translation(1 - 1e-3, 0.3, 0.4)), kA, kB));
  // Exactly touching face to face, and edge to edge: whether coplanar contact counts is FCL's
  // call, but the distance is 0 and nothing fails.
  for (const Transform& pose : {translation(1, 0, 0), translation(1, 1, 0), translation(1, 1, 1)}) {
    const World world = twoCubes(pose);
    EXPECT_NO_THROW(collide(world, kA, kB));
    EXPECT_NEAR(distance(world, kA, kB).distance, 0.0, kTol);
  }
}

TEST(Collision, CubeInsideCubeIsNotACollision) {
  // Surfaces only: a small cube wholly inside a big one crosses no triangle (GraspIt! alike).
  World world;
  addBody(world, cubeMesh(10), Transform::Identity());
  addBody(world, cubeMesh(1), translation(4, 4, 4));
  EXPECT_FALSE(collide(world, kA, kB));
  EXPECT_NEAR(distance(world, kA, kB).distance, 4.0, kTol);
}

TEST(Collision, EmptyAndDegenerateMeshes) {
  World world;
  addBody(world, cubeMesh(), Transform::Identity());
  addBody(world, std::make_shared<TriangleMesh>(), Transform::Identity(), BodyKind::Graspable,
          "empty");
  // A single triangle crossing the cube.
  auto single = std::make_shared<TriangleMesh>();
  single->vertices = {{-1, 0.5, -1}, {3, 0.5, -1}, {0.5, 0.5, 3}};
  single->triangles = {{0, 1, 2}};
  addBody(world, single, Transform::Identity(), BodyKind::Graspable, "single");
  // Zero-area triangles only: repeated vertices and collinear ones.
  auto flat = std::make_shared<TriangleMesh>();
  flat->vertices = {{0.5, 0.5, 0.5}, {0.5, 0.5, 0.5}, {0, 0, 0}, {1, 1, 1}, {2, 2, 2}};
  flat->triangles = {{0, 1, 2}, {2, 3, 4}, {0, 0, 0}};
  addBody(world, flat, Transform::Identity(), BodyKind::Graspable, "flat");
  // A cube with a few zero-area triangles mixed in.
  auto mixed = cubeMesh();
  mixed->triangles.push_back({0, 0, 1});
  mixed->triangles.push_back({0, 1, 1});
  addBody(world, mixed, translation(0.5, 0.5, 0.5), BodyKind::Graspable, "mixed");

  const BodyRef cube = BodyRef::body(0), empty = BodyRef::body(1), tri = BodyRef::body(2),
                flat_ref = BodyRef::body(3), mixed_ref = BodyRef::body(4);
  EXPECT_FALSE(collide(world, cube, empty));
  EXPECT_EQ(distance(world, cube, empty).distance, std::numeric_limits<double>::infinity());
  EXPECT_TRUE(collide(world, cube, tri));
  EXPECT_FALSE(collide(world, cube, flat_ref));
  EXPECT_FALSE(collide(world, flat_ref, tri));
  EXPECT_TRUE(collide(world, cube, mixed_ref));
  EXPECT_EQ(collisionGeometry(flat), nullptr);
  EXPECT_EQ(collisionGeometry(std::make_shared<TriangleMesh>()), nullptr);

  const auto report = collisionReport(world);
  for (const CollidingPair& pair : report) {
    EXPECT_NE(pair.first, empty);
    EXPECT_NE(pair.second, empty);
    EXPECT_NE(pair.first, flat_ref);
    EXPECT_NE(pair.second, flat_ref);
  }
  EXPECT_EQ(report.size(), 3u);  // cube-single, cube-mixed, single-mixed
}

TEST(Collision, MeshWithBadVertexIndexThrows) {
  auto bad = cubeMesh();
  bad->triangles.push_back({0, 1, 99});
  EXPECT_THROW(collisionGeometry(bad), Error);
}

TEST(Collision, ReportInterestListAndFirstOnly) {
  // Three cubes in a row, each overlapping the next: pairs (0,1) and (1,2) collide.
  World world;
  for (double x : {0.0, 0.6, 1.2}) addBody(world, cubeMesh(), translation(x, 0.1, 0.1));
  EXPECT_EQ(collisionReport(world).size(), 2u);
  const BodyRef first[] = {BodyRef::body(0)};
  const auto only_first = collisionReport(world, {first, false});
  ASSERT_EQ(only_first.size(), 1u);
  EXPECT_EQ(only_first[0].second, BodyRef::body(1));
  const BodyRef last[] = {BodyRef::body(2)};
  EXPECT_EQ(collisionReport(world, {last, false}).size(), 1u);
  EXPECT_EQ(collisionReport(world, {{}, true}).size(), 1u);
  EXPECT_TRUE(anyCollision(world, first));
  EXPECT_TRUE(anyCollision(world, {}));
  world.collisionFilter().setBodyEnabled(BodyRef::body(1), false);
  EXPECT_FALSE(anyCollision(world, {}));
  EXPECT_FALSE(anyCollision(world, first));
}

// ---------------------------------------------------------------------------------------------
// The broad phase

// The sweep must find exactly the overlapping pairs that testing every pair finds, in the same
// order, on sets large enough to sweep (clustered, so most boxes meet several others).
TEST(BroadPhase, SweepFindsWhatEveryPairFinds) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> where(0.0, 100.0), size(0.0, 6.0);
  for (int n : {49, 200, 1000}) {
    std::vector<WorldBox> boxes;
    for (int i = 0; i < n; ++i)
      boxes.push_back(
          {Vector3(where(random) * n / 100.0, where(random) * 0.2, where(random) * 0.05),
           Vector3(size(random), size(random), size(random))});
    boxes[n / 2].center.x() = std::numeric_limits<double>::quiet_NaN();  // overlaps nothing
    boxes[n / 3] = boxes[n / 4];                                         // identical boxes overlap
    std::vector<std::pair<std::size_t, std::size_t>> swept, every;
    collision::forEachOverlappingPair(boxes, [&](std::size_t i, std::size_t j) {
      swept.emplace_back(i, j);
      return true;
    });
    for (std::size_t i = 0; i < boxes.size(); ++i)
      for (std::size_t j = i + 1; j < boxes.size(); ++j)
        if (boxes[i].overlaps(boxes[j])) every.emplace_back(i, j);
    EXPECT_EQ(swept, every) << n << " boxes";
    EXPECT_GT(every.size(), static_cast<std::size_t>(n) / 2) << "the set should be clustered";
  }
}

// nearbyPairs must hold every active pair a contact search could find something on: each pair
// of cubes whose surfaces come within the margin (FCL distance, a second method), and no pair
// the filter turns off. 60 cubes in a jittered row, a few close enough to touch.
TEST(BroadPhase, NearbyPairsHoldEveryPairWithinTheMargin) {
  std::mt19937 random(11);
  std::uniform_real_distribution<double> jitter(-0.3, 0.3);
  World world;
  for (int i = 0; i < 60; ++i)
    addBody(world, cubeMesh(), translation(1.15 * i + jitter(random), jitter(random), 0.0));
  world.collisionFilter().setBodyEnabled(BodyRef::body(5), false);
  for (double margin : {0.0, 0.1, 0.5}) {
    const std::vector<BodyPair> pairs = nearbyPairs(world, margin);
    int near = 0;
    for (int i = 0; i < 60; ++i) {
      for (int j = i + 1; j < 60; ++j) {
        const BodyRef a = BodyRef::body(i), b = BodyRef::body(j);
        const bool listed = std::any_of(pairs.begin(), pairs.end(), [&](const BodyPair& p) {
          return p.first == a && p.second == b;
        });
        const bool active = world.collisionFilter().isActive(world, a, b);
        if (!active) EXPECT_FALSE(listed) << i << " " << j;
        if (active && distance(world, a, b).distance <= margin) {
          ++near;
          EXPECT_TRUE(listed) << i << " " << j << " margin " << margin;
        }
      }
    }
    EXPECT_GT(near, 0) << "margin " << margin;
    EXPECT_TRUE(
        std::is_sorted(pairs.begin(), pairs.end(), [](const BodyPair& x, const BodyPair& y) {
          return std::pair(x.first, x.second) < std::pair(y.first, y.second);
        }));
  }
}

// ---------------------------------------------------------------------------------------------
// The filter

TEST(CollisionFilter, BodyPairAndStaticSwitches) {
  World world;
  addBody(world, cubeMesh(), Transform::Identity(), BodyKind::Obstacle, "table");
  addBody(world, cubeMesh(), translation(0.5, 0, 0), BodyKind::Obstacle, "wall");
  addBody(world, cubeMesh(), translation(0, 0.5, 0), BodyKind::Graspable, "box");
  const BodyRef table = BodyRef::body(0), wall = BodyRef::body(1), box = BodyRef::body(2);
  CollisionFilter& filter = world.collisionFilter();

  EXPECT_FALSE(filter.isActive(world, box, box));
  // Obstacles are checked against each other by default, as GraspIt! does.
  EXPECT_TRUE(filter.isActive(world, table, wall));
  EXPECT_EQ(collisionReport(world).size(), 3u);
  filter.setStaticPairsEnabled(false);
  EXPECT_FALSE(filter.isActive(world, table, wall));
  EXPECT_TRUE(filter.isActive(world, table, box));
  EXPECT_EQ(collisionReport(world).size(), 2u);
  filter.setStaticPairsEnabled(true);

  filter.setPairEnabled(box, table, false);
  EXPECT_FALSE(filter.isActive(world, table, box));
  EXPECT_TRUE(filter.isActive(world, wall, box));
  filter.setPairEnabled(table, box, true);  // either order names the pair
  EXPECT_TRUE(filter.isActive(world, table, box));

  filter.setBodyEnabled(box, false);
  EXPECT_FALSE(filter.isActive(world, table, box));
  EXPECT_FALSE(filter.isActive(world, box, wall));
  EXPECT_TRUE(filter.isActive(world, table, wall));
  EXPECT_EQ(collisionReport(world).size(), 1u);
  filter.setBodyEnabled(box, true);
  EXPECT_TRUE(filter.isActive(world, box, wall));

  EXPECT_THROW(filter.isActive(world, table, BodyRef::body(7)), Error);
}

// Removing a body takes its switches with it and renumbers the switches of the bodies after it:
// the same pairs stay off, now under their new indices.
TEST(CollisionFilter, SwitchesFollowARemovedBodysNeighbours) {
  World world;
  for (const char* name : {"a", "b", "c", "d"})
    addBody(world, cubeMesh(), Transform::Identity(), BodyKind::Graspable, name);
  CollisionFilter& filter = world.collisionFilter();
  filter.setBodyEnabled(BodyRef::body(1), false);                    // b
  filter.setBodyEnabled(BodyRef::body(3), false);                    // d
  filter.setPairEnabled(BodyRef::body(0), BodyRef::body(2), false);  // a-c
  filter.setPairEnabled(BodyRef::body(1), BodyRef::body(2), false);  // b-c
  world.removeBody(1);                                               // b goes
  ASSERT_EQ(world.bodies().size(), 3u);
  EXPECT_EQ(world.bodies()[1].name, "c");
  EXPECT_TRUE(filter.bodyEnabled(BodyRef::body(1)));   // c: b's switch went with b
  EXPECT_FALSE(filter.bodyEnabled(BodyRef::body(2)));  // d, renumbered
  EXPECT_FALSE(filter.pairEnabled(BodyRef::body(0), BodyRef::body(1)));      // a-c, renumbered
  EXPECT_FALSE(filter.isActive(world, BodyRef::body(0), BodyRef::body(2)));  // d is off
  EXPECT_EQ(collisionReport(world).size(), 0u);  // a-c off, d off: nothing left to collide
  EXPECT_THROW(world.removeBody(3), Error);
}

std::optional<World> bh8World() {
  const fs::path models = test::modelsDir();
  LoadOptions options;
  options.roots = {models};
  options.useEnvironment = false;
  return loadWorldFile(models / "worlds" / "default.xml", options);
}

TEST(CollisionFilter, Bh8HandRules) {
  World world = *bh8World();
  ASSERT_EQ(world.robotCount(), 1);
  const auto& chains = world.robot(0).model().chains;
  const BodyRef palm = BodyRef::robotBase(0);
  auto link = [](int c, int l) { return BodyRef::robotLink(0, {c, l}); };
  const CollisionFilter& filter = world.collisionFilter();

  for (int c = 0; c < static_cast<int>(chains.size()); ++c) {
    SCOPED_TRACE(c);
    const int n = static_cast<int>(chains[c].links.size());
    EXPECT_FALSE(filter.isActive(world, palm, link(c, 0)));  // base and first link
    for (int l = 1; l < n; ++l) EXPECT_TRUE(filter.isActive(world, palm, link(c, l)));
    // Every pair within one chain, neighbours or not (GraspIt!'s World::addRobot).
    for (int l = 0; l < n; ++l)
      for (int k = 0; k < n; ++k)
        if (k != l) EXPECT_FALSE(filter.isActive(world, link(c, l), link(c, k)));
  }
  // Links of different fingers may collide.
  EXPECT_TRUE(filter.isActive(world, link(0, 0), link(1, 0)));
  EXPECT_TRUE(filter.isActive(world, link(0, 2), link(1, 2)));
  EXPECT_TRUE(filter.isActive(world, link(2, 0), link(0, 1)));

  const BodyRef floor = BodyRef::body(0), mug = BodyRef::body(1);
  EXPECT_TRUE(filter.isActive(world, palm, mug));
  EXPECT_TRUE(filter.isActive(world, link(0, 2), floor));

  // The hand as a whole, switched off and on.
  world.collisionFilter().setRobotEnabled(0, false);
  EXPECT_FALSE(filter.isActive(world, palm, mug));
  EXPECT_FALSE(filter.isActive(world, link(0, 2), link(1, 2)));
  EXPECT_TRUE(filter.isActive(world, floor, mug));
  world.collisionFilter().setRobotEnabled(0, true);
  EXPECT_TRUE(filter.isActive(world, palm, mug));

  // A user switch cannot undo a robot rule.
  world.collisionFilter().setPairEnabled(palm, link(0, 0), true);
  world.collisionFilter().setBodyEnabled(palm, true);
  EXPECT_FALSE(filter.isActive(world, palm, link(0, 0)));

  // The hand of the default world touches nothing. (The mug stands exactly on the floor,
  // coplanar faces, which FCL counts as a collision.)
  std::vector<BodyRef> hand;
  for (const BodyRef& ref : worldBodies(world))
    if (ref.isLink()) hand.push_back(ref);
  EXPECT_EQ(hand.size(),
            1 + chains[0].links.size() + chains[1].links.size() + chains[2].links.size());
  EXPECT_TRUE(collisionReport(world, {hand, false}).empty());
  EXPECT_FALSE(anyCollision(world, hand));
}

// A hand written at test time: a palm and two chains of unit cubes. Chain 0 has three links;
// link 2 has collisionRule Off. Chain 1 has two links; link 1 overlaps chain 0's link 1.
// <disableCollision> pairs: (chain 0 link 1, chain 1 link 0) and (base, chain 1 link 1).
fs::path writeRuleHand() {
  const fs::path dir = test::scratchDir() / "rule_hand";
  fs::create_directories(dir / "iv");
  std::ofstream(dir / "iv" / "cube.off")
      << "OFF\n8 6 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n"
         "4 0 3 2 1\n4 4 5 6 7\n4 0 1 5 4\n4 2 3 7 6\n4 1 2 6 5\n4 0 4 7 3\n";
  std::ofstream(dir / "iv" / "link.xml")
      << "<root><material>plastic</material><mass>10</mass>"
         "<geometryFile type=\"off\">cube.off</geometryFile></root>\n";
  const std::string dof =
      "<dof type=\"r\"><defaultVelocity>1</defaultVelocity><maxEffort>1</maxEffort><Kp>1</Kp>"
      "<Kd>1</Kd><draggerScale>1</draggerScale></dof>\n";
  auto joint = [](int d) {
    return "<joint type=\"Revolute\"><theta>d" + std::to_string(d) +
           "</theta><d>0</d><a>2</a><alpha>0</alpha><minValue>-90</minValue>"
           "<maxValue>90</maxValue></joint>\n";
  };
  const fs::path file = dir / "rule_hand.xml";
  std::ofstream(file)
      << "<?xml version=\"1.0\" ?>\n<robot type=\"Hand\">\n<palm>link.xml</palm>\n"
      << dof << dof << "<chain>\n"
      << joint(0) << joint(0) << joint(0)
      << "<link dynamicJointType=\"Revolute\">link.xml</link>\n"
         "<link dynamicJointType=\"Revolute\">link.xml</link>\n"
         "<link dynamicJointType=\"Revolute\" collisionRule=\"Off\">link.xml</link>\n"
         "</chain>\n<chain>\n"
      << joint(1) << joint(1)
      << "<link dynamicJointType=\"Revolute\">link.xml</link>\n"
         "<link dynamicJointType=\"Revolute\" collisionRule=\"OverlappingPair\" "
         "targetChain=\"0\" targetLink=\"1\">link.xml</link>\n"
         "</chain>\n"
         "<disableCollision body1_chain=\"0\" body1_link=\"1\" body2_chain=\"1\" "
         "body2_link=\"0\"/>\n"
         "<disableCollision body1_chain=\"-1\" body1_link=\"0\" body2_chain=\"1\" "
         "body2_link=\"1\"/>\n"
         "</robot>\n";
  return file;
}

TEST(CollisionFilter, RobotFileRules) {
  auto model = loadRobotFile(writeRuleHand());
  ASSERT_EQ(model->disabledCollisions.size(), 2u);
  World world;
  world.addRobot(Robot(model));
  addBody(world, cubeMesh(), Transform::Identity(), BodyKind::Graspable, "box");
  const BodyRef palm = BodyRef::robotBase(0), box = BodyRef::body(0);
  auto link = [](int c, int l) { return BodyRef::robotLink(0, {c, l}); };
  const CollisionFilter& filter = world.collisionFilter();

  // collisionRule Off: nothing at all, not even a free body.
  EXPECT_FALSE(filter.isActive(world, link(0, 2), box));
  EXPECT_FALSE(filter.isActive(world, link(0, 2), link(1, 1)));
  EXPECT_TRUE(filter.isActive(world, link(0, 1), box));
  // OverlappingPair: chain 1 link 1 with chain 0 link 1, in either order.
  EXPECT_FALSE(filter.isActive(world, link(1, 1), link(0, 1)));
  EXPECT_FALSE(filter.isActive(world, link(0, 1), link(1, 1)));
  EXPECT_TRUE(filter.isActive(world, link(1, 1), link(0, 0)));
  // <disableCollision>, including the base written as chain -1.
  EXPECT_FALSE(filter.isActive(world, link(0, 1), link(1, 0)));
  EXPECT_FALSE(filter.isActive(world, link(1, 0), link(0, 1)));
  EXPECT_FALSE(filter.isActive(world, palm, link(1, 1)));
  EXPECT_FALSE(robotRulesAllow(world, palm, link(1, 1)));
  // What no rule names stays active.
  EXPECT_TRUE(filter.isActive(world, link(0, 0), link(1, 0)));
  EXPECT_TRUE(filter.isActive(world, palm, link(0, 1)));
  EXPECT_TRUE(filter.isActive(world, palm, box));
}

TEST(CollisionFilter, MountedRobotRules) {
  const auto model = loadRobotFile(writeRuleHand());
  World world;
  world.addRobot(Robot(model));  // parent: chain 0 ends with link 2
  world.addRobot(Robot(model));  // child, mounted on the parent's chain 1 (last link 1)
  Connection connection;
  connection.parentRobot = 0;
  connection.parentChain = 1;
  connection.childRobot = 1;
  connection.mount = modelOf(cubeMesh(), "mount");
  world.connect(connection);
  const BodyRef mount = BodyRef::mount(0), child_base = BodyRef::robotBase(1);
  const BodyRef parent_end = BodyRef::robotLink(0, {1, 1});
  const BodyRef parent_first = BodyRef::robotLink(0, {1, 0});
  const CollisionFilter& filter = world.collisionFilter();

  EXPECT_FALSE(filter.isActive(world, mount, child_base));
  EXPECT_FALSE(filter.isActive(world, child_base, mount));
  EXPECT_FALSE(filter.isActive(world, mount, parent_end));
  EXPECT_FALSE(filter.isActive(world, child_base, parent_end));
  EXPECT_FALSE(filter.isActive(world, parent_end, child_base));
  EXPECT_TRUE(filter.isActive(world, mount, parent_first));
  EXPECT_TRUE(filter.isActive(world, child_base, parent_first));
  EXPECT_TRUE(filter.isActive(world, mount, BodyRef::robotLink(1, {0, 0})));
  EXPECT_TRUE(filter.isActive(world, BodyRef::robotBase(0), child_base));
  // The mount piece belongs to the child robot.
  world.collisionFilter().setRobotEnabled(1, false);
  EXPECT_FALSE(filter.isActive(world, mount, parent_first));
  EXPECT_TRUE(filter.isActive(world, BodyRef::robotBase(0), BodyRef::robotLink(0, {0, 1})));
}

// ---------------------------------------------------------------------------------------------
// Sharing and threads

TEST(CollisionGeometryCache, ClonesShareBvhAndOwnTheirFilter) {
  World world = *bh8World();
  const World clone = world.clone();
  const BodyRef palm = BodyRef::robotBase(0), mug = BodyRef::body(1);
  const auto& mesh = bodyModel(world, palm).mesh;
  ASSERT_EQ(mesh, bodyModel(clone, palm).mesh);
  const auto geometry = collisionGeometry(mesh);
  ASSERT_NE(geometry, nullptr);
  EXPECT_EQ(geometry, collisionGeometry(bodyModel(clone, palm).mesh));
  EXPECT_EQ(geometry, collisionGeometry(mesh));

  World second = world.clone();
  second.collisionFilter().setPairEnabled(palm, mug, false);
  EXPECT_FALSE(second.collisionFilter().isActive(second, palm, mug));
  EXPECT_TRUE(world.collisionFilter().isActive(world, palm, mug));
  EXPECT_TRUE(clone.collisionFilter().isActive(clone, palm, mug));
}

TEST(CollisionGeometryCache, NewMeshAtOldAddressGetsNewGeometry) {
  // A mesh that dies must not leave its BVH to whichever mesh takes its address next.
  for (int i = 0; i < 20; ++i) {
    auto mesh = cubeMesh(1.0 + i);
    const auto geometry = collisionGeometry(mesh);
    World world;
    addBody(world, mesh, Transform::Identity());
    addBody(world, cubeMesh(), translation(0.5 + i, 0, 0));
    EXPECT_TRUE(collide(world, kA, kB)) << i;
    EXPECT_FALSE(collide(twoCubes(translation(2.5 + i, 0, 0)), kA, kB)) << i;
  }
}

TEST(CollisionGeometryCache, TwoThreadsQueryAtOnce) {
  // Fresh meshes, so both threads race to build the same BVHs, then query them.
  constexpr int kBodies = 24;
  World world;
  std::vector<std::shared_ptr<TriangleMesh>> meshes;
  for (int i = 0; i < kBodies; ++i) {
    meshes.push_back(cubeMesh(1.0 + 0.01 * i));
    addBody(world, meshes.back(), translation(0.9 * i, 0.05 * i, 0), BodyKind::Graspable,
            "c" + std::to_string(i));
  }
  // Each cube overlaps the next one (side >= 1 > 0.9 step), no other.
  const std::size_t expected = kBodies - 1;
  std::vector<std::size_t> counts(2, 0);
  std::vector<std::thread> threads;
  for (int t = 0; t < 2; ++t) {
    threads.emplace_back([&, t] {
      const World mine = world.clone();
      std::size_t total = 0;
      for (int k = 0; k < 50; ++k) total += collisionReport(mine).size();
      counts[t] = total;
    });
  }
  for (auto& thread : threads) thread.join();
  EXPECT_EQ(counts[0], 50 * expected);
  EXPECT_EQ(counts[1], 50 * expected);
  // One geometry per mesh survived the race.
  for (const auto& mesh : meshes) {
    const auto geometry = collisionGeometry(mesh);
    ASSERT_NE(geometry, nullptr);
    EXPECT_EQ(geometry, collisionGeometry(mesh));
  }
}

}  // namespace
}  // namespace graspkit
