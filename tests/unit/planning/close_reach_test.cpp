// The bound on what a close can touch (graspkit/planning/close_reach.hpp), against the close
// itself: every state the bound rules out, closed in full by autoGrasp, has no contact with the
// object, and the autograsp-quality energy that skips those closes equals, bit for bit, the
// energy of the full close. States are drawn at random over the search space around the object
// (hand poses near the object, any posture), so that many closes touch it and many do not.

#include <cstring>
#include <fstream>
#include <iostream>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "graspkit/base/log.hpp"
#include "graspkit/collision/collision.hpp"
#include "graspkit/collision/contact_search.hpp"
#include "graspkit/grasp/autograsp.hpp"
#include "graspkit/grasp/grasp.hpp"
#include "graspkit/io/graspit/world_file.hpp"
#include "graspkit/model/world.hpp"
#include "graspkit/planning/close_reach.hpp"
#include "graspkit/planning/planner.hpp"
#include "graspkit/planning/planning_scene.hpp"
#include "graspkit/planning/search_energy.hpp"
#include "graspkit/planning/search_space.hpp"
#include "graspkit/plugin/registry.hpp"
#include "test_paths.hpp"

namespace graspkit {
namespace {

// A world of `hand` (relative to ../shared) and GraspIt!'s mug, written for the test.
std::shared_ptr<const World> handAndMug(const std::string& hand) {
  const auto shared = *test::sharedDir();
  const auto file = test::scratchDir() / "hand_and_mug.xml";
  std::ofstream(file) << "<?xml version=\"1.0\" ?>\n<world>\n<graspableBody><filename>"
                      << (shared / "graspit-data/models/objects/mug.xml").string()
                      << "</filename><transform><fullTransform>(+1 0 0 0)[0 0 150]"
                         "</fullTransform></transform></graspableBody>\n<robot><filename>"
                      << (shared / hand).string()
                      << "</filename><transform><fullTransform>(+1 0 0 0)[0 0 0]"
                         "</fullTransform></transform></robot>\n</world>\n";
  return std::make_shared<const World>(loadWorldFile(file));
}

struct Tally {
  int states = 0;
  int ruledOut = 0;         // the bound said the close cannot touch the object
  int touched = 0;          // the full close touched it
  int ruledOutTouched = 0;  // must stay 0
  int energyDiffers = 0;    // must stay 0
  int postureWithin = 0;    // links of ruled-out states' other postures within reach: must stay 0
};

// Draws `count` collision-free states over the axis-angle search space and closes each in full.
// Positions are drawn within `near` of their range, so that the hand is near the mug: at the
// edge of its reach as often as in reach or out of it.
Tally closeRandomStates(std::shared_ptr<const World> world, int count, unsigned seed, double near) {
  PlanningRequest request;
  request.world = std::move(world);
  request.object = BodyRef::body(0);
  request.energy = "autograsp-quality";
  const auto space = makeSearchSpace(request);
  const auto scene = makePlanningScene(request, space);
  auto energy = Registry::global().makeSearchEnergy("autograsp-quality");
  const CloseReach reach = closeReachOf(scene->hand().modelPtr());
  std::mt19937 random(seed);
  Tally tally;
  for (int attempt = 0; tally.states < count && attempt < 50 * count; ++attempt) {
    std::vector<double> values;
    for (const SearchVariable& v : space->variables()) {
      const double shrink = v.name.starts_with("T") ? near : 1.0;
      values.push_back(
          std::uniform_real_distribution<double>(shrink * v.min, shrink * v.max)(random));
    }
    scene->place(values);
    if (scene->handCollides()) continue;
    ++tally.states;
    const bool may = closeMayTouchObject(*scene, reach, kContactThreshold);
    const std::vector<double> start(scene->hand().dofValues().begin(),
                                    scene->hand().dofValues().end());
    const double skipping = energy->evaluate(*scene);
    scene->place(values);
    const AutoGraspResult closed = autoGrasp(scene->world(), scene->robot());
    const std::vector<Contact> on = contactsWith(closed.contacts, scene->object());
    const Grasp grasp = analyzeGrasp(scene->world(), scene->robot(), scene->object(), on);
    const double full = -(30.0 * grasp.volume + 100.0 * std::max(grasp.epsilon, 0.0));
    if (!may) {
      // The bound's claim is wider than one close: no posture with each DOF between where it
      // starts and its closing end comes within the threshold. Try some at random.
      const Robot& hand = scene->hand();
      for (int k = 0; k < 10; ++k) {
        std::vector<double> dofs;
        for (std::size_t d = 0; d < hand.model().dofs.size(); ++d) {
          const Dof& dof = hand.model().dofs[d];
          const double from = start[d];
          const double to = dof.defaultVelocity > 0   ? dof.max
                            : dof.defaultVelocity < 0 ? dof.min
                                                      : from;
          dofs.push_back(std::uniform_real_distribution<double>(std::min(from, to),
                                                                std::max(from, to))(random));
        }
        scene->world().setDofValues(scene->robot(), dofs);
        for (const BodyRef& link : scene->handLinks())
          tally.postureWithin +=
              withinDistance(scene->world(), link, scene->object(), kContactThreshold);
      }
    }
    tally.ruledOut += !may;
    tally.touched += !on.empty();
    tally.ruledOutTouched += !may && !on.empty();
    tally.energyDiffers += std::memcmp(&skipping, &full, sizeof full) != 0;
  }
  return tally;
}

void expectSound(const Tally& t, const std::string& hand) {
  SCOPED_TRACE(hand);
  std::cout << hand << ": " << t.states << " states, " << t.ruledOut << " ruled out, " << t.touched
            << " touched the object\n";
  ASSERT_GE(t.states, 100);
  EXPECT_EQ(t.ruledOutTouched, 0) << "a close the bound ruled out touched the object";
  EXPECT_EQ(t.energyDiffers, 0);
  EXPECT_EQ(t.postureWithin, 0) << "a posture of a ruled-out close comes within the threshold";
  // Not a vacuous test: the bound rules out some closes, and some of the others touch.
  EXPECT_GE(t.ruledOut, t.states / 10) << t.ruledOut << " of " << t.states;
  EXPECT_GE(t.touched, 5) << t.touched << " of " << t.states;
}

class CloseReachTest : public ::testing::Test {
 protected:
  void SetUp() override {
    GRASPKIT_REQUIRE_SHARED();
    setWarningHandler([](const Warning&) {});
  }
};

TEST_F(CloseReachTest, BarrettClosesRuledOutNeverTouchTheMug) {
  expectSound(closeRandomStates(handAndMug("graspit-data/models/robots/Barrett/Barrett.xml"), 200,
                                7, 1.0 / 3.0),
              "Barrett");
}

TEST_F(CloseReachTest, MenagerieGripperClosesRuledOutNeverTouchTheMug) {
  // An MJCF hand with a four-bar linkage and a prismatic-free close: the UMI gripper.
  expectSound(
      closeRandomStates(handAndMug("hands/menagerie/umi_gripper/umi_gripper.xml"), 300, 8, 0.25),
      "UMI gripper");
}

TEST_F(CloseReachTest, DexterousHandClosesRuledOutNeverTouchTheMug) {
  // 16 DOFs, four chains of four links (Allegro, URDF).
  expectSound(closeRandomStates(handAndMug("hands/dex-urdf/robots/hands/allegro_hand/variation/"
                                           "allegro_hand_right_fsr_simple.urdf"),
                                150, 9, 1.0 / 3.0),
              "Allegro");
}

// A close that moves the palm (the PR2 2010 gripper holds a fingertip and moves its base) is
// never ruled out; one that moves its DOFs both ways (RobotIQ) is bounded over its limits.
TEST_F(CloseReachTest, WhatACloseMovesDecidesWhatIsRuledOut) {
  for (const auto& [hand, movesPalm] : std::vector<std::pair<std::string, bool>>{
           {"graspit-data/models/robots/pr2_gripper/pr2_gripper_2010.xml", true},
           {"graspit-data/models/robots/RobotIQ/RobotIQ.xml", false}}) {
    SCOPED_TRACE(hand);
    PlanningRequest request;
    request.world = handAndMug(hand);
    request.object = BodyRef::body(0);
    const auto scene = makePlanningScene(request, makeSearchSpace(request));
    const CloseReach reach = closeReachOf(scene->hand().modelPtr());
    // A metre from the mug: no finger reaches it.
    Transform far = Transform::Identity();
    far.translation() = Vector3(1000.0, 0.0, 0.0);
    scene->setHand(far, scene->hand().dofValues());
    EXPECT_EQ(closeMayTouchObject(*scene, reach, kContactThreshold), movesPalm);
  }
}

}  // namespace
}  // namespace graspkit
