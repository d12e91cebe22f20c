// The RobotIQ and PR2 gripper plugins on GraspIt!'s own robot files (../shared/graspit-data).
//
// Collision rules (spec "Subclasses", GraspIt!'s robots/robotiq.cpp and robots/pr2Gripper.cpp):
// on top of the engine's rules (links of one chain never collide, nor the palm with a chain's
// first link), RobotIQ excludes the palm and link 1 of chains 0-2, Pr2Gripper excludes chain 0
// link 0 with chain 1 link 0, and Pr2Gripper2010 (a plain Hand subclass in GraspIt!) nothing.
//
// RobotIQ's autograsp closes each finger phalanx by phalanx. The boxes below sit in front of
// the palm (approach +y; finger 0 on +x, fingers 1 and 2 on -x, mirror images in z), so the
// truths are hand-checkable: the proximal DOF stops where a scan of the proximal link alone
// first meets the box, the middle DOF then runs to its limit, the distal DOF closes until one
// more step would push into the box. With the palm's collisions switched off and no object,
// every phalanx ends at its limit.
//
// Pr2Gripper2010's compliant close: a 20 mm wide box between the fingertips, once centred and
// once 15 mm off-centre. Centred, both tips meet it at once and the base stays. Off-centre,
// one tip meets it first; that tip then stays still while the base slides, and the hand ends
// with the opening of the centred case (same width) and the base 15 mm sideways.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "graspkit/collision/collision.hpp"
#include "graspkit/grasp/autograsp.hpp"
#include "graspkit/io/graspit/robot_file.hpp"
#include "graspkit/model/collision_filter.hpp"
#include "graspkit/model/robot.hpp"
#include "graspkit/model/world.hpp"
#include "test_paths.hpp"

namespace graspkit {
namespace {

std::filesystem::path robotFile(const std::string& relative) {
  return *test::graspitDataDir() / "models" / "robots" / relative;
}

World worldWith(const std::string& relative) {
  World world;
  world.addRobot(Robot(loadRobotFile(robotFile(relative))));
  return world;
}

// An axis-aligned box [lo, hi] (world frame) as a graspable body.
int addBox(World& world, const Vector3& lo, const Vector3& hi) {
  auto mesh = std::make_shared<TriangleMesh>();
  for (int i = 0; i < 8; ++i) {
    mesh->vertices.emplace_back(i & 1 ? hi.x() : lo.x(), (i >> 1) & 1 ? hi.y() : lo.y(),
                                (i >> 2) & 1 ? hi.z() : lo.z());
  }
  mesh->triangles = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
                     {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
  auto model = std::make_shared<BodyModel>();
  model->name = "box";
  model->mesh = mesh;
  Body body;
  body.model = model;
  body.kind = BodyKind::Graspable;
  body.name = "box";
  return world.addBody(body);
}

bool touches(const std::vector<Contact>& contacts, const BodyRef& a, const BodyRef& b) {
  return std::any_of(contacts.begin(), contacts.end(), [&](const Contact& c) {
    return (c.body1 == a && c.body2 == b) || (c.body1 == b && c.body2 == a);
  });
}

std::vector<BodyRef> robotBodies(const World& world) {
  std::vector<BodyRef> bodies;
  for (const BodyRef& ref : worldBodies(world))
    if (ref.isLink()) bodies.push_back(ref);
  return bodies;
}

// ---------------------------------------------------------------------------------------------
// Types and collision rules

// Whether the spec's rules exclude (a, b): the engine's general ones plus the type's pairs.
bool specExcludes(const LinkRef& a, const LinkRef& b, const std::vector<CollisionPair>& extra) {
  if (!a.isBase() && !b.isBase() && a.chain == b.chain) return true;
  if (a.isBase() && b.link == 0) return true;
  if (b.isBase() && a.link == 0) return true;
  return std::any_of(extra.begin(), extra.end(), [&](const CollisionPair& p) {
    return (p.first == a && p.second == b) || (p.first == b && p.second == a);
  });
}

struct TypeCase {
  std::string file, type, plugin;
  std::vector<CollisionPair> extra;
};

TEST(HandPlugins, EachFileLoadsWithItsTypeAndExactlyTheSpecExclusions) {
  GRASPKIT_REQUIRE_SHARED();
  const LinkRef base{};
  const std::vector<TypeCase> cases = {
      {"RobotIQ/RobotIQ.xml",
       "RobotIQ",
       "robotiq",
       {{base, {0, 1}}, {base, {1, 1}}, {base, {2, 1}}}},
      {"RobotIQ/RobotIQ_FingerTip.xml",
       "RobotIQ",
       "robotiq",
       {{base, {0, 1}}, {base, {1, 1}}, {base, {2, 1}}}},
      {"pr2_gripper/pr2_gripper.xml", "Pr2Gripper", "pr2_gripper", {{{0, 0}, {1, 0}}}},
      {"pr2_gripper/pr2_gripper_2008.xml", "Pr2Gripper", "pr2_gripper", {{{0, 0}, {1, 0}}}},
      {"pr2_gripper/pr2_gripper_2010.xml", "Pr2Gripper2010", "pr2_gripper", {}},
  };
  for (const TypeCase& c : cases) {
    SCOPED_TRACE(c.file);
    const World world = worldWith(c.file);
    const RobotModel& model = world.robot(0).model();
    EXPECT_EQ(model.type, c.type);
    ASSERT_NE(model.robotType, nullptr);
    EXPECT_EQ(model.typeProvider.rfind(c.plugin + " ", 0), 0u) << model.typeProvider;
    const std::vector<BodyRef> bodies = robotBodies(world);
    int excluded = 0;
    for (const BodyRef& a : bodies) {
      for (const BodyRef& b : bodies) {
        if (a == b) continue;
        const bool expected = !specExcludes(a.link, b.link, c.extra);
        EXPECT_EQ(robotRulesAllow(world, a, b), expected)
            << bodyName(world, a) << " / " << bodyName(world, b);
        EXPECT_EQ(world.collisionFilter().isActive(world, a, b), expected);
        excluded += expected ? 0 : 1;
      }
    }
    EXPECT_GT(excluded, 0);
  }
}

TEST(HandPlugins, Pr2GripperExclusionIsWhatKeepsItsFingerBasesApart) {
  GRASPKIT_REQUIRE_SHARED();
  for (const char* file : {"pr2_gripper/pr2_gripper.xml", "pr2_gripper/pr2_gripper_2008.xml"}) {
    SCOPED_TRACE(file);
    World world = worldWith(file);
    const BodyRef a = BodyRef::robotLink(0, {0, 0}), b = BodyRef::robotLink(0, {1, 0});
    const Dof& dof = world.robot(0).model().dofs[0];
    // At rest and wide open (closed past 0 the tips cross, which no rule hides).
    for (double q : {0.0, dof.max}) {
      const double values[] = {q};
      world.setDofValues(0, values);
      EXPECT_TRUE(collide(world, a, b));            // the meshes do overlap...
      EXPECT_TRUE(collisionReport(world).empty());  // ...and the hand still counts as free
    }
  }
}

// ---------------------------------------------------------------------------------------------
// RobotIQ autograsp

struct FingerLayout {
  int chain, firstDof, proximalLink;
};
constexpr FingerLayout kRobotIQFingers[] = {{0, 0, 0}, {1, 4, 1}, {2, 8, 1}};

// RobotIQ at rest with each distal DOF already at its min, where phase 1 would take it, so
// that phase 1 moves the proximal DOFs alone.
World robotIQStraight() {
  World world = worldWith("RobotIQ/RobotIQ.xml");
  const RobotModel& model = world.robot(0).model();
  std::vector<double> q(11, 0.0);
  for (const FingerLayout& f : kRobotIQFingers) q[f.firstDof + 2] = model.dofs[f.firstDof + 2].min;
  world.setDofValues(0, q);
  return world;
}

// The first value of `dof` (scanning up from its current value in 1e-4 rad) at which `link`
// collides with `object`: the test's own root finding, independent of the autograsp loop.
double firstCollision(World world, int dof, const BodyRef& link, const BodyRef& object) {
  std::vector<double> q(world.robot(0).dofValues().begin(), world.robot(0).dofValues().end());
  const double max = world.robot(0).model().dofs[dof].max;
  for (; q[dof] <= max; q[dof] += 1e-4) {
    world.setDofValues(0, q);
    if (collide(world, link, object)) return q[dof];
  }
  return max;
}

// A 60 mm slab across the palm, moved `shift` mm along x: shifted, one side's proximal
// phalanges touch first and end the motion's round while the other side's still close.
void closeOnSlab(double shift) {
  SCOPED_TRACE(shift);
  World world = robotIQStraight();
  const BodyRef box = BodyRef::body(addBox(world, {shift - 30, 52, -60}, {shift + 30, 62, 60}));
  ASSERT_TRUE(collisionReport(world).empty());
  const World start = world.clone();
  const RobotModel& model = world.robot(0).model();

  const AutoGraspResult result = autoGrasp(world, 0);
  EXPECT_EQ(result.end, MotionEnd::Settled);
  EXPECT_TRUE(collisionReport(world).empty());
  const auto q = world.robot(0).dofValues();
  EXPECT_EQ(q[3], 0.0);  // the scissor DOFs never move
  EXPECT_EQ(q[7], 0.0);
  for (const FingerLayout& f : kRobotIQFingers) {
    SCOPED_TRACE(f.chain);
    const BodyRef proximal = BodyRef::robotLink(0, {f.chain, f.proximalLink});
    const BodyRef middle = BodyRef::robotLink(0, {f.chain, f.proximalLink + 1});
    const BodyRef distal = BodyRef::robotLink(0, {f.chain, f.proximalLink + 2});
    // Phase 1: the proximal phalanx stopped where it first meets the box. It stops at the
    // first step that leaves it within the contact threshold (0.2 mm), so short of the
    // scanned collision by less than one 0.01 rad step.
    const double hit = firstCollision(start.clone(), f.firstDof, proximal, box);
    EXPECT_LT(hit, model.dofs[f.firstDof].max - 0.1);
    EXPECT_LE(q[f.firstDof], hit);
    EXPECT_GT(q[f.firstDof], hit - 0.01);
    EXPECT_TRUE(touches(result.contacts, proximal, box));
    EXPECT_LT(distance(world, proximal, box).distance, kContactThreshold);
    // Phase 2: nothing stops the middle phalanx, which reaches its limit exactly.
    EXPECT_EQ(q[f.firstDof + 1], model.dofs[f.firstDof + 1].max);
    EXPECT_FALSE(touches(result.contacts, middle, box));
    // Phase 3: the distal phalanx closed from its min until it touches the box; one more
    // autograsp step (0.01 rad) would push it in.
    EXPECT_GT(q[f.firstDof + 2], model.dofs[f.firstDof + 2].min + 0.1);
    EXPECT_LT(q[f.firstDof + 2], model.dofs[f.firstDof + 2].max);
    EXPECT_TRUE(touches(result.contacts, distal, box));
    World further = world.clone();
    std::vector<double> ahead(q.begin(), q.end());
    ahead[f.firstDof + 2] += 0.01;
    further.setDofValues(0, ahead);
    EXPECT_TRUE(collide(further, distal, box));
  }
  // Fingers 1 and 2 mirror each other in z.
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(q[4 + k], q[8 + k], 1e-12);
  EXPECT_LT(result.iterations, 1000 * 500);
}

TEST(RobotIQAutoGrasp, ProximalStopsAtTheBoxThenMiddleThenDistal) {
  GRASPKIT_REQUIRE_SHARED();
  closeOnSlab(0.0);
  closeOnSlab(4.0);   // finger 0 touches first
  closeOnSlab(-4.0);  // fingers 1 and 2 touch first
}

TEST(RobotIQAutoGrasp, WithoutObstaclesEveryPhalanxEndsAtItsLimit) {
  GRASPKIT_REQUIRE_SHARED();
  World world = worldWith("RobotIQ/RobotIQ.xml");
  const RobotModel& model = world.robot(0).model();
  // Scissor DOFs away from 0, to see that they hold; the palm out of collision detection, so
  // nothing stops any finger.
  std::vector<double> q(11, 0.0);
  q[3] = 0.1;
  q[7] = -0.1;
  world.setDofValues(0, q);
  for (const BodyRef& link : robotBodies(world))
    world.collisionFilter().setPairEnabled(BodyRef::robotBase(0), link, false);

  const AutoGraspResult result = autoGrasp(world, 0);
  EXPECT_EQ(result.end, MotionEnd::Settled);
  const auto v = world.robot(0).dofValues();
  EXPECT_EQ(v[3], 0.1);
  EXPECT_EQ(v[7], -0.1);
  for (const FingerLayout& f : kRobotIQFingers)
    for (int k = 0; k < 3; ++k) EXPECT_EQ(v[f.firstDof + k], model.dofs[f.firstDof + k].max);
  // Steps of 0.01 rad: phase 1 takes the proximal DOF from 0 to its max (the distal DOF going
  // to its min meanwhile, in fewer steps), then the middle from 0 and the distal from its min
  // to their maxes, one after the other; the steps of the three fingers are shared.
  const auto steps = [](double from, double to) { return std::ceil((to - from) / 0.01 - 1e-9); };
  const double expected = steps(0, model.dofs[0].max) + steps(0, model.dofs[1].max) +
                          steps(model.dofs[2].min, model.dofs[2].max);
  EXPECT_EQ(result.iterations, expected);
}

TEST(RobotIQAutoGrasp, WithThePalmTheDistalPhalanxStopsOnIt) {
  GRASPKIT_REQUIRE_SHARED();
  World world = worldWith("RobotIQ/RobotIQ.xml");
  const RobotModel& model = world.robot(0).model();
  const AutoGraspResult result = autoGrasp(world, 0);
  EXPECT_TRUE(collisionReport(world).empty());
  const auto v = world.robot(0).dofValues();
  for (const FingerLayout& f : kRobotIQFingers) {
    SCOPED_TRACE(f.chain);
    EXPECT_EQ(v[f.firstDof], model.dofs[f.firstDof].max);
    EXPECT_EQ(v[f.firstDof + 1], model.dofs[f.firstDof + 1].max);
    EXPECT_LT(v[f.firstDof + 2], model.dofs[f.firstDof + 2].max);
    const BodyRef distal = BodyRef::robotLink(0, {f.chain, f.proximalLink + 2});
    EXPECT_TRUE(touches(result.contacts, distal, BodyRef::robotBase(0)));
  }
}

TEST(RobotIQAutoGrasp, OpeningJumpsToTheOpenPoseKeepingTheScissor) {
  GRASPKIT_REQUIRE_SHARED();
  World world = worldWith("RobotIQ/RobotIQ.xml");
  std::vector<double> q = {0.5, 0.5, 0.2, 0.15, 0.5, 0.5, 0.2, -0.15, 0.5, 0.5, 0.2};
  world.setDofValues(0, q);
  autoGrasp(world, 0, {.speedFactor = -1.0});
  const auto v = world.robot(0).dofValues();
  for (int d = 0; d < 11; ++d) EXPECT_EQ(v[d], d == 3 ? 0.15 : d == 7 ? -0.15 : 0.0) << d;
}

// ---------------------------------------------------------------------------------------------
// Pr2Gripper2010 compliant close

constexpr double kPr2Open = 0.5235987755982988;  // 30 degrees, the DOF's max

// The 2010 gripper wide open around a 20 mm (y) box centred at y = `centre` between the
// fingertips (x 150..190 reaches inside both tips, which span x 128..185 when open).
World pr2AroundBox(double centre) {
  World world = worldWith("pr2_gripper/pr2_gripper_2010.xml");
  const double open[] = {kPr2Open};
  world.setDofValues(0, open);
  addBox(world, {150, centre - 10, -20}, {190, centre + 10, 20});
  return world;
}

const BodyRef kTip0 = BodyRef::robotLink(0, {0, 1});
const BodyRef kTip1 = BodyRef::robotLink(0, {1, 1});
const BodyRef kBox = BodyRef::body(0);

TEST(Pr2Gripper2010AutoGrasp, CentredBoxBothTipsTouchAndTheBaseStays) {
  GRASPKIT_REQUIRE_SHARED();
  World world = pr2AroundBox(0.0);
  ASSERT_TRUE(collisionReport(world).empty());
  const AutoGraspResult result = autoGrasp(world, 0);
  EXPECT_TRUE(world.robot(0).pose().isApprox(Transform::Identity(), 0.0));
  EXPECT_TRUE(touches(result.contacts, kTip0, kBox));
  EXPECT_TRUE(touches(result.contacts, kTip1, kBox));
  EXPECT_TRUE(collisionReport(world).empty());
}

TEST(Pr2Gripper2010AutoGrasp, OffCentreBoxTheFirstTipStaysAndTheBaseSlides) {
  GRASPKIT_REQUIRE_SHARED();
  // Where the first (plain) closing leaves the tip that meets the box first: chain 0's, on +y.
  World plain = pr2AroundBox(15.0);
  const AutoGraspResult first = genericAutoGrasp(plain, 0);
  ASSERT_TRUE(touches(first.contacts, kTip0, kBox));
  ASSERT_FALSE(touches(first.contacts, kTip1, kBox));
  const Transform tip_at_touch = bodyPose(plain, kTip0);

  World world = pr2AroundBox(15.0);
  const AutoGraspResult result = autoGrasp(world, 0);
  EXPECT_TRUE(collisionReport(world).empty());
  EXPECT_TRUE(touches(result.contacts, kTip0, kBox));
  EXPECT_TRUE(touches(result.contacts, kTip1, kBox));
  EXPECT_LT((bodyPose(world, kTip0).translation() - tip_at_touch.translation()).norm(), 1e-6);
  EXPECT_TRUE(bodyPose(world, kTip0).linear().isApprox(tip_at_touch.linear(), 1e-9));
  // The tip's collisions are back on.
  EXPECT_TRUE(world.collisionFilter().bodyEnabled(kTip0));

  // Same width as the centred box, so the same opening; the base ends 15 mm sideways (to
  // within the 0.1 mm the contact instant is found to), turned not at all.
  World centred = pr2AroundBox(0.0);
  autoGrasp(centred, 0);
  EXPECT_NEAR(world.robot(0).dofValues()[0], centred.robot(0).dofValues()[0], 1e-3);
  const Transform base = world.robot(0).pose();
  EXPECT_NEAR(base.translation().y(), 15.0, 0.1);
  EXPECT_TRUE(base.linear().isApprox(Matrix3::Identity(), 1e-9));
  // The slide along the approach axis is the fingertip's own: the parallel-link tip moves on an
  // arc of radius a = 91.503986 mm (pr2_gripper_2010.xml), so closing from q1 to q2 brings it
  // a * (cos(q2 + t) - cos(q1 + t)) forward, t = 3.100986421 degrees, and the base backs off
  // by as much.
  const double a = 91.503986, t = 3.100986421 * M_PI / 180.0;
  const double q1 = first.dofValues[0], q2 = world.robot(0).dofValues()[0];
  EXPECT_NEAR(base.translation().x(), -a * (std::cos(q2 + t) - std::cos(q1 + t)), 1e-6);
  EXPECT_NEAR(base.translation().z(), 0.0, 1e-9);
}

TEST(Pr2Gripper2010AutoGrasp, WithoutTheCompliantCloseTheHandWouldStopAtTheFirstTouch) {
  GRASPKIT_REQUIRE_SHARED();
  // The generic closing on the same off-centre box leaves tip 1 short of the box: what the
  // compliant close is there to fix.
  World world = pr2AroundBox(15.0);
  genericAutoGrasp(world, 0);
  EXPECT_GT(distance(world, kTip1, kBox).distance, 5.0);
  EXPECT_TRUE(world.robot(0).pose().isApprox(Transform::Identity(), 0.0));
}

}  // namespace
}  // namespace graspkit
