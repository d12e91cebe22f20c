// Collision on GraspIt!'s plannerMug world with its Barrett hand: GraspIt! loads the world
// collision-free, its autograsp pose (DOFs 0, 1.024375, 1.024375, 1.121875) leaves the fingers
// resting on the mug without penetrating it, and a palm pushed into the mug collides with it.

#include <gtest/gtest.h>

#include <algorithm>

#include "graspkit/base/log.hpp"
#include "graspkit/collision/collision.hpp"
#include "graspkit/io/graspit/world_file.hpp"
#include "graspkit/model/world.hpp"
#include "test_paths.hpp"

namespace graspkit {
namespace {

World plannerMug() {
  const auto previous = setWarningHandler([](const Warning&) {});
  const auto data = *test::graspitDataDir();
  World world = loadWorldFile(data / "worlds" / "plannerMug.xml", LoadOptions{{data}});
  setWarningHandler(previous);
  return world;
}

bool reports(const std::vector<CollidingPair>& report, const BodyRef& a, const BodyRef& b) {
  return std::any_of(report.begin(), report.end(), [&](const CollidingPair& p) {
    return (p.first == a && p.second == b) || (p.first == b && p.second == a);
  });
}

TEST(CollisionCompat, PlannerMugLoadsCollisionFree) {
  GRASPKIT_REQUIRE_SHARED();
  const World world = plannerMug();
  ASSERT_EQ(world.robotCount(), 1);
  ASSERT_EQ(world.robot(0).name(), "Barrett");
  const auto hand_bodies = worldBodies(world).size() - world.bodies().size();
  EXPECT_EQ(hand_bodies, 9u);  // palm and 3 + 3 + 2 links
  EXPECT_TRUE(collisionReport(world).empty());
}

TEST(CollisionCompat, AutograspPoseTouchesWithoutPenetrating) {
  GRASPKIT_REQUIRE_SHARED();
  World world = plannerMug();
  const double dofs[] = {0, 1.024375, 1.024375, 1.121875};
  world.setDofValues(0, dofs);
  EXPECT_TRUE(collisionReport(world).empty());
  // The fingertips rest on the mug, well within GraspIt!'s 0.2 mm contact threshold.
  const BodyRef mug = BodyRef::body(0);
  for (const LinkRef tip : {LinkRef{0, 2}, LinkRef{1, 2}, LinkRef{2, 1}}) {
    SCOPED_TRACE(bodyName(world, BodyRef::robotLink(0, tip)));
    const DistanceResult d = distance(world, BodyRef::robotLink(0, tip), mug);
    EXPECT_GT(d.distance, 0.0);
    EXPECT_LT(d.distance, 0.2);
    EXPECT_NEAR((d.pointOnA - d.pointOnB).norm(), d.distance, 1e-9);
  }
}

TEST(CollisionCompat, PalmSunkIntoMugCollides) {
  GRASPKIT_REQUIRE_SHARED();
  World world = plannerMug();
  const BodyRef palm = BodyRef::robotBase(0), mug = BodyRef::body(0);
  const double clearance = distance(world, palm, mug).distance;
  ASSERT_GT(clearance, 10.0);
  // Raise the hand (approach +z) past the clearance, 5 mm into the mug's bottom.
  Transform pose = Transform::Identity();
  pose.translation() = Vector3(0, 0, clearance + 5);
  world.setRobotPose(0, pose);
  const auto report = collisionReport(world);
  EXPECT_TRUE(reports(report, palm, mug));
  EXPECT_TRUE(collide(world, palm, mug));
  EXPECT_EQ(distance(world, palm, mug).distance, 0.0);
  const BodyRef interest[] = {palm};
  const auto palm_only = collisionReport(world, {interest, false});
  ASSERT_EQ(palm_only.size(), 1u);
  EXPECT_TRUE(reports(palm_only, palm, mug));
  EXPECT_TRUE(anyCollision(world, interest));
  // Never a pair the hand's own rules exclude: the palm and a chain's first link.
  for (int c = 0; c < 3; ++c) EXPECT_FALSE(reports(report, palm, BodyRef::robotLink(0, {c, 0})));
}

}  // namespace
}  // namespace graspkit
