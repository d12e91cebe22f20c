// GraspIt!'s own dynamics example, barrettGlassDyn, with gravity on: GraspIt! throws the glass
// at 0.53 s and never lifts it (reference figures, "dynamics"). Here the Barrett closes on the
// glass under its DOF controllers, the Puma lifts the hand 100 mm (its set-points from the
// Puma's inverse kinematics), and the glass must stay in the hand for 5 s.

#include <gtest/gtest.h>

#include "graspkit/dynamics/dynamics.hpp"
#include "graspkit/grasp/robot_type.hpp"
#include "graspkit/io/graspit/world_file.hpp"
#include "graspkit/model/inverse_kinematics.hpp"
#include "graspkit/model/world.hpp"
#include "test_paths.hpp"

namespace graspkit {
namespace {

TEST(DynamicsGlass, BarrettHoldsTheGlassWhileThePumaLiftsIt) {
  GRASPKIT_REQUIRE_SHARED();
  World world = loadWorldFile(*test::graspitDataDir() / "worlds/barrettGlassDyn.xml");
  ASSERT_EQ(world.robotCount(), 2);
  const int puma = 0, hand = 1;
  const int glass = 3;
  ASSERT_EQ(world.bodies()[glass].name, "glass");
  ASSERT_NEAR(world.gravity().z(), -kStandardGravity, 0.0);

  setClosingTargets(world, hand);
  simulate(world, {.seconds = 1.5});
  const Transform palm_closed = world.robot(hand).pose();
  const Transform held = palm_closed.inverse() * world.bodies()[glass].pose;

  Transform lifted = world.robot(puma).chainEndPose(0);
  lifted.translation().z() += 100.0;
  const IkResult ik = inverseKinematics(world.robot(puma), lifted);
  ASSERT_TRUE(ik.success) << ik.failure;
  world.setDofTargets(puma, ik.dofValues);

  double worst_slip = 0.0, worst_turn = 0.0;
  simulate(world,
           {.seconds = 5.0, .onStep = [&](const World& w, const StepReport&) {
              const Transform now = w.robot(hand).pose().inverse() * w.bodies()[glass].pose;
              worst_slip = std::max(worst_slip, (now.translation() - held.translation()).norm());
              worst_turn = std::max(
                  worst_turn, Quaternion(now.linear()).angularDistance(Quaternion(held.linear())));
              return true;
            }});
  const double rise = world.robot(hand).pose().translation().z() - palm_closed.translation().z();
  EXPECT_NEAR(rise, 100.0, 1.0);
  EXPECT_LT(worst_slip, 5.0);
  EXPECT_LT(worst_turn, 15.0 * M_PI / 180.0);
  // And the glass is off the table: it rose with the hand.
  EXPECT_GT(world.bodies()[glass].pose.translation().z(),
            (palm_closed * held).translation().z() + 90.0);
}

}  // namespace
}  // namespace graspkit
