// The generic iterative inverse kinematics (GraspIt!'s DOF-space Jacobian solver).
// Truths: the closed-form IK of a planar two-link arm built in code; for GraspIt!'s Barrett and
// Robonaut fingers (../shared), the DOF vector q* whose forward kinematics made the target (a
// finger with fewer DOFs than 6 has an isolated solution, so the solver must return q* itself);
// GraspIt!'s rejection rules (0.2 rad jump, joint limits); and failure, not NaN or a throw, for
// targets out of reach.

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "graspkit/base/error.hpp"
#include "graspkit/grasp/robot_type.hpp"
#include "graspkit/io/graspit/robot_file.hpp"
#include "graspkit/model/inverse_kinematics.hpp"
#include "graspkit/model/robot.hpp"
#include "test_paths.hpp"

namespace graspkit {
namespace {

// The solver stops when its last step is below 1e-4 rad. Gauss-Newton on a reachable target
// converges quadratically, so the pose it leaves is off by about |dq|^2 scaled by the chain's
// curvature: up to 1.9e-7 mm and 2.7e-8 rad on the fingers below (measured), hence tolerances
// of 1e-5 mm and 1e-6 rad: far tighter than any use of a finger pose, with a 50x margin.
constexpr double kPositionTolerance = 1e-5;     // mm
constexpr double kOrientationTolerance = 1e-6;  // rad
constexpr double kDofTolerance = 1e-7;          // rad, against q*

// A planar arm: chain of revolute joints about z (alpha 0), link lengths `lengths`, each joint
// driven by its own DOF with range [min, max].
std::shared_ptr<RobotModel> planarArm(const std::vector<double>& lengths, double min = -M_PI,
                                      double max = M_PI) {
  auto model = std::make_shared<RobotModel>();
  model->name = "planar";
  model->type = "Robot";
  KinematicChain chain;
  for (std::size_t j = 0; j < lengths.size(); ++j) {
    Joint joint;
    joint.a = lengths[j];
    joint.dof = static_cast<int>(j);
    joint.min = min;
    joint.max = max;
    chain.joints.push_back(joint);
    Link link;
    link.lastJoint = static_cast<int>(j);
    chain.links.push_back(link);
    Dof dof;
    dof.min = min;
    dof.max = max;
    dof.joints = {static_cast<int>(j)};
    model->dofs.push_back(dof);
  }
  model->chains.push_back(chain);
  return model;
}

// The end frame of a planar two-link arm: rotation about z by q1 + q2, origin at the tip.
Transform planarEnd(double l1, double l2, double q1, double q2) {
  Transform t = Transform::Identity();
  t.rotate(Eigen::AngleAxisd(q1 + q2, Vector3::UnitZ()));
  t.translation() = Vector3(l1 * std::cos(q1) + l2 * std::cos(q1 + q2),
                            l1 * std::sin(q1) + l2 * std::sin(q1 + q2), 0.0);
  return t;
}

// Closed-form IK of the planar two-link arm (elbow sign chosen by `elbow_up`).
std::pair<double, double> planarIk(double l1, double l2, double x, double y, bool elbow_up) {
  const double c2 = (x * x + y * y - l1 * l1 - l2 * l2) / (2 * l1 * l2);
  const double q2 = (elbow_up ? 1 : -1) * std::acos(c2);
  const double q1 = std::atan2(y, x) - std::atan2(l2 * std::sin(q2), l1 + l2 * std::cos(q2));
  return {q1, q2};
}

::testing::AssertionResult reaches(const Transform& actual, const Transform& target) {
  const double dp = (actual.translation() - target.translation()).norm();
  const double dr = Eigen::AngleAxisd(actual.linear().transpose() * target.linear()).angle();
  if (dp <= kPositionTolerance && dr <= kOrientationTolerance) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure()
         << "position error " << dp << " mm, orientation error " << dr << " rad";
}

bool allFinite(const std::vector<double>& values) {
  for (double v : values)
    if (!std::isfinite(v)) return false;
  return true;
}

TEST(IterativeIk, PlanarArmMatchesTheClosedForm) {
  const double l1 = 120, l2 = 80;
  Robot robot(planarArm({l1, l2}));
  robot.setPose(Transform(Eigen::Translation3d(10, 20, 30)));  // targets are in world frame
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> angle(0.3, 2.5);  // elbow up, away from q2 = 0
  std::uniform_real_distribution<double> perturbation(-0.09, 0.09);
  for (int sample = 0; sample < 50; ++sample) {
    const double q1 = angle(rng) - 1.4, q2 = angle(rng);
    Transform target = planarEnd(l1, l2, q1, q2);
    const auto [e1, e2] =
        planarIk(l1, l2, target.translation().x(), target.translation().y(), true);
    target = robot.pose() * target;
    robot.setDofValues(std::vector<double>{q1 + perturbation(rng), q2 + perturbation(rng)});
    const IkResult ik = iterativeInverseKinematics(robot, target);
    SCOPED_TRACE(::testing::Message() << "sample " << sample);
    ASSERT_TRUE(ik.success) << ik.failure;
    EXPECT_LT(ik.iterations, 20);
    EXPECT_NEAR(ik.dofValues[0], e1, kDofTolerance);
    EXPECT_NEAR(ik.dofValues[1], e2, kDofTolerance);
  }
}

TEST(IterativeIk, GenericTypeDispatchesToTheIterativeSolver) {
  Robot robot(planarArm({100, 100}));  // a model built in code has no RobotType
  const Transform target = planarEnd(100, 100, 0.2, 0.9);
  robot.setDofValues(std::vector<double>{0.25, 0.85});
  const IkResult ik = inverseKinematics(robot, target);
  ASSERT_TRUE(ik.success) << ik.failure;
  EXPECT_GT(ik.iterations, 0);
  EXPECT_NEAR(ik.dofValues[0], 0.2, kDofTolerance);
  EXPECT_NEAR(ik.dofValues[1], 0.9, kDofTolerance);
}

TEST(IterativeIk, RejectsAJumpOfMoreThanTwoTenthsOfARadian) {
  // q* is the only solution nearby, 0.3 rad from the start: the solver reaches it and GraspIt!'s
  // rule rejects it.
  Robot robot(planarArm({100, 100}));
  const Transform target = planarEnd(100, 100, 0.2, 0.9);
  robot.setDofValues(std::vector<double>{0.5, 0.9});
  const IkResult ik = iterativeInverseKinematics(robot, target);
  EXPECT_FALSE(ik.success);
  EXPECT_TRUE(ik.dofValues.empty());
  EXPECT_NE(ik.failure.find("DOF 0 would move"), std::string::npos) << ik.failure;
  EXPECT_NE(ik.failure.find("0.2 rad"), std::string::npos) << ik.failure;

  robot.setDofValues(std::vector<double>{0.39, 0.9});  // 0.19 rad: accepted
  EXPECT_TRUE(iterativeInverseKinematics(robot, target).success);
}

TEST(IterativeIk, RejectsASolutionOutsideTheJointLimits) {
  Robot robot(planarArm({100, 100}, -0.5, 1.0));
  robot.setDofValues(std::vector<double>{-0.55, 0.5}, LimitPolicy::Ignore);
  const Transform target = robot.chainEndPose(0);
  robot.setDofValues(std::vector<double>{-0.45, 0.5});
  const IkResult ik = iterativeInverseKinematics(robot, target);
  EXPECT_FALSE(ik.success);
  EXPECT_NE(ik.failure.find("out of range: joint 0 of chain 0"), std::string::npos) << ik.failure;
}

TEST(IterativeIk, UnreachableTargetFailsWithoutNaN) {
  Robot robot(planarArm({100, 100}));
  robot.setDofValues(std::vector<double>{0.2, 0.3});
  for (const Vector3& where : {Vector3(3000, 0, 0), Vector3(0, 0, 500), Vector3(1, 1, 0)}) {
    Transform target = Transform::Identity();
    target.translation() = where;
    IkResult ik;
    ASSERT_NO_THROW(ik = iterativeInverseKinematics(robot, target));
    EXPECT_FALSE(ik.success) << where.transpose();
    EXPECT_FALSE(ik.failure.empty());
    EXPECT_TRUE(allFinite(ik.dofValues));
  }
}

TEST(IterativeIk, ReportsNoConvergenceAfterTheCap) {
  Robot robot(planarArm({100, 100}));
  robot.setDofValues(std::vector<double>{0.2, 0.3});
  IkRequest request;
  request.maxIterations = 1;  // one Newton step cannot land within 1e-4 rad from 0.1 rad away
  const IkResult ik = iterativeInverseKinematics(robot, planarEnd(100, 100, 0.3, 0.35), request);
  EXPECT_FALSE(ik.success);
  EXPECT_EQ(ik.iterations, 1);
  EXPECT_NE(ik.failure.find("no convergence after 1 iterations"), std::string::npos) << ik.failure;
}

TEST(IterativeIk, BadChainIndexThrows) {
  Robot robot(planarArm({100, 100}));
  EXPECT_THROW(iterativeInverseKinematics(robot, Transform::Identity(), IkRequest{.chain = 1}),
               Error);
  EXPECT_THROW(inverseKinematics(robot, Transform::Identity(), IkRequest{.chain = -1}), Error);
}

// ---------------------------------------------------------------------------------------------
// GraspIt!'s hands.

struct FingerCase {
  const char* file;
  int chain;
};

// Random q* (every DOF of the chain inside its range by 0.1 rad), target = FK(q*), start within
// 0.1 rad of q*: the solver must return q* and reach the target, in few steps; other DOFs stay.
void checkFinger(const FingerCase& finger, unsigned seed) {
  const auto model = loadRobotFile(*test::graspitDataDir() / finger.file);
  Robot robot(model);
  robot.setPose(Transform(Eigen::Translation3d(-40, 15, 300) *
                          Eigen::AngleAxisd(0.4, Vector3(0, 1, 1).normalized())));
  std::vector<bool> drives(model->dofs.size(), false);
  for (const Joint& joint : model->chains[finger.chain].joints) drives[joint.dof] = true;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> perturbation(-0.099, 0.099);
  int max_iterations = 0;
  for (int sample = 0; sample < 50; ++sample) {
    std::vector<double> truth(model->dofs.size()), start(model->dofs.size());
    for (std::size_t d = 0; d < truth.size(); ++d) {
      const Dof& dof = model->dofs[d];
      truth[d] = std::uniform_real_distribution<double>(dof.min + 0.1, dof.max - 0.1)(rng);
      start[d] = drives[d] ? truth[d] + perturbation(rng) : truth[d] - 0.05;
    }
    robot.setDofValues(truth);
    const Transform target = robot.chainEndPose(finger.chain);
    robot.setDofValues(start);
    const IkResult ik = iterativeInverseKinematics(robot, target, IkRequest{.chain = finger.chain});
    SCOPED_TRACE(::testing::Message()
                 << finger.file << " chain " << finger.chain << " sample " << sample);
    ASSERT_TRUE(ik.success) << ik.failure;
    EXPECT_LT(ik.iterations,
              20);  // Newton from 0.1 rad away: 3 to 5 steps measured; the cap is 200
    max_iterations = std::max(max_iterations, ik.iterations);
    for (std::size_t d = 0; d < truth.size(); ++d)
      EXPECT_NEAR(ik.dofValues[d], drives[d] ? truth[d] : start[d], kDofTolerance) << "DOF " << d;
    robot.setDofValues(ik.dofValues);
    EXPECT_TRUE(reaches(robot.chainEndPose(finger.chain), target));
  }
  ::testing::Test::RecordProperty(
      std::string(finger.file) + "_chain" + std::to_string(finger.chain) + "_max_iterations",
      max_iterations);
}

TEST(IterativeIk, BarrettFingersConverge) {
  GRASPKIT_REQUIRE_SHARED();
  for (int chain = 0; chain < 3; ++chain)
    checkFinger({"models/robots/Barrett/Barrett.xml", chain}, 100 + chain);
}

TEST(IterativeIk, RobonautFingersConverge) {
  GRASPKIT_REQUIRE_SHARED();
  for (int chain = 0; chain < 5; ++chain)
    checkFinger({"models/robots/Robonaut/Robonaut.xml", chain}, 200 + chain);
}

TEST(IterativeIk, BarrettFingerRejectsATargetNeedingMoreThanTwoTenths) {
  GRASPKIT_REQUIRE_SHARED();
  Robot robot(loadRobotFile(*test::graspitDataDir() / "models/robots/Barrett/Barrett.xml"));
  const std::vector<double> truth{0.8, 1.0, 0.5, 0.5};
  robot.setDofValues(truth);
  const Transform target = robot.chainEndPose(0);
  robot.setDofValues(std::vector<double>{0.8, 1.3, 0.5, 0.5});  // flexion 0.3 rad away
  const IkResult ik = iterativeInverseKinematics(robot, target);
  EXPECT_FALSE(ik.success);
  EXPECT_NE(ik.failure.find("DOF 1 would move"), std::string::npos) << ik.failure;
}

}  // namespace
}  // namespace graspkit
