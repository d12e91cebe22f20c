// The Puma560 plugin's closed-form inverse kinematics on GraspIt!'s Puma560.xml. The truth is
// forward kinematics (checked against GraspIt!'s own link poses in
// forward_kinematics_reference_test) and kinematic identities of the arm: a target made by FK
// from q* must be reached exactly, and from q* itself the selection rule must return q*; the
// wrist flip (theta4 + pi, -theta5, theta6 + pi) is the same pose. Unreachable targets fail
// with a message, never NaN or a throw. The iterative solver, started near q*, must agree.

#include <cmath>
#include <fstream>
#include <random>
#include <set>
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

namespace fs = std::filesystem;

constexpr double kPositionTolerance = 1e-6;  // mm
constexpr double kRotationTolerance = 1e-9;  // rad, rotation-matrix entries

std::shared_ptr<const RobotModel> puma() {
  return loadRobotFile(*test::graspitDataDir() / "models/robots/Puma560/Puma560.xml");
}

// A base pose away from the identity, so the world -> base conversion is exercised.
Transform mountPose() {
  Transform t = Transform::Identity();
  t.rotate(Eigen::AngleAxisd(0.7, Vector3(1, 2, 3).normalized()));
  t.translation() = Vector3(250, -120, 80);
  return t;
}

std::vector<double> randomDofs(const RobotModel& model, std::mt19937& rng, double margin = 1e-3) {
  std::vector<double> q;
  for (const Dof& dof : model.dofs)
    q.push_back(std::uniform_real_distribution<double>(dof.min + margin, dof.max - margin)(rng));
  return q;
}

Transform endPose(Robot& robot, const std::vector<double>& q) {
  robot.setDofValues(q, LimitPolicy::Ignore);
  return robot.chainEndPose(0);
}

::testing::AssertionResult poseNear(const Transform& actual, const Transform& expected) {
  const double dp = (actual.translation() - expected.translation()).norm();
  const double dr = (actual.linear() - expected.linear()).cwiseAbs().maxCoeff();
  if (dp <= kPositionTolerance && dr <= kRotationTolerance) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "position error " << dp << " mm, rotation error " << dr;
}

// Difference of two angles modulo whole turns, in [-pi, pi].
double angleDifference(double a, double b) {
  return std::remainder(a - b, 2.0 * M_PI);
}

bool allFinite(const std::vector<double>& values) {
  for (double v : values)
    if (!std::isfinite(v)) return false;
  return true;
}

class Puma560Ik : public ::testing::Test {
 protected:
  void SetUp() override {
    GRASPKIT_REQUIRE_SHARED();
    model_ = puma();
  }
  std::shared_ptr<const RobotModel> model_;
};

TEST_F(Puma560Ik, RoundTripsTwoHundredRandomPosesFromAnotherConfiguration) {
  std::mt19937 rng(560);
  Robot robot(model_);
  robot.setPose(mountPose());
  for (int sample = 0; sample < 200; ++sample) {
    const std::vector<double> truth = randomDofs(*model_, rng);
    const Transform target = endPose(robot, truth);
    robot.setDofValues(randomDofs(*model_, rng));
    const IkResult ik = inverseKinematics(robot, target);
    SCOPED_TRACE(::testing::Message() << "sample " << sample);
    ASSERT_TRUE(ik.success) << ik.failure;
    EXPECT_EQ(ik.iterations, 0);
    ASSERT_EQ(ik.dofValues.size(), 6u);
    for (int d = 0; d < 6; ++d) {
      EXPECT_GE(ik.dofValues[d], model_->dofs[d].min);
      EXPECT_LE(ik.dofValues[d], model_->dofs[d].max);
    }
    EXPECT_TRUE(poseNear(endPose(robot, ik.dofValues), target));
  }
}

TEST_F(Puma560Ik, StartedAtTheSolutionReturnsIt) {
  std::mt19937 rng(561);
  Robot robot(model_);
  robot.setPose(mountPose());
  int ties = 0;
  for (int sample = 0; sample < 200; ++sample) {
    const std::vector<double> truth = randomDofs(*model_, rng);
    const Transform target = endPose(robot, truth);
    const IkResult ik = inverseKinematics(robot, target);  // the robot stands at `truth`
    SCOPED_TRACE(::testing::Message() << "sample " << sample);
    ASSERT_TRUE(ik.success) << ik.failure;
    // Joint 6's range (+-215 deg) is wider than a turn: GraspIt! shifts an angle only when it is
    // out of range, so q6 and q6 -+ 2 pi are both answers. Every other range is narrower.
    double largest = 0.0;
    for (int d = 0; d < 6; ++d)
      largest = std::max(largest, std::abs(angleDifference(ik.dofValues[d], truth[d])));
    if (largest > 1e-9) {
      // The selection rule passes ties within 0.05 rad on to the next joint, so another
      // candidate can win only if it is within 0.05 rad of q* on every joint (near the edge of
      // the workspace, where the two elbows meet). It must still reach the target.
      EXPECT_LT(largest, 0.05);
      EXPECT_TRUE(poseNear(endPose(robot, ik.dofValues), target));
      ++ties;
      robot.setDofValues(truth);
      continue;
    }
    for (int d = 0; d < 5; ++d) EXPECT_NEAR(ik.dofValues[d], truth[d], 1e-9) << "DOF " << d;
  }
  EXPECT_LE(ties, 10) << "ties should be rare";
}

TEST_F(Puma560Ik, WristFlipIsReturnedWhenTheRobotStandsOnIt) {
  Robot robot(model_);
  const std::vector<double> truth{0.3, 0.5, -0.8, 1.2, 0.6, -0.2};
  const Transform target = endPose(robot, truth);
  // (theta4 + pi, -theta5, theta6 + pi) is the same pose; theta4 + pi is beyond 110 deg, so the
  // reachable flip has theta4 - pi (-111 deg, inside [-135, 110]).
  const std::vector<double> flip{0.3, 0.5, -0.8, 1.2 - M_PI, -0.6, -0.2 + M_PI};
  ASSERT_TRUE(poseNear(endPose(robot, flip), target)) << "the flip identity itself";
  const IkResult ik = inverseKinematics(robot, target);  // robot stands at the flip
  ASSERT_TRUE(ik.success) << ik.failure;
  for (int d = 0; d < 6; ++d) EXPECT_NEAR(ik.dofValues[d], flip[d], 1e-9) << "DOF " << d;
}

TEST_F(Puma560Ik, DistinctBranchesAllReachTheTarget) {
  // A generic pose whose shoulder, elbow and wrist-flip branches are mostly within the ranges.
  // Starting from a grid of configurations selects different candidates; each must reach the
  // target, and together they must cover both shoulders and both wrist flips.
  Robot robot(model_);
  const std::vector<double> truth{-0.6, 1.0, -1.2, 0.7, 0.9, 0.2};
  const Transform target = endPose(robot, truth);
  std::vector<std::vector<double>> distinct;
  for (double q1 = -2.7; q1 < 2.8; q1 += 0.6)
    for (double q2 = -0.6; q2 < 3.7; q2 += 0.6)
      for (double q3 = -4.0; q3 < 0.9; q3 += 0.8)
        for (double q4 : {-2.2, 0.0, 1.8}) {
          robot.setDofValues(std::vector<double>{q1, q2, q3, q4, 0.0, 0.0});
          const IkResult ik = inverseKinematics(robot, target);
          ASSERT_TRUE(ik.success) << ik.failure;
          ASSERT_TRUE(poseNear(endPose(robot, ik.dofValues), target));
          bool seen = false;
          for (const std::vector<double>& other : distinct) {
            double gap = 0;
            for (int d = 0; d < 6; ++d) gap = std::max(gap, std::abs(ik.dofValues[d] - other[d]));
            seen = seen || gap < 1e-6;
          }
          if (!seen) distinct.push_back(ik.dofValues);
        }
  EXPECT_GE(distinct.size(), 6u) << "shoulder x elbow x wrist should give several solutions";
  std::set<long> shoulders;
  bool positive_wrist = false, negative_wrist = false;
  for (const std::vector<double>& q : distinct) {
    shoulders.insert(std::lround(q[0] * 100));
    positive_wrist = positive_wrist || q[4] > 0.1;
    negative_wrist = negative_wrist || q[4] < -0.1;
  }
  EXPECT_EQ(shoulders.size(), 2u);
  EXPECT_TRUE(positive_wrist && negative_wrist);
}

TEST_F(Puma560Ik, WristSingularityKeepsTheCurrentTheta4) {
  Robot robot(model_);
  const std::vector<double> truth{-0.4, 0.9, -1.2, 0.5, 0.0, 0.3};
  const Transform target = endPose(robot, truth);
  robot.setDofValues(std::vector<double>{-0.4, 0.9, -1.2, -0.25, 0.1, 0.0});
  const IkResult ik = inverseKinematics(robot, target);
  ASSERT_TRUE(ik.success) << ik.failure;
  ASSERT_TRUE(allFinite(ik.dofValues));
  EXPECT_TRUE(poseNear(endPose(robot, ik.dofValues), target));
  // Only theta4 + theta6 is determined at theta5 = 0.
  EXPECT_NEAR(ik.dofValues[4], 0.0, 1e-9);
  EXPECT_NEAR(ik.dofValues[3], -0.25, 1e-9);
  EXPECT_NEAR(ik.dofValues[3] + ik.dofValues[5], 0.8, 1e-9);
}

TEST_F(Puma560Ik, UnreachableTargetsFailWithAMessage) {
  Robot robot(model_);
  robot.setPose(mountPose());
  std::vector<Transform> targets;
  Transform far = mountPose();
  far.translation() += Vector3(2000, 0, 0);  // 2 m away: beyond a2 + d4 = 864 mm
  targets.push_back(far);
  Transform on_axis = mountPose();  // wrist centre on joint 1's axis: closer than d3 to it
  targets.push_back(on_axis);
  for (const Transform& target : targets) {
    IkResult ik;
    ASSERT_NO_THROW(ik = inverseKinematics(robot, target));
    EXPECT_FALSE(ik.success);
    EXPECT_TRUE(ik.dofValues.empty());
    EXPECT_NE(ik.failure.find("no valid solution"), std::string::npos) << ik.failure;
    EXPECT_NE(ik.failure.find("out of reach"), std::string::npos) << ik.failure;
  }
}

TEST_F(Puma560Ik, OrientationOutsideTheWristRangeFails) {
  // theta5 = 170 deg: reachable position, but theta5 is limited to +-100 deg on both flips.
  Robot robot(model_);
  const Transform target = endPose(robot, {0.3, 0.5, -0.8, 0.0, 170.0 * M_PI / 180.0, 0.0});
  robot.setDofValues(std::vector<double>(6, 0.0));
  const IkResult ik = inverseKinematics(robot, target);
  EXPECT_FALSE(ik.success);
  EXPECT_NE(ik.failure.find("joint"), std::string::npos) << ik.failure;
  EXPECT_NE(ik.failure.find("out of range"), std::string::npos) << ik.failure;
}

TEST_F(Puma560Ik, BadChainIndexThrows) {
  Robot robot(model_);
  EXPECT_THROW(inverseKinematics(robot, Transform::Identity(), IkRequest{.chain = 1}), Error);
  EXPECT_THROW(inverseKinematics(robot, Transform::Identity(), IkRequest{.chain = -1}), Error);
}

TEST_F(Puma560Ik, IterativeSolverAgreesWithTheClosedFormNearby) {
  std::mt19937 rng(562);
  std::normal_distribution<double> jitter(0.0, 0.03);
  Robot robot(model_);
  robot.setPose(mountPose());
  int agreed = 0;
  for (int sample = 0; sample < 50; ++sample) {
    const std::vector<double> truth = randomDofs(*model_, rng, 0.2);
    if (std::abs(truth[4]) < 0.1) continue;  // the wrist singularity has a family of answers
    const Transform target = endPose(robot, truth);
    std::vector<double> start = truth;
    for (double& q : start) q += jitter(rng);
    robot.setDofValues(start);
    const IkResult closed = inverseKinematics(robot, target);
    const IkResult iterative = iterativeInverseKinematics(robot, target);
    SCOPED_TRACE(::testing::Message() << "sample " << sample);
    ASSERT_TRUE(closed.success) << closed.failure;
    ASSERT_TRUE(iterative.success) << iterative.failure;
    EXPECT_LT(iterative.iterations, 20);
    for (int d = 0; d < 6; ++d)
      EXPECT_NEAR(angleDifference(iterative.dofValues[d], closed.dofValues[d]), 0.0, 1e-6);
    ++agreed;
  }
  EXPECT_GE(agreed, 40);
}

TEST(Puma560Configure, RefusesAFileWithoutThePumaKinematics) {
  GRASPKIT_REQUIRE_SHARED();
  // A Puma560-typed file with one revolute joint, written beside a copy-free cube link.
  const fs::path dir = test::scratchDir() / "not_a_puma";
  fs::create_directories(dir / "iv");
  std::ofstream(dir / "iv" / "cube.off")
      << "OFF\n8 6 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n"
         "4 0 3 2 1\n4 4 5 6 7\n4 0 1 5 4\n4 2 3 7 6\n4 1 2 6 5\n4 0 4 7 3\n";
  std::ofstream(dir / "iv" / "link.xml")
      << "<root><material>plastic</material><mass>10</mass>"
         "<geometryFile type=\"off\">cube.off</geometryFile></root>\n";
  const fs::path file = dir / "not_a_puma.xml";
  std::ofstream(file)
      << "<?xml version=\"1.0\" ?>\n<robot type=\"Puma560\">\n  <palm>link.xml</palm>\n"
         "  <dof type=\"r\"><defaultVelocity>1</defaultVelocity><maxEffort>1</maxEffort><Kp>1</Kp>"
         "<Kd>1</Kd><draggerScale>1</draggerScale></dof>\n"
         "  <chain><joint type=\"Revolute\"><theta>d0</theta><d>0</d><a>10</a><alpha>0</alpha>"
         "<minValue>-90</minValue><maxValue>90</maxValue></joint>"
         "<link dynamicJointType=\"Revolute\">link.xml</link></chain>\n</robot>\n";
  try {
    loadRobotFile(file);
    FAIL() << "a one-joint Puma560 loaded";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("not_a_puma.xml"), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("6 DOFs"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace graspkit
