// Autograsp on this repository's own models, against what the model files say by hand:
// models/worlds/gripper_box.xml puts the parallel-jaw gripper's inner faces at x = +-(40 - d0)
// (robots/parallel_jaw/parallel_jaw.xml: chain bases at palm x = +-40, prismatic d0 towards the
// centre; the hand turned 180 degrees about x keeps world x = palm x) around the 60 mm wide box
// (objects/box.xml, faces x = +-30). Fingers span world z 70..130 (palm at z 131, links from
// palm z 1 to 61) and y -10..10; the box's top is at z 120. So closing stops at d0 just below
// 10, each jaw 0 .. 0.2 mm from its box face.

#include "graspkit/grasp/autograsp.hpp"

#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "graspkit/base/error.hpp"
#include "graspkit/collision/collision.hpp"
#include "graspkit/grasp/grasp.hpp"
#include "graspkit/io/graspit/body_file.hpp"
#include "graspkit/io/graspit/robot_file.hpp"
#include "graspkit/io/graspit/world_file.hpp"
#include "graspkit/model/robot.hpp"
#include "graspkit/model/world.hpp"
#include "test_paths.hpp"

namespace graspkit {
namespace {

constexpr double kTol = 1e-9;

World gripperBox() {
  return loadWorldFile(test::modelsDir() / "worlds" / "gripper_box.xml");
}

BodyRef graspable(const World& world) {
  for (std::size_t i = 0; i < world.bodies().size(); ++i)
    if (world.bodies()[i].kind == BodyKind::Graspable) return BodyRef::body(static_cast<int>(i));
  ADD_FAILURE() << "no graspable body";
  return {};
}

std::vector<BodyRef> robotLinks(const World& world, int robot) {
  std::vector<BodyRef> links;
  for (const BodyRef& ref : worldBodies(world))
    if (ref.isLink() && ref.index == robot) links.push_back(ref);
  return links;
}

void expectNoLinkCollides(const World& world, int robot, const BodyRef& object) {
  for (const BodyRef& link : robotLinks(world, robot))
    EXPECT_FALSE(collide(world, link, object)) << bodyName(world, link);
}

TEST(AutoGrasp, ParallelJawClosesOnTheBox) {
  World world = gripperBox();
  const BodyRef box = graspable(world);
  ASSERT_EQ(world.robot(0).dofCount(), 1);
  ASSERT_EQ(world.robot(0).dofValues()[0], 0.0);

  const AutoGraspResult result = autoGrasp(world, 0);
  EXPECT_EQ(result.end, MotionEnd::Settled);
  ASSERT_EQ(result.dofValues.size(), 1u);
  EXPECT_EQ(result.dofValues[0], world.robot(0).dofValues()[0]);

  // Each jaw's face is at |x| = 40 - d0, the box's at 30: the gap is within the threshold.
  const double d0 = result.dofValues[0];
  const double gap = 40.0 - d0 - 30.0;
  EXPECT_GT(gap, 0.0);
  EXPECT_LE(gap, kContactThreshold);
  // The opening 80 - 2 d0 matches the box's 60 mm width within one threshold per jaw.
  EXPECT_NEAR(80.0 - 2.0 * d0, 60.0, 2.0 * kContactThreshold);

  const BodyRef jaw[2] = {BodyRef::robotLink(0, LinkRef{0, 0}),
                          BodyRef::robotLink(0, LinkRef{1, 0})};
  int per_jaw[2] = {0, 0};
  for (const Contact& c : result.contacts) {
    SCOPED_TRACE(bodyName(world, c.body1) + " at " + ::testing::PrintToString(c.position1.x()));
    EXPECT_EQ(c.body2, box);
    EXPECT_GT(c.distance, 0.0);
    EXPECT_LE(c.distance, kContactThreshold);
    const int j = c.body1 == jaw[0] ? 0 : (c.body1 == jaw[1] ? 1 : -1);
    ASSERT_GE(j, 0) << "contact on " << bodyName(world, c.body1);
    ++per_jaw[j];
    // Jaw 0 is on the +x side: the normal into it is +x, its point on its face x = 30 + gap.
    const double side = j == 0 ? 1.0 : -1.0;
    EXPECT_LT((c.normal - side * Vector3::UnitX()).norm(), 1e-6) << c.normal.transpose();
    EXPECT_NEAR(c.position1.x(), side * (30.0 + gap), 1e-6);
    EXPECT_NEAR(c.position2.x(), side * 30.0, 1e-6);
    EXPECT_NEAR(c.distance, gap, 1e-6);
    // The touching patch: finger width y in [-10, 10], z from the finger tip (70) to the
    // box's top (120).
    EXPECT_LE(std::abs(c.position1.y()), 10.0 + 1e-6);
    EXPECT_GE(c.position1.z(), 70.0 - 1e-6);
    EXPECT_LE(c.position1.z(), 120.0 + 1e-6);
    // GraspIt!'s table: rubber fingers on a plastic box.
    EXPECT_DOUBLE_EQ(c.mu, 1.0);
  }
  EXPECT_GT(per_jaw[0], 0);
  EXPECT_GT(per_jaw[1], 0);
  expectNoLinkCollides(world, 0, box);
  for (const BodyRef& link : robotLinks(world, 0)) {
    if (link == jaw[0] || link == jaw[1])
      EXPECT_LE(distance(world, link, box).distance, gap + 1e-6);
  }
}

// A close asked to stop (a planner's time budget running out) ends before its next step, where
// it is, and says so: the jaw stands where the steps taken so far put it.
TEST(AutoGrasp, KeepGoingStopsTheCloseBetweenSteps) {
  World reference = gripperBox();
  const AutoGraspResult whole = autoGrasp(reference, 0);
  ASSERT_GT(whole.iterations, 4);

  World world = gripperBox();
  int asked = 0;
  AutoGraspOptions options;
  options.keepGoing = [&asked] { return ++asked <= 3; };
  const AutoGraspResult stopped = autoGrasp(world, 0, options);
  EXPECT_EQ(stopped.end, MotionEnd::Stopped);
  EXPECT_EQ(stopped.iterations, 3);
  EXPECT_EQ(asked, 4);  // asked before each of the 3 steps, and once more to stop
  EXPECT_GT(world.robot(0).dofValues()[0], 0.0);
  EXPECT_LT(world.robot(0).dofValues()[0], whole.dofValues[0]);
  EXPECT_EQ(nameOf(MotionEnd::Stopped), "stopped");
}

TEST(AutoGrasp, OpenUntilFreeAfterClosingIntoTheBox) {
  World world = gripperBox();
  const BodyRef box = graspable(world);
  const std::vector<double> into_box = {15.0};  // faces at |x| = 25, inside the box
  world.setDofValues(0, into_box);
  EXPECT_TRUE(collide(world, BodyRef::robotLink(0, LinkRef{0, 0}), box));
  EXPECT_TRUE(openUntilFree(world, 0));
  expectNoLinkCollides(world, 0, box);
  // Free means the faces are back outside the box: 40 - d0 >= 30.
  EXPECT_LE(world.robot(0).dofValues()[0], 10.0 + kTol);
}

TEST(AutoGrasp, OpenUntilFreeAfterAutoGrasp) {
  World world = gripperBox();
  autoGrasp(world, 0);
  EXPECT_TRUE(openUntilFree(world, 0));
  expectNoLinkCollides(world, 0, graspable(world));
  EXPECT_LE(world.robot(0).dofValues()[0], 10.0 + kTol);
}

TEST(AutoGrasp, BarrettOnTheMugNeverInterpenetrates) {
  World world = loadWorldFile(test::modelsDir() / "worlds" / "default.xml");
  const BodyRef mug = graspable(world);
  const AutoGraspResult result = autoGrasp(world, 0);
  EXPECT_NE(result.end, MotionEnd::InterpolationError);
  EXPECT_NE(result.end, MotionEnd::IterationLimit);
  for (const Contact& c : result.contacts) {
    EXPECT_TRUE(c.body1.isLink());
    EXPECT_EQ(c.body1.index, 0);
    EXPECT_GT(c.distance, 0.0) << bodyName(world, c.body1);
    EXPECT_LE(c.distance, kContactThreshold) << bodyName(world, c.body1);
  }
  expectNoLinkCollides(world, 0, mug);
}

// A close's own contacts, taken with one body, are what a contact search with that body alone
// finds: the planner measures its closes from them (contactsWith) instead of searching again.
TEST(AutoGrasp, ContactsWithABodyAreTheSearchWithThatBody) {
  for (const char* file : {"default.xml", "gripper_box.xml"}) {
    World world = loadWorldFile(test::modelsDir() / "worlds" / file);
    const AutoGraspResult result = autoGrasp(world, 0);
    ASSERT_FALSE(result.contacts.empty()) << file;
    std::size_t shared_out = 0;
    for (const BodyRef& body : worldBodies(world)) {
      const std::vector<Contact> taken = contactsWith(result.contacts, body);
      const std::vector<Contact> searched = robotContacts(world, 0, &body);
      ASSERT_EQ(taken.size(), searched.size()) << file << ", " << bodyName(world, body);
      for (std::size_t i = 0; i < taken.size(); ++i) {
        EXPECT_EQ(taken[i].body1, searched[i].body1);
        EXPECT_EQ(taken[i].body2, body);
        EXPECT_EQ(taken[i].position1, searched[i].position1);
        EXPECT_EQ(taken[i].normal, searched[i].normal);
        EXPECT_EQ(taken[i].distance, searched[i].distance);
      }
      shared_out += taken.size();
    }
    // Every contact is with exactly one other body.
    EXPECT_EQ(shared_out, result.contacts.size()) << file;
  }
}

// GraspIt!'s breakaway: a joint is in breakaway once its DOF has gone on more than 1e-5 past
// where the joint stopped. A contact on a distal link stops the joints behind it too, so a
// finger's DOF stops with its distal joint: that joint still follows its DOF, and a simulation
// drives the finger through it. (On this world every finger stops at one contact instant, so no
// joint is left behind; SimAnn.SavedGraspWorldsReloadToTheSameGrasp has fingers that are.)
TEST(AutoGrasp, OnlyJointsTheirDofWentOnPastAreInBreakaway) {
  World world = loadWorldFile(test::modelsDir() / "worlds" / "default.xml");
  autoGrasp(world, 0);
  const Robot& hand = world.robot(0);
  const RobotModel& model = hand.model();
  int stopped_fingers = 0;
  for (const KinematicChain& chain : model.chains) {
    for (std::size_t local = 0; local < chain.joints.size(); ++local) {
      const Joint& joint = chain.joints[local];
      const Dof& dof = model.dofs[joint.dof];
      if (dof.type != DofType::Breakaway) continue;
      const int j = chain.firstJoint + static_cast<int>(local);
      const BreakawayState& state = hand.breakaway()[j];
      const double value = hand.dofValues()[joint.dof];
      SCOPED_TRACE(j);
      if (state.engaged) EXPECT_GT(value - state.value, kBreakawayLag);
      const bool distal = local + 1 == chain.joints.size();
      if (distal && value < dof.max - 1e-6) {  // the DOF stopped at a contact, not its limit
        EXPECT_FALSE(state.engaged);
        ++stopped_fingers;
      }
    }
  }
  EXPECT_GT(stopped_fingers, 0);
}

TEST(AutoGrasp, MoveDofsToContactsStopsShortOfItsTargetOrAtTheBox) {
  // The jaw's prismatic DOF toward a target before the box (d0 = 4 leaves a 6 mm gap): it
  // stops there, in 0.5 mm steps (ceil(4 / 0.5) = 8); toward 20 (past the box) it stops at
  // the box, as autograsp does; a zero step holds the DOF.
  World world = gripperBox();
  DofMotion motion{.targets = {4.0}, .steps = {0.5}};
  AutoGraspResult result = moveDofsToContacts(world, 0, motion);
  EXPECT_EQ(result.dofValues[0], 4.0);
  EXPECT_EQ(result.iterations, 8);
  EXPECT_EQ(result.end, MotionEnd::Settled);

  motion.steps = {0.0};
  motion.targets = {20.0};
  result = moveDofsToContacts(world, 0, motion);
  EXPECT_EQ(result.dofValues[0], 4.0);
  EXPECT_EQ(result.iterations, 0);

  motion.steps = {-0.5};  // a magnitude: the sign comes from the target
  result = moveDofsToContacts(world, 0, motion);
  const double gap = 40.0 - result.dofValues[0] - 30.0;
  EXPECT_GT(gap, 0.0);
  EXPECT_LE(gap, kContactThreshold);
}

TEST(AutoGrasp, MoveDofsToContactsNamesAWrongDofCount) {
  World world = gripperBox();
  try {
    moveDofsToContacts(world, 0, DofMotion{.targets = {1.0, 2.0}, .steps = {0.1, 0.1}});
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("1 DOFs, the motion gives 2 targets"), std::string::npos)
        << e.what();
  }
}

// A given direction replaces the approach direction: the hand moves along it in a straight line
// and stops touching the box; along a zero vector it refuses to move.
TEST(AutoGrasp, ApproachAlongAGivenDirection) {
  World world;
  world.addRobot(
      Robot(loadRobotFile(test::modelsDir() / "robots" / "parallel_jaw" / "parallel_jaw.xml")));
  Body box;
  box.model = loadBodyFile(test::modelsDir() / "objects" / "box.xml");
  box.kind = BodyKind::Graspable;
  const int b = world.addBody(std::move(box));
  Transform start = Transform::Identity();
  start.translation() = Vector3(-400, 0, 0);
  world.setRobotPose(0, start);
  const AutoGraspResult result = approachToContact(
      world, 0, ApproachOptions{.maxDistance = 1000, .direction = Vector3(3, 0, 0)});
  EXPECT_EQ(result.end, MotionEnd::Contact);
  const Transform end = world.robot(0).pose();
  EXPECT_TRUE(end.linear().isApprox(start.linear(), 1e-12));
  EXPECT_NEAR(end.translation().y(), 0.0, kTol);
  EXPECT_NEAR(end.translation().z(), 0.0, kTol);
  EXPECT_GT(end.translation().x(), -400.0);
  double gap = 1e9;
  for (const BodyRef& link : robotLinks(world, 0))
    gap = std::min(gap, distance(world, link, BodyRef::body(b)).distance);
  EXPECT_LT(gap, 0.1);
  EXPECT_THROW(approachToContact(world, 0, ApproachOptions{.direction = Vector3::Zero()}), Error);
}

TEST(AutoGrasp, RobotIndexOutOfRangeThrows) {
  World world = gripperBox();
  EXPECT_THROW(autoGrasp(world, 1), Error);
  EXPECT_THROW(autoGrasp(world, -1), Error);
  EXPECT_THROW(openUntilFree(world, 1), Error);
  EXPECT_THROW(approachToContact(world, 1), Error);
  EXPECT_THROW(robotContacts(world, 1), Error);
}

TEST(AutoGrasp, RobotWithoutChainsIsNamedInTheError) {
  // Robot files must have a chain (the loader refuses one without), so the model is built here.
  auto palm = std::make_shared<BodyModel>();
  palm->name = "stump_palm";
  auto mesh = std::make_shared<TriangleMesh>();
  mesh->vertices = {Vector3(0, 0, 0), Vector3(10, 0, 0), Vector3(0, 10, 0), Vector3(0, 0, 10)};
  mesh->triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  palm->mesh = mesh;
  auto model = std::make_shared<RobotModel>();
  model->name = "Stump";
  model->type = "Hand";
  model->dbName = "Stump";
  model->palm = palm;
  World world;
  const int robot = world.addRobot(Robot(model));
  try {
    autoGrasp(world, robot);
    FAIL() << "autoGrasp accepted a robot without chains";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("Stump"), std::string::npos) << e.what();
  }
}

TEST(AutoGrasp, RobotFileWithoutChainsIsRefusedWhereItIsRead) {
  // The same robot written as a file never reaches autoGrasp: the loader names the file.
  const std::filesystem::path dir = test::scratchDir();
  std::filesystem::create_directories(dir / "iv");
  std::ofstream(dir / "iv" / "tet.off") << "OFF\n4 4 0\n0 0 0\n10 0 0\n0 10 0\n0 0 10\n"
                                           "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
  std::ofstream(dir / "iv" / "palm.xml")
      << "<root><material>plastic</material><geometryFile type=\"off\">tet.off</geometryFile>"
         "</root>\n";
  std::ofstream(dir / "Stump.xml") << "<?xml version=\"1.0\" ?>\n<robot type=\"Hand\">\n"
                                      "  <palm>palm.xml</palm>\n</robot>\n";
  std::ofstream(dir / "world.xml") << "<?xml version=\"1.0\" ?>\n<world>\n  <robot>\n"
                                      "    <filename>Stump.xml</filename>\n  </robot>\n</world>\n";
  try {
    loadWorldFile(dir / "world.xml");
    FAIL() << "a robot without chains loaded";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("Stump.xml"), std::string::npos) << e.what();
  }
}

TEST(AutoGrasp, GraspQualityOfTheParallelJaw) {
  World world = gripperBox();
  const BodyRef box = graspable(world);
  const AutoGraspResult result = autoGrasp(world, 0);
  ASSERT_FALSE(result.contacts.empty());

  // With friction: epsilon is positive exactly when the grasp is force closure.
  const Grasp with_friction = analyzeGrasp(world, 0, box, result.contacts);
  EXPECT_EQ(with_friction.epsilon > 0.0, with_friction.forceClosure);
  if (!with_friction.forceClosure) EXPECT_EQ(with_friction.epsilon, -1.0);
  EXPECT_GE(with_friction.volume, 0.0);

  // Frictionless: every normal is +-x, so no contact force has a y or z component and a force
  // along y cannot be resisted. Never force closure.
  std::vector<Contact> frictionless = result.contacts;
  for (Contact& c : frictionless) {
    c.mu = 0.0;
    c.model = ContactModel::Frictionless;
  }
  const Grasp without = analyzeGrasp(world, 0, box, frictionless);
  EXPECT_FALSE(without.forceClosure);
  EXPECT_EQ(without.epsilon, -1.0);
}

}  // namespace
}  // namespace graspkit
