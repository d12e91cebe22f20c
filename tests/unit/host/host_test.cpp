// The host layer: the choices, defaults and runs every front end shares (graspkit/host/).

#include <gtest/gtest.h>

#include <cmath>
#include <thread>

#include "graspkit/base/error.hpp"
#include "graspkit/host/object_task.hpp"
#include "graspkit/host/plan_task.hpp"
#include "graspkit/host/simulation_task.hpp"
#include "graspkit/host/subject.hpp"
#include "graspkit/host/world_session.hpp"
#include "graspkit/io/graspit/body_file.hpp"
#include "test_paths.hpp"

namespace graspkit {
namespace {

using test::modelsDir;

LoadOptions modelRoot() {
  LoadOptions options;
  options.roots = {modelsDir()};
  return options;
}

// drop.xml lists the floor (an obstacle) before the box (graspable): "the object" is the box,
// not the first body.
TEST(HostSubject, TheObjectIsTheFirstGraspableBodyNotTheFirstBody) {
  const auto session = host::WorldSession::load(modelsDir() / "worlds" / "drop.xml", modelRoot());
  ASSERT_EQ(session.world.bodies().size(), 2u);
  EXPECT_FALSE(session.world.bodies()[0].isDynamic());
  EXPECT_EQ(host::defaultObject(session.world).index, 1);
  EXPECT_EQ(host::objectNamed(session.world, "").index, 1);
  EXPECT_EQ(host::objectNamed(session.world, session.world.bodies()[0].name).index, 0);
  try {
    host::objectNamed(session.world, "teapot");
    FAIL() << "an unknown body was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("teapot"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(session.world.bodies()[1].name), std::string::npos);
  }
  // No robot at all: a clear error, not index 0.
  EXPECT_THROW(host::defaultHand(session.world), Error);
}

TEST(HostSubject, TheHandIsNamedByNameOrZeroBasedIndex) {
  auto session = host::WorldSession::load(modelsDir() / "worlds" / "default.xml", modelRoot());
  ASSERT_GE(session.world.robotCount(), 1);
  const int hand = host::defaultHand(session.world);
  EXPECT_TRUE(session.world.robot(hand).model().isHand);
  EXPECT_EQ(host::handNamed(session.world, ""), hand);
  EXPECT_EQ(host::handNamed(session.world, session.world.robot(hand).name()), hand);
  EXPECT_EQ(host::handNamed(session.world, std::to_string(hand)), hand);
  const std::string outside = std::to_string(session.world.robotCount());
  try {
    host::handNamed(session.world, outside);
    FAIL() << "robot " << outside << " was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("no robot with that index"), std::string::npos);
  }
  EXPECT_THROW(host::handNamed(session.world, "-1"), Error);
  EXPECT_THROW(host::handNamed(session.world, "1x"), Error);
}

TEST(HostPlanSettings, TheDefaultsAreGraspkitPlans) {
  const host::PlanSettings settings;
  auto world = std::make_shared<const World>(
      host::WorldSession::load(modelsDir() / "worlds" / "default.xml", modelRoot()).world);
  const PlanningRequest request = host::planningRequest(world, host::defaultHand(*world),
                                                        host::defaultObject(*world), settings);
  EXPECT_EQ(request.options.at("mode"), "restarts");  // simann's own default is anneal
  EXPECT_EQ(request.energy, "contact");
  EXPECT_EQ(request.seed, 1u);
  EXPECT_EQ(request.bestListSize, 20);
  EXPECT_EQ(request.threads, static_cast<int>(std::max(1u, std::thread::hardware_concurrency())));
  const PlanningBudget budget = host::planningBudget(settings);
  ASSERT_TRUE(budget.steps.has_value());
  EXPECT_EQ(*budget.steps, 40000);  // GraspIt!'s search length
  EXPECT_FALSE(budget.seconds.has_value());
}

TEST(HostPlanSettings, BadSettingsAreRefusedBeforePlanning) {
  auto world = std::make_shared<const World>(
      host::WorldSession::load(modelsDir() / "worlds" / "default.xml", modelRoot()).world);
  const int hand = host::defaultHand(*world);
  const BodyRef object = host::defaultObject(*world);
  host::PlanSettings list;
  list.planner = "list";
  list.mode = "anneal";  // a simann setting
  EXPECT_THROW(host::planningRequest(world, hand, object, list), Error);
  host::PlanSettings energy;
  energy.energy = "no-such-energy";
  EXPECT_THROW(host::planningRequest(world, hand, object, energy), Error);
  host::PlanSettings top;
  top.top = 0;
  EXPECT_THROW(host::planningRequest(world, hand, object, top), Error);
  host::PlanSettings threads;
  threads.threads = -2;
  EXPECT_THROW(host::planningRequest(world, hand, object, threads), Error);
  EXPECT_THROW(host::planningRequest(world, hand, BodyRef::body(99), {}), Error);
  host::PlanSettings both;
  both.steps = 10;
  both.seconds = 1.0;
  EXPECT_THROW(host::planningBudget(both), Error);
  host::PlanSettings zero;
  zero.steps = 0;
  EXPECT_THROW(host::planningBudget(zero), Error);
  host::PlanSettings nan;
  nan.seconds = std::nan("");
  EXPECT_THROW(host::planningBudget(nan), Error);
}

// A box dropped on the floor comes to rest with its centre at half its height plus the 0.1 mm
// contacts settle at (drop.xml's closed form), and the frames come before the first step and
// after every `every` steps.
TEST(HostSimulation, ADroppedBoxRestsWhereTheClosedFormPutsIt) {
  auto session = host::WorldSession::load(modelsDir() / "worlds" / "drop.xml", modelRoot());
  host::SimulationSettings settings;
  settings.seconds = 1.0;
  settings.every = 40;
  int frames = 0;
  const host::SimulationOutcome outcome =
      host::simulateWorld(session.world, settings, [&](const World&) { ++frames; });
  ASSERT_TRUE(outcome.completed) << outcome.stopReason;
  EXPECT_EQ(outcome.result.steps, 400);  // 1 s / 0.0025 s
  EXPECT_EQ(frames, 1 + 400 / 40);
  const double z = session.world.bodies()[1].pose.translation().z();
  EXPECT_NEAR(z, 60.1, 0.2);

  host::SimulationSettings bad;
  bad.every = 0;
  EXPECT_THROW(host::simulateWorld(session.world, bad), Error);
  host::SimulationSettings autograsp;
  autograsp.autograsp = true;  // drop.xml has no hand to close
  EXPECT_THROW(host::simulateWorld(session.world, autograsp), Error);
}

// Handles to bodies follow removals: later bodies move down one, the removed one is gone.
TEST(HostWorldSession, BodyIndicesFollowRemovals) {
  host::WorldSession session;
  const auto box = modelsDir() / "objects" / "box.xml";
  for (int i = 0; i < 4; ++i) session.addBody(box, BodyKind::Graspable);
  const std::string third = session.world.bodies()[2].name;
  const std::string fourth = session.world.bodies()[3].name;
  std::size_t seenThird = 0, seenFourth = 0, seenFirst = 0;
  int thirdIndex = 2, fourthIndex = 3, firstIndex = 0;
  session.removeBody(1);
  session.removeBody(2);  // what was the fourth body
  EXPECT_TRUE(session.followRemovals(thirdIndex, seenThird));
  EXPECT_EQ(thirdIndex, 1);
  EXPECT_EQ(session.world.bodies()[1].name, third);
  EXPECT_FALSE(session.followRemovals(fourthIndex, seenFourth));
  EXPECT_TRUE(session.followRemovals(firstIndex, seenFirst));
  EXPECT_EQ(firstIndex, 0);
  EXPECT_EQ(session.world.bodies().size(), 2u);
  (void)fourth;
}

// addFile merges a whole world and says where its bodies and robots start; a file that fails
// leaves the world as it was.
TEST(HostWorldSession, AddFileMergesAndFailsWhole) {
  auto session = host::WorldSession::load(modelsDir() / "worlds" / "drop.xml", modelRoot());
  const auto [firstBody, firstRobot] =
      session.addFile(modelsDir() / "worlds" / "default.xml", modelRoot());
  EXPECT_EQ(firstBody, 2);
  EXPECT_EQ(firstRobot, 0);
  const auto before = session.world.bodies().size();
  EXPECT_THROW(session.addFile(modelsDir() / "worlds" / "no_such_world.xml", modelRoot()), Error);
  EXPECT_EQ(session.world.bodies().size(), before);
}

// A generated object saved by the host layer loads back with the mass it was made with.
TEST(HostObjects, ASavedObjectLoadsBackWithItsMass) {
  const auto folder = test::scratchDir();
  ObjectGeneratorOptions options;
  options.seed = 9;
  const host::SavedObject saved = host::saveGeneratedObject(folder, options, 4);
  EXPECT_EQ(saved.file, folder / (saved.name + ".xml"));
  const auto body = loadBodyFile(saved.file);
  EXPECT_NEAR(body->mass, saved.mass, 1e-9 * saved.mass);
  EXPECT_EQ(saved.name, generateObject(options, 4).name);
}

}  // namespace
}  // namespace graspkit
