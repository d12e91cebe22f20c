// The statics of a settled grasp (dynamics/static_hold.hpp) against the closed forms of
// grasp_validation_test.cpp: the parallel-jaw gripper of models/worlds/gripper_box.xml squeezes
// the 300 g plastic box between its rubber pads (mu_s = 1.0), one DOF saturated at maxEffort F
// driving both jaws. Along the pads (z) friction carries a pull up to mu_s F; across them (x) the
// box tips at F ((1 + mu_s) z1 - z0) / ((1 + mu_s) z1 + z0), the pads reaching from z0 = 10 mm to
// z1 = 60 mm above the box's centre. With no margins, statics must find an equilibrium a tenth
// below each limit and none a tenth above it; with margins, the pull they scale.

#include "graspkit/dynamics/static_hold.hpp"

#include <gtest/gtest.h>

#include "graspkit/dynamics/dynamics.hpp"
#include "graspkit/dynamics/grasp_validation.hpp"
#include "graspkit/grasp/autograsp.hpp"
#include "graspkit/io/graspit/world_file.hpp"
#include "graspkit/model/material.hpp"
#include "test_paths.hpp"

namespace graspkit {
namespace {

struct SettledSqueeze {
  World world;  // the box is body 0
  HeldContacts contacts;
  double mass = 0.0;
  double squeeze = 0.0;  // the DOF's maxEffort
};

// The gripper closed on the box, the floor taken away, squeezing without gravity for 0.5 s (it
// is at rest within 0.2 s), with the contacts of its last two steps.
SettledSqueeze settledSqueeze() {
  World world = loadWorldFile(test::modelsDir() / "worlds" / "gripper_box.xml");
  autoGrasp(world, 0);
  for (int b = static_cast<int>(world.bodies().size()) - 1; b >= 0; --b)
    if (world.bodies()[b].name != "box") world.removeBody(b);
  world.setGravity(Vector3::Zero());
  setClosingTargets(world, 0);
  std::vector<ContactImpulse> before_last, last;
  simulate(world, {.seconds = 0.5, .onStep = [&](const World& w, const StepReport&) {
                     before_last = std::move(last);
                     last = w.lastImpulses();
                     return true;
                   }});
  SettledSqueeze out{std::move(world), {}, 0.0, 0.0};
  out.contacts = heldContacts(out.world, 0, before_last, last, kDefaultTimeStep);
  out.mass = out.world.bodies()[0].model->mass;
  out.squeeze = out.world.robot(0).model().dofs[0].maxEffort;
  return out;
}

double sharedFriction() {
  return staticFriction(Material::Rubber, Material::Plastic);
}

// No margins, and a pyramid of 64 edges (within 0.12 % of the cone).
constexpr StaticHoldMargins kExact{.loadFactor = 1.0,
                                   .disturbance = 0.0,
                                   .frictionShare = 1.0,
                                   .leastShare = 0.0,
                                   .coneEdges = 64};

bool holds(const SettledSqueeze& s, const Vector3& acceleration,
           const StaticHoldMargins& margins = kExact) {
  return staticHold(s.world, 0, s.contacts, {.acceleration = acceleration, .margins = margins})
      .holds;
}

TEST(StaticHold, TheSqueezeTouchesTheBoxWithBothPadsOnly) {
  const SettledSqueeze s = settledSqueeze();
  EXPECT_FALSE(s.contacts.betweenOthers);
  ASSERT_GE(s.contacts.onObject.size(), 4u);
  Vector3 net = Vector3::Zero();
  double pressed = 0.0;
  for (const HeldContact& c : s.contacts.onObject) {
    EXPECT_EQ(c.other.kind, BodyRef::Kind::Link);
    EXPECT_NEAR(std::abs(c.normal.x()), 1.0, 1e-6);  // the pads face each other across x
    EXPECT_NEAR(c.mu, sharedFriction(), 1e-12);
    net += c.force;
    pressed += std::abs(c.force.x());
  }
  // At rest without gravity the pads' forces cancel, and their normal forces add up to the
  // squeeze (one DOF drives both jaws: N0 + N1 = F).
  EXPECT_LT(net.norm(), 1e-3 * pressed);
  EXPECT_NEAR(pressed, s.squeeze, 0.02 * s.squeeze);
}

TEST(StaticHold, FrictionAlongThePadsCarriesUpToMuTimesTheSqueeze) {
  const SettledSqueeze s = settledSqueeze();
  const double limit = sharedFriction() * s.squeeze / s.mass;
  for (const double sign : {1.0, -1.0}) {
    SCOPED_TRACE(sign);
    EXPECT_TRUE(holds(s, Vector3(0, 0, sign * 0.9 * limit)));
    EXPECT_FALSE(holds(s, Vector3(0, 0, sign * 1.1 * limit)));
  }
}

TEST(StaticHold, APullAcrossThePadsIsHeldUpToTheTippingBalance) {
  const SettledSqueeze s = settledSqueeze();
  const double low = 10.0, high = 60.0;
  const double limit = ((1.0 + sharedFriction()) * high - low) /
                       ((1.0 + sharedFriction()) * high + low) * s.squeeze / s.mass;
  for (const double sign : {1.0, -1.0}) {
    SCOPED_TRACE(sign);
    EXPECT_TRUE(holds(s, Vector3(sign * 0.9 * limit, 0, 0)));
    EXPECT_FALSE(holds(s, Vector3(sign * 1.1 * limit, 0, 0)));
  }
}

TEST(StaticHold, TheLoadFactorScalesThePull) {
  const SettledSqueeze s = settledSqueeze();
  const double limit = sharedFriction() * s.squeeze / s.mass;
  StaticHoldMargins doubled = kExact;
  doubled.loadFactor = 2.0;
  EXPECT_TRUE(holds(s, Vector3(0, 0, 0.45 * limit), doubled));
  EXPECT_FALSE(holds(s, Vector3(0, 0, 0.55 * limit), doubled));
  // A share of the friction lowers the limit by that share.
  StaticHoldMargins half_friction = kExact;
  half_friction.frictionShare = 0.5;
  EXPECT_TRUE(holds(s, Vector3(0, 0, 0.45 * limit), half_friction));
  EXPECT_FALSE(holds(s, Vector3(0, 0, 0.55 * limit), half_friction));
}

// Disturbing wrenches on top of a pull along the pads: the pads carry a quarter of the weight
// (and a moment of that times the box's radius) about every axis at the box's own weight, but a
// disturbing force along the pads adds to the pull, so near the friction limit it tips the
// balance: 0.8 of the limit plus a quarter of it is past the limit.
TEST(StaticHold, DisturbingWrenchesAddToThePull) {
  const SettledSqueeze s = settledSqueeze();
  StaticHoldMargins disturbed = kExact;
  disturbed.disturbance = 0.25;
  EXPECT_TRUE(holds(s, Vector3(0, 0, -kStandardGravity), disturbed));
  const double limit = sharedFriction() * s.squeeze / s.mass;
  EXPECT_TRUE(holds(s, Vector3(0, 0, -0.75 * limit)));
  EXPECT_FALSE(holds(s, Vector3(0, 0, -0.85 * limit), disturbed));
}

TEST(StaticHold, ContactsBetweenOtherBodiesLeaveItUndecided) {
  SettledSqueeze s = settledSqueeze();
  s.contacts.betweenOthers = true;
  const StaticHoldResult result = staticHold(s.world, 0, s.contacts, {});
  EXPECT_FALSE(result.holds);
  EXPECT_NE(result.reason.find("touch each other"), std::string::npos) << result.reason;
  EXPECT_THROW(staticHold(s.world, 3, s.contacts, {}), Error);
  EXPECT_THROW(staticHold(s.world, 0, s.contacts, {.margins = {.loadFactor = 0.5}}), Error);
}

// Statics only ever says held, and only where the simulation holds too: at 0.3 times the
// friction limit along the pads its +-z directions are decided by statics (the default load
// factor 2 keeps them within it) after a probe shorter than the simulated rest, and the labels of
// all six are the simulation's. Beyond the limit the same directions go to the simulation, which
// lets them go.
TEST(StaticHold, ValidationWithStaticsKeepsTheSimulatedLabels) {
  World world = loadWorldFile(test::modelsDir() / "worlds" / "gripper_box.xml");
  autoGrasp(world, 0);
  int box = -1;
  for (int b = 0; b < static_cast<int>(world.bodies().size()); ++b)
    if (world.bodies()[b].name == "box") box = b;
  ASSERT_GE(box, 0);
  const double limit =
      sharedFriction() * world.robot(0).model().dofs[0].maxEffort / world.bodies()[box].model->mass;
  for (const double share : {0.3, 1.1}) {
    SCOPED_TRACE(share);
    ValidationRequest request;
    request.seconds = 1.0;
    request.gravity = share * limit;
    const ValidationResult simulated = validateGrasp(world, 0, box, request);
    request.statics = true;
    const ValidationResult with_statics = validateGrasp(world, 0, box, request);
    EXPECT_EQ(with_statics.held, simulated.held);
    for (int k = 0; k < 6; ++k) {
      SCOPED_TRACE(k);
      EXPECT_EQ(with_statics.directions[k].held, simulated.directions[k].held);
      EXPECT_FALSE(simulated.directions[k].byStatics);
      if (with_statics.directions[k].byStatics) {  // ended after the probe, barely moved
        EXPECT_NEAR(with_statics.directions[k].seconds, request.staticsProbeSeconds, request.dt);
        EXPECT_LE(with_statics.directions[k].slip, request.staticsProbeShare * request.maxSlip);
        EXPECT_LT(with_statics.directions[k].seconds, simulated.directions[k].seconds);
      }
    }
    const bool along_by_statics =
        with_statics.directions[4].byStatics && with_statics.directions[5].byStatics;
    EXPECT_EQ(along_by_statics, share < 0.5);
  }
}

}  // namespace
}  // namespace graspkit
