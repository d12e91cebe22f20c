// The list and approach planner plugins, loaded through the registry as users get them.
//
// list: GraspIt!'s force-closure grasp of the mug (reference/graspit-figures.json), given as a
// file of hand states, ranks first with the autograsp-quality energy GraspIt!'s own epsilon and
// volume give, -(30 volume + 100 epsilon), and closes to a force-closure grasp with GraspIt!'s
// epsilon (1%); the hand as loaded ranks second with GraspIt!'s volume; a colliding state is
// dropped (as GraspIt!'s list planner does); bad files give errors naming file and entry.
//
// approach: every grasp's hand is collision-free before it closes, its approach axis is one of
// the Fibonacci directions and the line along it passes through the object's centre of mass and
// meets the object, its energy is what closing the hand there independently gives, and runs
// are identical (also across thread counts).

#include <cmath>
#include <fstream>
#include <numbers>

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "../compat/reference.hpp"
#include "graspkit/base/error.hpp"
#include "graspkit/grasp/autograsp.hpp"
#include "graspkit/grasp/grasp.hpp"
#include "graspkit/io/graspit/world_file.hpp"
#include "graspkit/model/robot.hpp"
#include "graspkit/planning/planner.hpp"
#include "graspkit/planning/planning_scene.hpp"
#include "graspkit/plugin/registry.hpp"
#include "graspkit/raycast/ray_scene.hpp"
#include "quiet_warnings.hpp"
#include "test_paths.hpp"

namespace graspkit {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

constexpr double kRelativeTolerance = 0.01;  // as the GraspIt! reference tests
// GraspIt!'s autograsp-quality weights.
constexpr double kVolumeWeight = 30.0;
constexpr double kEpsilonWeight = 100.0;

const json& referenceGrasp(const char* key) {
  return test::referenceJson().at("grasps").at(key);
}

PlanningRequest mugRequest(const std::string& energy) {
  test::QuietWarnings quiet;
  auto world =
      std::make_shared<World>(loadWorldFile(*test::graspitDataDir() / "worlds" / "plannerMug.xml"));
  PlanningRequest request;
  request.world = world;
  request.robot = 0;
  for (int i = 0; i < static_cast<int>(world->bodies().size()); ++i)
    if (world->bodies()[i].isDynamic()) request.object = BodyRef::body(i);
  request.energy = energy;
  request.threads = 1;
  return request;
}

json handState(const Transform& pose, const std::vector<double>& dofs) {
  const Quaternion q(pose.rotation());
  const Vector3 t = pose.translation();
  return {{"translation", {t.x(), t.y(), t.z()}},
          {"quaternion", {q.w(), q.x(), q.y(), q.z()}},
          {"dofs", dofs}};
}

fs::path writeFile(const std::string& name, const std::string& text) {
  const fs::path file = test::scratchDir() / name;
  std::ofstream(file) << text;
  return file;
}

std::vector<PlannedGrasp> runToEnd(Planner& planner) {
  PlanningBudget budget;
  budget.steps = 1000000;
  PlanningRun run = runPlanner(planner, budget);
  EXPECT_TRUE(planner.done());
  return run.grasps;
}

std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "no graspkit::Error";
  return "";
}

// --- list ---------------------------------------------------------------------------------

struct MugStates {
  json reference;  // GraspIt!'s force-closure grasp
  json asLoaded;   // the hand where the world file puts it
  json colliding;  // the hand's palm at the mug's centre of mass
};

MugStates mugStates(const PlanningRequest& request) {
  const json& fc = referenceGrasp("plannerMug_force_closure_1");
  const json& loaded = referenceGrasp("plannerMug_as_loaded");
  MugStates s;
  s.reference = handState(test::jsonPose(fc.at("hand_pose_before")),
                          fc.at("hand_dofs_before").get<std::vector<double>>());
  s.asLoaded = handState(test::jsonPose(loaded.at("hand_pose_before")),
                         loaded.at("hand_dofs_before").get<std::vector<double>>());
  const World& world = *request.world;
  const Vector3 cog = bodyPose(world, request.object) * bodyModel(world, request.object).cog;
  s.colliding = handState(makeTransform(cog, Quaternion::Identity()), {0, 0, 0, 0});
  return s;
}

TEST(ListPlanner, RanksGraspItsForceClosureGraspFirstAndDropsACollidingState) {
  GRASPKIT_REQUIRE_SHARED();
  PlanningRequest request = mugRequest("autograsp-quality");
  const MugStates s = mugStates(request);
  request.options["file"] =
      writeFile("mug_states.json", json::array({s.asLoaded, s.colliding, s.reference}).dump())
          .string();
  auto planner = Registry::global().makePlanner("list", request);
  const std::vector<PlannedGrasp> grasps = runToEnd(*planner);
  EXPECT_EQ(planner->stepsDone(), 3);
  ASSERT_EQ(grasps.size(), 2u) << "the colliding state should be dropped";

  // Energies from GraspIt!'s own volume and epsilon for these two hand states.
  const json& fc = referenceGrasp("plannerMug_force_closure_1").at("autograsp");
  const json& loaded = referenceGrasp("plannerMug_as_loaded").at("autograsp");
  const double fcEnergy = -(kVolumeWeight * fc.at("volume_L1").get<double>() +
                            kEpsilonWeight * fc.at("epsilon_L1").get<double>());
  const double loadedEnergy = -kVolumeWeight * loaded.at("volume_L1").get<double>();
  EXPECT_NEAR(grasps[0].energy, fcEnergy, kRelativeTolerance * std::abs(fcEnergy));
  EXPECT_NEAR(grasps[1].energy, loadedEnergy, kRelativeTolerance * std::abs(loadedEnergy));
  EXPECT_LT(grasps[0].energy, grasps[1].energy);
  // The first grasp is the file's hand state itself.
  const Transform given =
      test::jsonPose(referenceGrasp("plannerMug_force_closure_1").at("hand_pose_before"));
  EXPECT_LT((grasps[0].pose.translation() - given.translation()).norm(), 1e-6);
  EXPECT_LT((grasps[0].pose.linear() - given.linear()).norm(), 1e-6);

  std::vector<PlannedGrasp> first = {grasps[0]};
  finishGrasps(request, first);
  const double epsilon = fc.at("epsilon_L1").get<double>();
  EXPECT_TRUE(first[0].forceClosure);
  EXPECT_EQ(first[0].contacts, fc.at("num_contacts").get<int>());
  EXPECT_NEAR(first[0].epsilon, epsilon, kRelativeTolerance * epsilon);

  // The dropped state does collide: checked on a scene of our own.
  auto scene = makePlanningScene(request, makeSearchSpace(request));
  const Transform pose = test::jsonPose(
      {{"t_mm", s.colliding.at("translation")}, {"q_wxyz", s.colliding.at("quaternion")}});
  scene->world().setRobotPose(0, pose);
  scene->world().setDofValues(0, std::vector<double>{0, 0, 0, 0});
  EXPECT_TRUE(scene->handCollides());
}

TEST(ListPlanner, RequestStatesComeFirstAndThreadsDoNotChangeTheRanking) {
  GRASPKIT_REQUIRE_SHARED();
  PlanningRequest request = mugRequest("contact");
  const MugStates s = mugStates(request);
  // Request states: the reference grasp and the hand turned about its approach axis.
  const auto space = makeSearchSpace(request);
  const Transform pose =
      test::jsonPose(referenceGrasp("plannerMug_force_closure_1").at("hand_pose_before"));
  const auto dofs = referenceGrasp("plannerMug_force_closure_1")
                        .at("hand_dofs_before")
                        .get<std::vector<double>>();
  request.states.push_back({space->encode(pose, dofs)});
  request.options["file"] =
      writeFile("states.json", json{{"grasps", json::array({s.reference, s.asLoaded})}}.dump())
          .string();
  auto one = runToEnd(*Registry::global().makePlanner("list", request));
  request.threads = 2;
  auto two = runToEnd(*Registry::global().makePlanner("list", request));
  ASSERT_EQ(one.size(), 3u);
  ASSERT_EQ(two.size(), 3u);
  for (std::size_t i = 0; i < one.size(); ++i) {
    EXPECT_EQ(one[i].values, two[i].values);
    EXPECT_EQ(one[i].energy, two[i].energy);
    if (i > 0) EXPECT_LE(one[i - 1].energy, one[i].energy);
  }
  // The same hand state from the request and from the file: the same energy, request first.
  int same = 0;
  for (std::size_t i = 0; i + 1 < one.size(); ++i)
    if (one[i].energy == one[i + 1].energy) {
      ++same;
      EXPECT_EQ(one[i].values, request.states[0].values);
    }
  EXPECT_EQ(same, 1);
}

TEST(ListPlanner, BadInputGivesErrorsNamingTheFileAndEntry) {
  GRASPKIT_REQUIRE_SHARED();
  PlanningRequest request = mugRequest("contact");
  auto make = [&](const std::string& file) {
    PlanningRequest r = request;
    r.options["file"] = file;
    Registry::global().makePlanner("list", r);
  };
  const fs::path missing = test::scratchDir() / "missing.json";
  EXPECT_NE(errorOf([&] { make(missing.string()); }).find(missing.string()), std::string::npos);

  const fs::path notJson = writeFile("broken.json", "[{\"translation\": [1, 2");
  const std::string e1 = errorOf([&] { make(notJson.string()); });
  EXPECT_NE(e1.find(notJson.string()), std::string::npos) << e1;
  EXPECT_NE(e1.find("not JSON"), std::string::npos) << e1;

  const json good = handState(Transform::Identity(), {0, 0, 0, 0});
  json noDofs = good;
  noDofs.erase("dofs");
  const fs::path second = writeFile("no_dofs.json", json::array({good, noDofs}).dump());
  const std::string e2 = errorOf([&] { make(second.string()); });
  EXPECT_NE(e2.find(second.string() + ": entry 1: no \"dofs\""), std::string::npos) << e2;

  json threeDofs = good;
  threeDofs["dofs"] = {0, 0, 0};
  const fs::path wrong = writeFile("three_dofs.json", json::array({threeDofs}).dump());
  const std::string e3 = errorOf([&] { make(wrong.string()); });
  EXPECT_NE(e3.find(wrong.string() + ": entry 0: 3 DOF values for a hand with 4"),
            std::string::npos)
      << e3;

  // A spread of 1 with fingers apart is off the Barrett's two eigengrasps.
  json offSubspace = good;
  offSubspace["dofs"] = {1.0, 0.2, 0.9, 0.4};
  const fs::path eigen = writeFile("off_subspace.json", json::array({good, offSubspace}).dump());
  const std::string e4 = errorOf([&] { make(eigen.string()); });
  EXPECT_NE(e4.find(eigen.string() + ": entry 1: the axis-angle/eigen search space cannot"),
            std::string::npos)
      << e4;

  PlanningRequest unknown = request;
  unknown.options["fiel"] = "x";
  EXPECT_NE(errorOf([&] { Registry::global().makePlanner("list", unknown); }).find("'fiel'"),
            std::string::npos);
  EXPECT_NE(
      errorOf([&] { Registry::global().makePlanner("list", request); }).find("no hand states"),
      std::string::npos);
}

// --- approach -----------------------------------------------------------------------------

// The Fibonacci lattice written out independently of the plugin.
std::vector<Vector3> lattice(int n) {
  std::vector<Vector3> points;
  for (int i = 0; i < n; ++i) {
    const double z = 1.0 - (2.0 * i + 1.0) / n;
    const double angle = i * std::numbers::pi * (3.0 - std::sqrt(5.0));
    points.emplace_back(std::sqrt(1.0 - z * z) * std::cos(angle),
                        std::sqrt(1.0 - z * z) * std::sin(angle), z);
  }
  return points;
}

TEST(ApproachPlanner, GraspsStartFreeAndAimAtTheObjectsCentre) {
  GRASPKIT_REQUIRE_SHARED();
  PlanningRequest request = mugRequest("autograsp-quality");
  request.options = {{"directions", "16"}, {"rolls", "2"}};
  request.bestListSize = 100;
  auto planner = Registry::global().makePlanner("approach", request);
  const std::vector<PlannedGrasp> grasps = runToEnd(*planner);
  EXPECT_EQ(planner->stepsDone(), 32);
  ASSERT_GE(grasps.size(), 8u);

  const World& world = *request.world;
  const Transform objectPose = bodyPose(world, request.object);
  const Vector3 cog = objectPose * bodyModel(world, request.object).cog;
  RaySceneOptions onlyObject;
  onlyObject.include = [&](const BodyRef& b) { return b == request.object; };
  const RayScene rays(world, onlyObject);
  const Transform approachFrame = world.robot(0).model().approachFrame();
  const std::vector<Vector3> directions = lattice(16);
  auto scene = makePlanningScene(request, makeSearchSpace(request));
  int forceClosure = 0;
  for (std::size_t i = 0; i < grasps.size(); ++i) {
    const PlannedGrasp& g = grasps[i];
    if (i > 0) EXPECT_LE(grasps[i - 1].energy, g.energy);
    // Collision-free before autograsp.
    scene->world().setRobotPose(0, g.pose);
    scene->world().setDofValues(0, g.dofs);
    EXPECT_FALSE(scene->handCollides()) << "grasp " << i;
    // The approach axis: one of the lattice's directions (pointing inward), through the CoG.
    const Transform frame = g.pose * approachFrame;
    const Vector3 axis = frame.linear().col(2);
    double nearest = 1e9;
    for (const Vector3& d : directions)
      nearest = std::min(nearest, (axis + objectPose.linear() * d).norm());
    EXPECT_LT(nearest, 1e-9) << "grasp " << i;
    const Vector3 toCog = cog - frame.translation();
    EXPECT_LT((toCog - toCog.dot(axis) * axis).norm(), 1e-6) << "grasp " << i;
    EXPECT_GT(toCog.dot(axis), 0.0) << "grasp " << i;
    Ray ray;
    ray.origin = frame.translation();
    ray.direction = axis;
    EXPECT_TRUE(rays.intersect(ray).has_value()) << "grasp " << i;
    // Its energy: what closing the hand there gives, by GraspIt!'s formula.
    World closed = world.clone();
    closed.setRobotPose(0, g.pose);
    closed.setDofValues(0, g.dofs);
    autoGrasp(closed, 0);
    const Grasp measured = analyzeGrasp(closed, 0, request.object);
    const double energy =
        -(kVolumeWeight * measured.volume + kEpsilonWeight * std::max(measured.epsilon, 0.0));
    EXPECT_NEAR(g.energy, energy, 1e-9) << "grasp " << i;
    forceClosure += measured.forceClosure ? 1 : 0;
  }
  EXPECT_GT(forceClosure, 0);
}

TEST(ApproachPlanner, RunsAreIdenticalAcrossRunsAndThreadCounts) {
  GRASPKIT_REQUIRE_SHARED();
  PlanningRequest request = mugRequest("contact");
  request.options = {{"directions", "12"}, {"rolls", "3"}};
  const auto a = runToEnd(*Registry::global().makePlanner("approach", request));
  const auto b = runToEnd(*Registry::global().makePlanner("approach", request));
  request.threads = 2;
  const auto c = runToEnd(*Registry::global().makePlanner("approach", request));
  ASSERT_FALSE(a.empty());
  ASSERT_EQ(a.size(), b.size());
  ASSERT_EQ(a.size(), c.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].values, b[i].values);
    EXPECT_EQ(a[i].energy, b[i].energy);
    EXPECT_EQ(a[i].values, c[i].values);
    EXPECT_EQ(a[i].energy, c[i].energy);
  }
}

TEST(ApproachPlanner, RefusesBadOptionsAndSpaces) {
  GRASPKIT_REQUIRE_SHARED();
  PlanningRequest request = mugRequest("contact");
  request.options = {{"directions", "0"}};
  EXPECT_NE(errorOf([&] {
              Registry::global().makePlanner("approach", request);
            }).find("directions = '0'"),
            std::string::npos);
  request.options = {{"roll", "2"}};
  EXPECT_NE(errorOf([&] { Registry::global().makePlanner("approach", request); }).find("'roll'"),
            std::string::npos);
  request.options.clear();
  request.position = PositionSpace::Ellipsoid;
  EXPECT_NE(errorOf([&] { Registry::global().makePlanner("approach", request); }).find("ellipsoid"),
            std::string::npos);
}

}  // namespace
}  // namespace graspkit
