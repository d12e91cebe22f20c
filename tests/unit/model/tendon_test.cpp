// Tendon geometry and statics against hand computation, on a planar two-link finger built in
// code: joint 0 at the origin, link lengths 40 and 30 mm along x, both joints about world z.
// Link l's frame sits at the end of link l (x along the link), so a point s mm from joint l
// along the link and h mm off it has link-frame position (s - length_l, h, 0).

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "graspkit/base/error.hpp"
#include "graspkit/model/robot.hpp"
#include "graspkit/model/tendon.hpp"

namespace graspkit {
namespace {

constexpr double kTendonTolerance = 1e-9;
constexpr double kLink0 = 40.0;
constexpr double kLink1 = 30.0;

std::shared_ptr<RobotModel> fingerModel() {
  auto model = std::make_shared<RobotModel>();
  model->name = "finger";
  KinematicChain chain;
  for (int j = 0; j < 2; ++j) {
    Joint joint;
    joint.a = j == 0 ? kLink0 : kLink1;
    joint.dof = j;
    joint.min = -M_PI;
    joint.max = M_PI;
    chain.joints.push_back(joint);
    Link link;
    link.lastJoint = j;
    chain.links.push_back(link);
    Dof dof;
    dof.min = -M_PI;
    dof.max = M_PI;
    dof.joints = {j};
    model->dofs.push_back(dof);
  }
  model->chains.push_back(chain);
  return model;
}

TendonInsertionPoint at(LinkRef link, double x, double y) {
  return TendonInsertionPoint{link, Vector3(x, y, 0), 0.0};
}

const LinkRef kPalm{};
const LinkRef kLink0Ref{0, 0};
const LinkRef kLink1Ref{0, 1};

// A flexor below the finger (y = -5): palm (-20,-5), link 0 at 20 mm, link 1 at 20 mm.
Tendon flexor() {
  Tendon t;
  t.name = "flexor";
  t.insertionPoints = {at(kPalm, -20, -5), at(kLink0Ref, 20 - kLink0, -5),
                       at(kLink1Ref, 20 - kLink1, -5)};
  return t;
}

Robot fingerWith(std::vector<Tendon> tendons, std::vector<TendonWrapper> wrappers = {}) {
  auto model = fingerModel();
  model->tendons = std::move(tendons);
  model->tendonWrappers = std::move(wrappers);
  return Robot(model);
}

TEST(TendonPath, StraightTendonLengthIsTheSumOfItsSegments) {
  Robot robot = fingerWith({flexor()});
  // Straight finger: the points are (-20,-5), (20,-5), (60,-5).
  TendonPath path = tendonPath(robot, 0);
  ASSERT_EQ(path.points.size(), 3u);
  EXPECT_NEAR(path.length, 80.0, kTendonTolerance);
  EXPECT_NEAR((path.points[2].world - Vector3(60, -5, 0)).norm(), 0.0, kTendonTolerance);

  // Joint 0 at theta, joint 1 straight: the link points rotate about the origin.
  const double theta = -0.4;
  robot.setDofValues(std::vector<double>{theta, 0.0});
  const double c = std::cos(theta), s = std::sin(theta);
  const Vector3 p1(20 * c + 5 * s, 20 * s - 5 * c, 0);
  const Vector3 p2(60 * c + 5 * s, 60 * s - 5 * c, 0);
  path = tendonPath(robot, 0);
  EXPECT_NEAR(path.length, (p1 - Vector3(-20, -5, 0)).norm() + (p2 - p1).norm(), kTendonTolerance);
  EXPECT_NEAR(path.length, (p1 - Vector3(-20, -5, 0)).norm() + 40.0, kTendonTolerance);
  EXPECT_NEAR(tendonLength(robot, path), path.length, kTendonTolerance);
}

TEST(TendonStatics, JointTorqueIsMomentArmTimesForce) {
  Robot robot = fingerWith({flexor()});
  const double f = 3.0e6;
  // Straight finger: the middle point's pulls cancel; the distal point is pulled along -x at
  // 5 mm below both joint axes, a moment arm of 5 mm, clockwise (negative) about each.
  const Eigen::VectorXd tau = tendonJointTorques(robot, 0, f);
  ASSERT_EQ(tau.size(), 2);
  EXPECT_NEAR(tau[0], -5.0 * f, 1e-6);
  EXPECT_NEAR(tau[1], -5.0 * f, 1e-6);

  const std::vector<Vector3> forces = insertionForces(tendonPath(robot, 0), f);
  EXPECT_NEAR((forces[0] - Vector3(f, 0, 0)).norm(), 0.0, 1e-6);
  EXPECT_NEAR(forces[1].norm(), 0.0, 1e-6);
  EXPECT_NEAR((forces[2] - Vector3(-f, 0, 0)).norm(), 0.0, 1e-6);
}

TEST(TendonStatics, BentFingerTorqueFromTheLineOfAction) {
  // Palm (-20,-5) to one point on link 0 at 20 mm, 5 mm below; joint 0 flexed to theta. The
  // torque is the force times the distance from the joint axis to the tendon's line; the line
  // crosses x = 0 at y = -12.3, below the axis, so the pull towards the palm is clockwise.
  Tendon t;
  t.name = "short";
  t.insertionPoints = {at(kPalm, -20, -5), at(kLink0Ref, 20 - kLink0, -5)};
  Robot robot = fingerWith({t});
  const double theta = -0.7;
  robot.setDofValues(std::vector<double>{theta, 0.0});
  const Vector3 a(-20, -5, 0);
  const Vector3 p(20 * std::cos(theta) + 5 * std::sin(theta),
                  20 * std::sin(theta) - 5 * std::cos(theta), 0);
  const Vector3 u = (a - p).normalized();
  const double arm = std::abs(a.x() * u.y() - a.y() * u.x());  // |origin-to-line distance|
  const double f = 2.0;
  const Eigen::VectorXd tau = tendonJointTorques(robot, 0, f);
  EXPECT_NEAR(std::abs(tau[0]), arm * f, 1e-12);
  EXPECT_LT(tau[0], 0.0);
  EXPECT_NEAR(tau[1], 0.0, 1e-12);
}

// A wrapper: a cylinder along z, radius 5, length 10, at `centre` on `link`.
TendonWrapper cylinder(LinkRef link, Vector3 centre) {
  TendonWrapper w;
  w.link = link;
  w.position = centre;
  w.orientation = Vector3::UnitZ();
  w.radius = 5.0;
  w.length = 10.0;
  return w;
}

TEST(TendonWrapping, SegmentCuttingIntoAWrapperIsRoutedOverItsSurface) {
  // Palm points (-40,2) and (40,2) with a palm wrapper on the z axis: the segment passes 2 mm
  // from the axis, so the tendon is rerouted through (0,5), the surface point above the axis.
  // The two new segments pass 40*5/sqrt(40^2+3^2) = 4.986 mm from the axis, outside 0.995 r.
  Tendon t;
  t.name = "over";
  t.insertionPoints = {at(kPalm, -40, 2), at(kPalm, 40, 2)};
  Robot robot = fingerWith({t}, {cylinder(kPalm, Vector3::Zero())});
  const TendonPath path = tendonPath(robot, 0);
  ASSERT_EQ(path.points.size(), 3u);
  EXPECT_TRUE(path.points[1].isWrapPoint());
  EXPECT_EQ(path.points[1].wrapper, 0);
  EXPECT_NEAR((path.points[1].world - Vector3(0, 5, 0)).norm(), 0.0, kTendonTolerance);
  EXPECT_NEAR(path.length, 2.0 * std::sqrt(40.0 * 40.0 + 3.0 * 3.0), kTendonTolerance);
}

TEST(TendonWrapping, ExemptionsAndWrapperEndsLeaveTheTendonStraight) {
  Tendon t;
  t.name = "over";
  t.insertionPoints = {at(kPalm, -40, 2), at(kPalm, 40, 2)};
  TendonWrapper exempting = cylinder(kPalm, Vector3::Zero());
  exempting.exemptions = {"over"};
  EXPECT_NEAR(tendonPath(fingerWith({t}, {exempting}), 0).length, 80.0, kTendonTolerance);

  // At z = 8 the segment's closest axis point lies beyond the wrapper's end (|z| <= 5).
  Tendon high = t;
  for (auto& p : high.insertionPoints) p.position.z() = 8.0;
  const TendonPath path = tendonPath(fingerWith({high}, {cylinder(kPalm, Vector3::Zero())}), 0);
  EXPECT_EQ(path.points.size(), 2u);
  EXPECT_NEAR(path.length, 80.0, kTendonTolerance);
}

TEST(TendonWrapping, PulleyAtAJointGivesAMomentArmOfItsRadius) {
  // A wrapper on link 0 centred on joint 1's axis (40,0); the tendon runs 4.5 mm above the
  // finger from link 0 (at 20 mm) to link 1 (at 20 mm from joint 1), so it wraps at (40,5).
  Tendon t;
  t.name = "extensor";
  t.insertionPoints = {at(kLink0Ref, 20 - kLink0, 4.5), at(kLink1Ref, 20 - kLink1, 4.5)};
  Robot robot = fingerWith({t}, {cylinder(kLink0Ref, Vector3::Zero())});
  const TendonPath path = tendonPath(robot, 0);
  ASSERT_EQ(path.points.size(), 3u);
  EXPECT_NEAR((path.points[1].world - Vector3(40, 5, 0)).norm(), 0.0, kTendonTolerance);
  EXPECT_EQ(path.points[1].link, kLink0Ref);

  // The distal point (60,4.5) is pulled towards (40,5): the moment about joint 1 is
  // (20*0.5 + 4.5*20)/sqrt(20^2+0.5^2) = 100/sqrt(400.25) per unit force (counter-clockwise).
  // Joint 0 carries both ends of the tendon, so its moments cancel.
  const double f = 7.0;
  const Eigen::VectorXd tau = tendonJointTorques(robot, path, f);
  EXPECT_NEAR(tau[1], f * 100.0 / std::sqrt(400.25), 1e-12);
  EXPECT_NEAR(tau[0], 0.0, 1e-12);
}

TEST(TendonStatics, ForceIsActivePlusStretchedSpring) {
  Tendon t;
  t.stiffness = 2.0e6;
  EXPECT_NEAR(tendonForce(t, 105.0, 100.0), 1.0e7, 1e-6);  // k * 5 mm
  EXPECT_NEAR(tendonForce(t, 105.0, 100.0, 3.0), 1.0e7 + 3.0, 1e-6);
  EXPECT_EQ(tendonForce(t, 95.0, 100.0, 3.0), 3.0);   // slack: active only
  EXPECT_EQ(tendonForce(t, 95.0, 100.0, -3.0), 0.0);  // no pushing
  t.passiveForce = false;
  EXPECT_EQ(tendonForce(t, 105.0, 100.0, 3.0), 3.0);
}

TEST(TendonStatics, RestLengthIsTheFilesOrTheDefaultPostureLength) {
  auto model = fingerModel();
  model->dofs[0].defaultValue = -0.4;
  Tendon t = flexor();
  model->tendons = {t};
  Robot robot(model);
  robot.setDofValues(std::vector<double>{0.3, 0.2});  // the current posture must not matter
  // Default posture: joint 0 at -0.4, as in StraightTendonLengthIsTheSumOfItsSegments.
  const double c = std::cos(-0.4), s = std::sin(-0.4);
  const double at_default =
      (Vector3(20 * c + 5 * s, 20 * s - 5 * c, 0) - Vector3(-20, -5, 0)).norm() + 40.0;
  EXPECT_NEAR(tendonRestLength(robot, 0), at_default, kTendonTolerance);

  model->tendons[0].preTensionLength = 3.0;
  EXPECT_NEAR(tendonRestLength(Robot(model), 0), at_default - 3.0, kTendonTolerance);
  model->tendons[0].restLength = 70.0;
  EXPECT_EQ(tendonRestLength(Robot(model), 0), 70.0);
}

TEST(TendonPath, UnknownTendonIsAnError) {
  Robot robot = fingerWith({flexor()});
  EXPECT_THROW(tendonPath(robot, 1), Error);
  EXPECT_THROW(tendonRestLength(robot, -1), Error);
}

}  // namespace
}  // namespace graspkit
