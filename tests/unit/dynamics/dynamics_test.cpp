// Time stepping against closed forms: free fall, a cube landing and resting, a block on an
// incline below and above its friction angle, a pendulum's period, a DOF PD controller and its
// effort limit, and the errors of bad input and bad states.

#include "graspkit/dynamics/dynamics.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "graspkit/collision/contact.hpp"
#include "graspkit/geometry/mass_properties.hpp"
#include "graspkit/model/world.hpp"
#include "test_meshes.hpp"

namespace graspkit {
namespace {

constexpr double g = kStandardGravity;

Body makeBody(const std::shared_ptr<TriangleMesh>& mesh, BodyKind kind, Material material,
              double mass, const std::string& name) {
  auto model = std::make_shared<BodyModel>();
  model->name = name;
  model->mesh = mesh;
  model->material = material;
  model->mass = mass;
  const MassProperties properties = computeMassProperties(*mesh);
  model->cog = properties.centroid;
  model->inertia = properties.inertia;
  model->maxRadius = maxRadius(*mesh, properties.centroid);
  Body body;
  body.model = model;
  body.kind = kind;
  body.name = name;
  body.setPose(Transform::Identity());
  return body;
}

Transform translation(double x, double y, double z) {
  Transform t = Transform::Identity();
  t.translation() = Vector3(x, y, z);
  return t;
}

// A 50 mm wooden cube (centred on its frame) and a 1 m x 1 m floor slab whose top is z = 0.
Body cube(double mass = 300.0) {
  return makeBody(test::box(Vector3(-25, -25, -25), Vector3(25, 25, 25)), BodyKind::Graspable,
                  Material::Wood, mass, "cube");
}
Body floorSlab() {
  return makeBody(test::box(Vector3(-500, -500, -20), Vector3(500, 500, 0)), BodyKind::Obstacle,
                  Material::Wood, 1000.0, "floor");
}

TEST(Dynamics, FreeFallFollowsTheParabola) {
  World world;
  Body body = cube();
  body.setPose(translation(0, 0, 3000));
  body.state.v << 100, 0, 0, 0, 0, 0;
  world.addBody(body);
  const SimulateResult result = simulate(world, {.seconds = 0.7});
  EXPECT_EQ(result.steps, 280);
  const double t = world.time();
  const Vector3 centre = world.bodies()[0].pose.translation();
  const double drop = g * t * t / 2.0;
  EXPECT_NEAR(centre.z(), 3000.0 - drop, 1e-3 * drop);
  EXPECT_NEAR(centre.x(), 100.0 * t, 1e-9);
  EXPECT_NEAR(world.bodies()[0].state.v.z(), -g * t, 1e-6);
}

TEST(Dynamics, DroppedCubeLandsWithoutBounceAndStaysPut) {
  World world;
  world.addBody(floorSlab());
  Body body = cube();
  body.setPose(translation(0, 0, 125));  // 100 mm above the floor
  body.state.v << 0, 0, -500, 0, 0, 0;
  const int index = world.addBody(body);
  // Falls 100 mm: lands after t = (-500 + sqrt(500^2 + 2 g 100)) / g = 0.1000 s.
  double landed = -1.0;
  double highest_after_landing = -1e9;
  simulate(world, {.seconds = 1.0, .onStep = [&](const World& w, const StepReport& report) {
                     const double z = w.bodies()[index].pose.translation().z();
                     if (landed < 0 && report.activeContacts > 0) landed = w.time();
                     if (landed >= 0) highest_after_landing = std::max(highest_after_landing, z);
                     return true;
                   }});
  const double expected_landing = (-500.0 + std::sqrt(500.0 * 500.0 + 2.0 * g * 100.0)) / g;
  EXPECT_NEAR(landed, expected_landing, 0.0051);
  const Transform rest = world.bodies()[index].pose;
  EXPECT_NEAR(rest.translation().z(), 25.0 + kRestingSeparation, 0.05);
  EXPECT_LT(highest_after_landing, 25.0 + kContactThreshold + 0.5);  // no bounce
  simulate(world, {.seconds = 5.0});
  const Transform later = world.bodies()[index].pose;
  EXPECT_LT((later.translation() - rest.translation()).norm(), 0.1);
  EXPECT_LT(Quaternion(later.linear()).angularDistance(Quaternion(rest.linear())), 1e-4);
}

// A wooden block on a wooden incline of angle theta, released at rest. Returns how far it slid
// down the slope between t = 0.5 s and t = 1.5 s, and its displacement over the first 2 s.
struct InclineRun {
  double acceleration = 0.0;
  double moved = 0.0;
};

InclineRun slideOnIncline(double theta) {
  World world;
  const Transform tilt(Eigen::AngleAxisd(theta, Vector3::UnitX()));
  // Long enough down the slope for 2 s of sliding (about 3.5 m).
  Body slab = makeBody(test::box(Vector3(-500, -5000, -20), Vector3(500, 500, 0)),
                       BodyKind::Obstacle, Material::Wood, 1000.0, "incline");
  slab.setPose(tilt);
  world.addBody(slab);
  Body body = cube(200.0);
  body.setPose(tilt * translation(0, 300, 25.0 + kRestingSeparation));
  const int index = world.addBody(body);
  const Vector3 start = world.bodies()[index].pose.translation();
  const Vector3 down_slope = tilt.linear() * Vector3(0, -1, 0);  // z falls along -y' for theta > 0
  std::vector<double> along;
  simulate(world,
           {.seconds = 2.0, .onStep = [&](const World& w, const StepReport&) {
              along.push_back((w.bodies()[index].pose.translation() - start).dot(down_slope));
              return true;
            }});
  InclineRun run;
  run.moved = (world.bodies()[index].pose.translation() - start).norm();
  // s(t) = s0 + v0 t + a t^2 / 2 sampled at t1 = 0.5, t2 = 1.0, t3 = 1.5 s: a from the second
  // difference.
  const double dt = kDefaultTimeStep;
  const auto at = [&](double t) { return along[static_cast<int>(std::lround(t / dt)) - 1]; };
  run.acceleration = (at(1.5) - 2.0 * at(1.0) + at(0.5)) / (0.5 * 0.5);
  return run;
}

TEST(Dynamics, BlockStaysOnAnInclineBelowTheFrictionAngle) {
  const double mu_s = staticFriction(Material::Wood, Material::Wood);
  const InclineRun run = slideOnIncline(std::atan(mu_s) - 0.05);
  EXPECT_LT(run.moved, 0.1);
}

TEST(Dynamics, BlockSlidesAboveTheFrictionAngleWithKineticFriction) {
  const double mu_s = staticFriction(Material::Wood, Material::Wood);
  const double mu_k = kineticFriction(Material::Wood, Material::Wood);
  const double theta = std::atan(mu_s) + 0.08;
  const InclineRun run = slideOnIncline(theta);
  const double expected = g * (std::sin(theta) - mu_k * std::cos(theta));
  EXPECT_NEAR(run.acceleration, expected, 0.02 * expected);
}

// A robot of one revolute joint whose axis is the world's x axis, carrying a 40 mm cube whose
// centre sits `arm` mm from the axis (DH a = arm). Passive unless gains are given.
std::shared_ptr<RobotModel> pendulumModel(double arm, double Kp = 0, double Kd = 0,
                                          double max_effort = 0) {
  auto model = std::make_shared<RobotModel>();
  model->name = "pendulum";
  model->type = "Robot";
  model->isHand = false;
  KinematicChain chain;
  Joint joint;
  joint.a = arm;
  joint.min = -M_PI;
  joint.max = M_PI;
  chain.joints.push_back(joint);
  Link link;
  link.lastJoint = 0;
  link.name = "pendulum_chain0_link0";
  Body bob = makeBody(test::box(Vector3(-20, -20, -20), Vector3(20, 20, 20)), BodyKind::Obstacle,
                      Material::Metal, 500.0, "bob");
  link.body = bob.model;
  chain.links.push_back(link);
  model->chains.push_back(chain);
  Dof dof;
  dof.min = -M_PI;
  dof.max = M_PI;
  dof.joints = {0};
  dof.Kp = Kp;
  dof.Kd = Kd;
  dof.maxEffort = max_effort;
  model->dofs.push_back(dof);
  return model;
}

// The joint's axis is the base's z: turn the base so that z is the world's x, and the arm
// (the base's x at angle 0) hangs along -z of the world at angle 0.
int addPendulum(World& world, std::shared_ptr<RobotModel> model) {
  Robot robot(std::move(model));
  Transform base = Transform::Identity();
  base.linear() << 0, 0, 1,  //
      0, 1, 0,               //
      -1, 0, 0;              // columns: base x -> world -z, y -> y, z -> world x
  robot.setPose(base);
  return world.addRobot(robot);
}

TEST(Dynamics, PendulumPeriodMatchesTheCompoundPendulum) {
  const double arm = 150.0;
  World world;
  const int r = addPendulum(world, pendulumModel(arm));
  const Transform base = world.robot(r).pose();
  ASSERT_NEAR(base.linear().col(2).dot(Vector3::UnitX()), 1.0, 1e-12);
  // Where gravity pulls the bob at angle 0: the arm must hang straight down there.
  const Vector3 hang = world.robot(r).linkPose(0, 0).translation() - base.translation();
  ASSERT_NEAR(hang.normalized().z(), -1.0, 1e-12);
  const double amplitude = 0.03;
  const std::vector<double> start{amplitude};
  world.setDofValues(r, start);
  // Cube of side 40 mm: I about its centre per unit mass = (40^2 + 40^2) / 12.
  const double inertia_pivot = 500.0 * (2.0 * 40.0 * 40.0 / 12.0 + arm * arm);
  const double period = 2.0 * M_PI * std::sqrt(inertia_pivot / (500.0 * g * arm));
  // Crossings of zero velocity from positive to negative angle: one per period.
  std::vector<double> turns;
  double previous = 0.0;
  simulate(world, {.seconds = 4.0 * period + 0.1,
                   .dt = 0.001,
                   .onStep = [&](const World& w, const StepReport&) {
                     const double v = w.robot(r).dofVelocities()[0];
                     if (previous > 0.0 && v <= 0.0) turns.push_back(w.time());
                     previous = v;
                     return true;
                   }});
  ASSERT_GE(turns.size(), 3u);
  const double measured = (turns.back() - turns.front()) / (turns.size() - 1);
  EXPECT_NEAR(measured, period, 0.01 * period);
}

TEST(Dynamics, PdControllerReachesItsSetPoint) {
  World world;
  world.setGravity(Vector3::Zero());
  const int r = addPendulum(world, pendulumModel(100.0, 1.0e9, 1.0e8));
  const std::vector<double> target{0.5};
  world.setDofTargets(r, target);
  simulate(world, {.seconds = 2.0});
  EXPECT_NEAR(world.robot(r).dofValues()[0], 0.5, 1e-4);
  EXPECT_NEAR(world.robot(r).dofVelocities()[0], 0.0, 1e-3);
}

TEST(Dynamics, PdControllerTorqueIsClampedToMaxEffort) {
  World world;
  world.setGravity(Vector3::Zero());
  const double max_effort = 1.0e6;
  const int r = addPendulum(world, pendulumModel(100.0, 1.0e9, 1.0e6, max_effort));
  const std::vector<double> target{1.0};
  world.setDofTargets(r, target);
  const double inertia_pivot = 500.0 * (2.0 * 40.0 * 40.0 / 12.0 + 100.0 * 100.0);
  step(world);
  // Kp * 1 rad = 1e9 wants far more than maxEffort: the joint accelerates at maxEffort / I.
  EXPECT_NEAR(world.robot(r).dofVelocities()[0], kDefaultTimeStep * max_effort / inertia_pivot,
              1e-9);
}

// GraspIt!'s compliant DOF pushes towards its target with maxEffort through a 40 mm lever,
// ramped in over the first second: torque tau(t) = maxEffort * 40 * t, so from rest
// theta(t) = maxEffort * 40 * t^3 / (6 I), and after the ramp the torque stays at its full value.
TEST(Dynamics, CompliantDofRampsItsTorqueOverTheFirstSecond) {
  World world;
  world.setGravity(Vector3::Zero());
  auto model = pendulumModel(100.0);
  model->dofs[0].type = DofType::Compliant;
  model->dofs[0].maxEffort = 3.85e5;
  const int r = addPendulum(world, model);
  world.setDofTargets(r, std::vector<double>{3.0});
  const double inertia_pivot = 500.0 * (2.0 * 40.0 * 40.0 / 12.0 + 100.0 * 100.0);
  const double full_torque = 3.85e5 * 40.0;
  simulate(world, {.seconds = 0.5, .dt = 0.0005});
  const double t = world.time();
  const double expected = full_torque * t * t * t / (6.0 * inertia_pivot);
  EXPECT_NEAR(world.robot(r).dofValues()[0], expected, 0.01 * expected);
  EXPECT_NEAR(world.robot(r).dofVelocities()[0], full_torque * t * t / (2.0 * inertia_pivot),
              0.01 * full_torque * t * t / (2.0 * inertia_pivot));
  // Past the ramp the angular acceleration is the full torque's.
  simulate(world, {.seconds = 0.6, .dt = 0.0005});
  const double v0 = world.robot(r).dofVelocities()[0];
  simulate(world, {.seconds = 0.1, .dt = 0.0005});
  const double acceleration = (world.robot(r).dofVelocities()[0] - v0) / 0.1;
  EXPECT_NEAR(acceleration, full_torque / inertia_pivot, 0.01 * full_torque / inertia_pivot);
}

// A finger of two links (100 mm and 60 mm bars turning about z) on one breakaway DOF that
// drives both joints at ratio 1, closing towards 1.5 rad, and a block [30, 45] x [30, 45] whose
// corner (45, 30) the proximal bar's top face (5 mm off its centre line) meets when
// 30 cos t - 45 sin t = 5, at t = 0.4954 rad; contacts rest 0.1 mm apart, 0.0018 rad before
// that at the corner's 54 mm. The distal bar clears the block all the way to 1.5 rad.
struct BreakawayFinger {
  World world;
  int robot = 0;
};

BreakawayFinger breakawayFinger(double break_away_torque) {
  auto model = std::make_shared<RobotModel>();
  model->name = "finger";
  model->type = "Robot";
  model->isHand = false;
  KinematicChain chain;
  for (const double length : {100.0, 60.0}) {
    Joint joint;
    joint.a = length;
    joint.min = 0.0;
    joint.max = 1.5;
    chain.joints.push_back(joint);
    Link link;
    link.lastJoint = static_cast<int>(chain.joints.size()) - 1;
    link.name = "finger_chain0_link" + std::to_string(link.lastJoint);
    // The bar ends 2 mm short of the next joint, so the links do not touch each other.
    link.body = makeBody(test::box(Vector3(-length + 2.0, -5, -5), Vector3(-2.0, 5, 5)),
                         BodyKind::Obstacle, Material::Metal, 100.0, link.name)
                    .model;
    chain.links.push_back(link);
  }
  model->chains.push_back(chain);
  Dof dof;
  dof.type = DofType::Breakaway;
  dof.min = 0.0;
  dof.max = 1.5;
  dof.joints = {0, 1};
  dof.defaultVelocity = 1.0;
  dof.Kp = 1.0e10;
  dof.Kd = 1.0e7;
  dof.maxEffort = 1.0e9;  // 1 N m
  dof.breakAwayTorque = break_away_torque;
  model->dofs.push_back(dof);

  BreakawayFinger finger;
  finger.world.setGravity(Vector3::Zero());
  finger.robot = finger.world.addRobot(Robot(model));
  finger.world.addBody(makeBody(test::box(Vector3(30, 30, -20), Vector3(45, 45, 20)),
                                BodyKind::Obstacle, Material::Wood, 1000.0, "block"));
  setClosingTargets(finger.world, finger.robot);
  return finger;
}

TEST(Dynamics, BreakawayClutchSlipsAndTheDistalJointCloses) {
  // 0.1 N m (GraspIt!'s units once read: N mm), a tenth of what the DOF can push with.
  BreakawayFinger finger = breakawayFinger(100.0);
  simulate(finger.world, {.seconds = 3.0});
  const Robot& robot = finger.world.robot(finger.robot);
  // The proximal joint stays where the block stopped it, the DOF and the distal joint close to
  // their limit.
  EXPECT_NEAR(robot.jointValues()[0], 0.4954 - 0.0018, 0.001);
  EXPECT_TRUE(robot.breakaway()[0].engaged);
  EXPECT_NEAR(robot.dofValues()[0], 1.5, 0.01);
  EXPECT_NEAR(robot.jointValues()[1], 1.5, 0.01);
}

TEST(Dynamics, BreakawayClutchHoldsBelowItsTorque) {
  // 10 N m: more than the DOF's 1 N m, so the whole finger stops at the block.
  BreakawayFinger finger = breakawayFinger(10000.0);
  simulate(finger.world, {.seconds = 3.0});
  const Robot& robot = finger.world.robot(finger.robot);
  EXPECT_FALSE(robot.breakaway()[0].engaged);
  EXPECT_NEAR(robot.jointValues()[0], 0.4954 - 0.0018, 0.001);
  EXPECT_NEAR(robot.dofValues()[0], 0.4954 - 0.0018, 0.001);
}

TEST(Dynamics, BreakawayClutchTakesHoldAgainWhenTheDofOpens) {
  BreakawayFinger finger = breakawayFinger(100.0);
  simulate(finger.world, {.seconds = 3.0});
  ASSERT_TRUE(finger.world.robot(finger.robot).breakaway()[0].engaged);
  finger.world.setDofTargets(finger.robot, std::vector<double>{0.2});
  simulate(finger.world, {.seconds = 3.0});
  const Robot& robot = finger.world.robot(finger.robot);
  EXPECT_FALSE(robot.breakaway()[0].engaged);
  EXPECT_NEAR(robot.jointValues()[0], 0.2, 0.01);
  EXPECT_NEAR(robot.jointValues()[1], 0.2, 0.01);
}

TEST(Dynamics, RefusesBadTimeSteps) {
  World world;
  world.addBody(cube());
  EXPECT_THROW(step(world, 0.0), Error);
  EXPECT_THROW(step(world, 1.0), Error);
  EXPECT_THROW(step(world, std::nan("")), Error);
  EXPECT_EQ(world.time(), 0.0);
}

TEST(Dynamics, RefusesANonPositiveMass) {
  World world;
  world.addBody(cube(0.0));
  try {
    step(world);
    FAIL() << "a massless dynamic body was stepped";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("cube"), std::string::npos) << error.what();
  }
}

// Masses and inertias that would make the contact problem singular are refused before Siconos
// sees them (it aborts the process on some): a 1e-300 g cube resting on the floor, and an
// indefinite inertia whose determinant is positive (moments -1, -1, 1).
TEST(Dynamics, RefusesMassesAndInertiasThatWouldAbortTheSolver) {
  for (int variant = 0; variant < 2; ++variant) {
    SCOPED_TRACE(variant);
    World world;
    world.addBody(floorSlab());
    Body body = cube(variant == 0 ? 1e-300 : 300.0);
    if (variant == 1) {
      auto model = std::make_shared<BodyModel>(*body.model);
      model->inertia = Vector3(-1.0, -1.0, 1.0).asDiagonal();
      body.model = model;
    }
    body.setPose(translation(0, 0, 25));
    world.addBody(std::move(body));
    try {
      simulate(world, {});
      FAIL() << "stepped";
    } catch (const Error& error) {
      EXPECT_NE(std::string(error.what()).find("cube"), std::string::npos) << error.what();
    }
  }
}

TEST(Dynamics, NanVelocityStopsWithTheState) {
  World world;
  Body body = cube();
  body.state.v[0] = std::nan("");
  world.addBody(body);
  try {
    step(world);
    FAIL() << "a NaN velocity was stepped";
  } catch (const DynamicsError& error) {
    EXPECT_NE(std::string(error.what()).find("finite"), std::string::npos) << error.what();
    EXPECT_NE(error.state().find("\"bodies\""), std::string::npos);
    EXPECT_NE(error.state().find("cube"), std::string::npos);
  }
}

// A cube placed exactly on the floor (its bottom in the floor's plane, as world files put
// objects) is in contact, not in collision: it rests there.
TEST(Dynamics, ABodyStandingExactlyOnAnotherRests) {
  World world;
  world.addBody(floorSlab());
  Body body = cube();
  body.setPose(translation(0, 0, 25));
  world.addBody(body);
  simulate(world, {.seconds = 1.0});
  const Vector3 moved = world.bodies()[1].pose.translation() - Vector3(0, 0, 25);
  // It settles at the resting separation, 0.1 mm up, and goes nowhere else.
  EXPECT_LT(moved.head<2>().norm(), 1e-3);
  EXPECT_GE(moved.z(), 0.0);
  EXPECT_LT(moved.z(), 0.1 + 1e-3);
}

// Contact margins cover what free motion can close, but an impulse can send a body farther: a
// cube hit at 2 m/s by another of the same mass (no restitution) leaves at 1 m/s, 2.5 mm in one
// step, towards a wall 1 mm away that was beyond the pair's margin when the step began. The step
// must not pass it through the wall (the next step would stop on an interpenetration): the cubes
// end at rest against the wall, each at the resting separation from the next, momentum gone.
TEST(Dynamics, ACubeKnockedFasterThanItsMarginStopsAtTheWall) {
  World world;
  world.setGravity(Vector3::Zero());
  Body wall = makeBody(test::box(Vector3(0, -100, -100), Vector3(20, 100, 100)), BodyKind::Obstacle,
                       Material::Wood, 1000.0, "wall");
  world.addBody(wall);
  Body struck = cube();
  struck.setPose(translation(-26.0, 0, 0));  // 1 mm from the wall
  const int b = world.addBody(struck);
  Body striker = cube();
  striker.setPose(translation(-26.0 - 50.0 - kRestingSeparation, 0, 0));
  striker.state.v << 2000, 0, 0, 0, 0, 0;
  const int a = world.addBody(striker);
  EXPECT_NO_THROW(simulate(world, {.seconds = 0.1}));
  const double gap_b = -25.0 - world.bodies()[b].pose.translation().x();
  const double gap_a =
      world.bodies()[b].pose.translation().x() - world.bodies()[a].pose.translation().x() - 50.0;
  EXPECT_GE(gap_b, 0.0);
  EXPECT_LT(gap_b, kContactThreshold);
  EXPECT_GE(gap_a, 0.0);
  EXPECT_LT(gap_a, kContactThreshold);
  EXPECT_LT(world.bodies()[a].state.v.head<3>().norm(), 1.0);
  EXPECT_LT(world.bodies()[b].state.v.head<3>().norm(), 1.0);
}

TEST(Dynamics, InterpenetrationAtTheStartIsAnError) {
  World world;
  world.addBody(floorSlab());
  Body body = cube();
  body.setPose(translation(0, 0, 10));  // 15 mm into the floor
  world.addBody(body);
  EXPECT_THROW(step(world), DynamicsError);
}

TEST(Dynamics, RunawayVelocityIsAnError) {
  World world;
  world.setGravity(Vector3::Zero());
  Body body = cube();
  body.state.v << 0, 0, 0, 0, 0, 500;  // rad/s
  world.addBody(body);
  EXPECT_THROW(step(world), DynamicsError);
}

}  // namespace
}  // namespace graspkit

// The Jacobians the step uses against finite differences of the kinematics: every link's
// points move as J * dq says, on the project's bh8 hand (coupled DOFs) at a random posture.
#include "dynamics/generalized_coordinates.hpp"
#include "graspkit/io/graspit/robot_file.hpp"
#include "test_paths.hpp"

namespace graspkit {
namespace {

// Every link's points move as J * dq says: each DOF nudged by eps against the kinematics.
void expectJacobiansMatchFiniteDifferences(const std::filesystem::path& robot_file) {
  World world;
  const int r = world.addRobot(Robot(loadRobotFile(robot_file)));
  Transform pose = Transform::Identity();
  pose.linear() = Eigen::AngleAxisd(0.7, Vector3(1, 2, 3).normalized()).toRotationMatrix();
  pose.translation() = Vector3(10, -20, 30);
  world.setRobotPose(r, pose);
  const Robot& robot = world.robot(r);
  std::vector<double> q(robot.dofCount());
  for (int d = 0; d < robot.dofCount(); ++d) {
    const Dof& dof = robot.model().dofs[d];
    q[d] = dof.min + (0.3 + 0.03 * (d % 10)) * (dof.max - dof.min);
  }
  world.setDofValues(r, q);
  const dynamics::GeneralizedCoordinates coordinates(world);
  const double eps = 1e-6;
  for (int d = 0; d < robot.dofCount(); ++d) {
    World moved = world.clone();
    std::vector<double> q2 = q;
    q2[d] += eps;
    moved.setDofValues(r, q2, LimitPolicy::Ignore);
    for (int c = 0; c < static_cast<int>(robot.model().chains.size()); ++c) {
      for (int l = 0; l < static_cast<int>(robot.model().chains[c].links.size()); ++l) {
        const BodyRef link = BodyRef::robotLink(r, {c, l});
        const Vector3 local(5, -7, 11);
        const Vector3 p = world.robot(r).linkPose(c, l) * local;
        const Vector3 p2 = moved.robot(r).linkPose(c, l) * local;
        const Vector3 expected = (p2 - p) / eps;
        const Vector3 column =
            coordinates.linearJacobian(link, p).col(coordinates.robotOffset(r) + d);
        EXPECT_NEAR((column - expected).norm(), 0.0, 1e-4 * (1.0 + expected.norm()))
            << "dof " << d << " chain " << c << " link " << l;
      }
    }
  }
}

// bh8: coupled DOFs (one DOF turns two joints of a finger).
TEST(DynamicsJacobian, MatchesFiniteDifferencesOnACoupledHand) {
  expectJacobiansMatchFiniteDifferences(test::modelsDir() / "robots/bh8/bh8.xml");
}

// GraspIt!'s HumanHand20DOF and ShadowHandSimple: Universal links (two joints, each with its
// DOF, between a link and the one before) besides Revolute ones.
TEST(DynamicsJacobian, MatchesFiniteDifferencesWithUniversalLinks) {
  GRASPKIT_REQUIRE_SHARED();
  for (const char* hand : {"HumanHand/HumanHand20DOF.xml", "ShadowHand/ShadowHandSimple.xml"}) {
    SCOPED_TRACE(hand);
    expectJacobiansMatchFiniteDifferences(*test::graspitDataDir() / "models/robots" / hand);
  }
}

}  // namespace
}  // namespace graspkit

// Siconos prints its warnings on standard output, where a command's --json goes: the engine's own
// numerics_warning takes the place of Siconos' (dynamics/friction_contact_solver.cpp). A
// squeezing Barrett made NSGS warn a few times per grasp validated.
extern "C" void numerics_warning(const char* function, const char* format, ...);

namespace graspkit {
namespace {

TEST(FrictionContactSolver, SiconosWarningsStayOffStandardOutput) {
  testing::internal::CaptureStdout();
  numerics_warning("fc3d_nsgs", " tolerance has to be positive!! (%d)", 1);
  std::fflush(stdout);
  EXPECT_EQ(testing::internal::GetCapturedStdout(), "");
}

}  // namespace
}  // namespace graspkit
