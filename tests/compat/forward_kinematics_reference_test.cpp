// Forward kinematics against GraspIt!'s own link poses: Barrett at two DOF vectors, Puma560,
// HumanHand20DOF. Positions within 1e-6 mm, quaternion components within 1e-9.

#include <gtest/gtest.h>

#include "graspkit/io/graspit/robot_file.hpp"
#include "graspkit/model/robot.hpp"
#include "reference.hpp"

namespace graspkit {
namespace {

using nlohmann::json;

constexpr double kPositionTolerance = 1e-6;    // mm
constexpr double kQuaternionTolerance = 1e-9;  // per component

void expectPose(const Transform& actual, const json& expected, const std::string& what) {
  const Transform truth = test::jsonPose(expected);
  const Vector3 dt = actual.translation() - truth.translation();
  EXPECT_LT(dt.cwiseAbs().maxCoeff(), kPositionTolerance)
      << what << ": position " << actual.translation().transpose() << " vs "
      << truth.translation().transpose();
  // q and -q are the same rotation; compare against the file's sign.
  Eigen::Vector4d a = Quaternion(actual.linear()).coeffs();
  const auto& q = expected.at("q_wxyz");
  const Eigen::Vector4d b(q[1].get<double>(), q[2].get<double>(), q[3].get<double>(),
                          q[0].get<double>());
  if (a.dot(b) < 0) a = -a;
  EXPECT_LT((a - b).cwiseAbs().maxCoeff(), kQuaternionTolerance)
      << what << ": quaternion (xyzw) " << a.transpose() << " vs " << b.transpose();
}

void checkConfig(const std::string& file, const std::string& config_name, const json& config) {
  SCOPED_TRACE(file + " " + config_name);
  Robot robot(loadRobotFile(*test::graspitDataDir() / file));
  const json& state = config.at("state");
  if (config.contains("requested_dof_values")) {
    robot.setDofValues(config.at("requested_dof_values").get<std::vector<double>>());
  }
  ASSERT_EQ(robot.dofCount(), state.at("num_dof").get<int>());
  ASSERT_EQ(robot.model().chains.size(), state.at("num_chains").get<std::size_t>());
  ASSERT_EQ(robot.model().jointCount(), state.at("num_joints").get<int>());

  const auto dof_values = state.at("dof_values").get<std::vector<double>>();
  for (int d = 0; d < robot.dofCount(); ++d) {
    EXPECT_NEAR(robot.dofValues()[d], dof_values[d], 1e-9) << "DOF " << d;
    const json& dof = state.at("dofs").at(d);
    EXPECT_NEAR(robot.model().dofs[d].min, dof.at("min").get<double>(), 1e-9) << "DOF " << d;
    EXPECT_NEAR(robot.model().dofs[d].max, dof.at("max").get<double>(), 1e-9) << "DOF " << d;
    EXPECT_NEAR(robot.model().dofs[d].defaultVelocity, dof.at("default_velocity").get<double>(),
                1e-12);
  }
  expectPose(robot.pose(), state.at("base").at("tran"), "base");
  const json& chains = state.at("chains");
  for (std::size_t c = 0; c < chains.size(); ++c) {
    const auto& chain = robot.model().chains[c];
    const json& links = chains[c].at("links");
    ASSERT_EQ(chain.links.size(), links.size()) << "chain " << c;
    const json& joints = chains[c].at("joints");
    for (std::size_t j = 0; j < joints.size(); ++j) {
      EXPECT_NEAR(robot.jointValues()[chain.firstJoint + j], joints[j].at("value").get<double>(),
                  1e-9)
          << "chain " << c << " joint " << j;
      EXPECT_NEAR(chain.joints[j].min, joints[j].at("min").get<double>(), 1e-9);
      EXPECT_NEAR(chain.joints[j].max, joints[j].at("max").get<double>(), 1e-9);
    }
    for (std::size_t l = 0; l < links.size(); ++l) {
      EXPECT_EQ(chain.links[l].name, links[l].at("name").get<std::string>());
      expectPose(robot.linkPose(c, l), links[l].at("tran"), chain.links[l].name);
    }
  }
}

TEST(ForwardKinematicsReference, MatchesGraspItLinkPoses) {
  GRASPKIT_REQUIRE_SHARED();
  const json& robots = test::referenceJson().at("forward_kinematics");
  ASSERT_GE(robots.size(), 3u);
  int configs = 0;
  for (const auto& [file, entry] : robots.items()) {
    for (const auto& [name, config] : entry.at("configs").items()) {
      checkConfig(file, name, config);
      ++configs;
    }
  }
  EXPECT_GE(configs, 5);
}

}  // namespace
}  // namespace graspkit
