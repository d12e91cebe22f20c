// Autograsp and grasp quality against GraspIt!'s own figures (reference/graspit-figures.json,
// "grasps"): the Barrett hand on the mug of worlds/plannerMug.xml, as loaded and from a
// force-closure pose. Final DOFs within 1e-6, the same contacts (same link, position within
// 0.01 mm, normal within 1e-4), epsilon and volume within 1%. GraspIt!'s L-infinity wrench
// space fails inside qhull on the force-closure grasp; ours must be built and contain the L1 one.

#include <algorithm>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "graspkit/grasp/autograsp.hpp"
#include "graspkit/grasp/grasp.hpp"
#include "graspkit/io/graspit/world_file.hpp"
#include "graspkit/model/world.hpp"
#include "reference.hpp"

namespace graspkit {
namespace {

using nlohmann::json;

constexpr double kDofTolerance = 1e-6;
constexpr double kContactPositionTolerance = 0.01;  // mm
constexpr double kNormalTolerance = 1e-4;
constexpr double kRelativeTolerance = 0.01;

World plannerMugWorld() {
  return loadWorldFile(*test::graspitDataDir() / "worlds" / "plannerMug.xml");
}

const json& grasps() {
  return test::referenceJson().at("grasps");
}

BodyRef mugOf(const World& world) {
  const BodyRef mug = BodyRef::body(0);
  EXPECT_EQ(bodyName(world, mug), "mug");
  return mug;
}

// Autograsp from the world as it stands, then the grasp, compared with `reference`.
Grasp checkAutoGrasp(World& world, const json& reference) {
  const BodyRef mug = mugOf(world);
  const AutoGraspResult result = autoGrasp(world, 0);
  const Grasp grasp = analyzeGrasp(world, 0, mug, result.contacts);

  const auto dofs = reference.at("final_dofs").get<std::vector<double>>();
  EXPECT_EQ(result.dofValues.size(), dofs.size());
  for (std::size_t d = 0; d < std::min(dofs.size(), result.dofValues.size()); ++d)
    EXPECT_NEAR(result.dofValues[d], dofs[d], kDofTolerance) << "DOF " << d;

  const json& contacts = reference.at("contacts");
  EXPECT_EQ(grasp.contacts.size(), reference.at("num_contacts").get<std::size_t>());
  EXPECT_EQ(contacts.size(), reference.at("num_contacts").get<std::size_t>());
  std::string ours;
  for (const Contact& c : grasp.contacts)
    ours += "\n  ours: " + bodyName(world, c.body1) + " at " +
            ::testing::PrintToString(c.position1.transpose()) + " normal " +
            ::testing::PrintToString(c.normal.transpose());
  // Greedy matching: each reference contact takes the first unused one of ours that agrees.
  std::vector<bool> used(grasp.contacts.size(), false);
  for (const json& expected : contacts) {
    const std::string link = expected.at("body1_link").get<std::string>();
    const Vector3 position = test::jsonVector3(expected.at("pos_world_mm"));
    const Vector3 normal = test::jsonVector3(expected.at("normal_world"));
    bool matched = false;
    for (std::size_t i = 0; i < grasp.contacts.size() && !matched; ++i) {
      const Contact& c = grasp.contacts[i];
      if (used[i] || bodyName(world, c.body1) != link) continue;
      if ((c.position1 - position).norm() > kContactPositionTolerance) continue;
      if ((c.normal - normal).norm() > kNormalTolerance) continue;
      used[i] = matched = true;
      EXPECT_NEAR(c.mu, expected.at("cof_static").get<double>(), 1e-12) << link;
    }
    EXPECT_TRUE(matched) << "no contact on " << link << " at " << position.transpose()
                         << " with normal " << normal.transpose() << ours;
  }

  const double volume = reference.at("volume_L1").get<double>();
  EXPECT_NEAR(grasp.volume, volume, kRelativeTolerance * volume);
  return grasp;
}

TEST(GraspReference, PlannerMugAsLoaded) {
  GRASPKIT_REQUIRE_SHARED();
  World world = plannerMugWorld();
  const json& reference = grasps().at("plannerMug_as_loaded").at("autograsp");
  const Grasp grasp = checkAutoGrasp(world, reference);
  EXPECT_EQ(reference.at("epsilon_L1").get<double>(), -1.0);
  EXPECT_EQ(grasp.epsilon, -1.0);
  EXPECT_FALSE(grasp.forceClosure);
}

// The force-closure case: pose and DOFs set first, as GraspIt!'s script did.
World forceClosureStart(const json& entry) {
  World world = plannerMugWorld();
  world.setRobotPose(0, test::jsonPose(entry.at("hand_pose_before")));
  const auto dofs = entry.at("hand_dofs_before").get<std::vector<double>>();
  world.setDofValues(0, dofs);
  return world;
}

TEST(GraspReference, PlannerMugForceClosure) {
  GRASPKIT_REQUIRE_SHARED();
  const json& entry = grasps().at("plannerMug_force_closure_1");
  World world = forceClosureStart(entry);
  const json& reference = entry.at("autograsp");
  const Grasp grasp = checkAutoGrasp(world, reference);
  EXPECT_EQ(grasp.contacts.size(), 4u);
  const double epsilon = reference.at("epsilon_L1").get<double>();
  EXPECT_DOUBLE_EQ(epsilon, 0.00275059144185);
  EXPECT_NEAR(grasp.epsilon, epsilon, kRelativeTolerance * epsilon);
  EXPECT_TRUE(grasp.forceClosure);
}

TEST(GraspReference, PlannerMugForceClosureLInfinity) {
  GRASPKIT_REQUIRE_SHARED();
  const json& entry = grasps().at("plannerMug_force_closure_1");
  World world = forceClosureStart(entry);
  const BodyRef mug = mugOf(world);
  const AutoGraspResult result = autoGrasp(world, 0);
  const Grasp l1 = analyzeGrasp(world, 0, mug, result.contacts);
  GraspRequest request;
  request.wrenchSpace.type = WrenchSpaceType::LInfinity;
  const Grasp linf = analyzeGrasp(world, 0, mug, result.contacts, request);
  // GraspIt! fails here (its note: epsilon -1, volume 0); the L-infinity space contains the L1
  // one, so its epsilon is at least L1's.
  EXPECT_TRUE(linf.wrenchSpace.built) << linf.wrenchSpace.failure;
  EXPECT_EQ(linf.wrenchSpace.type, WrenchSpaceType::LInfinity);
  EXPECT_TRUE(linf.forceClosure);
  ASSERT_TRUE(l1.forceClosure);
  EXPECT_GE(linf.epsilon, l1.epsilon);
  EXPECT_GE(linf.epsilon,
            entry.at("autograsp").at("epsilon_L1").get<double>() * (1.0 - kRelativeTolerance));
  EXPECT_GE(linf.volume, l1.volume);
}

}  // namespace
}  // namespace graspkit
