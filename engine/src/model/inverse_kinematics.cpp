// Inverse kinematics dispatch, and the generic iterative solver GraspIt! uses for every robot
// without a closed form (Robot::invKinematics in its robot.cpp).
//
// The solver, in GraspIt!'s terms:
// - End frame: the world pose of the chain's last link (robot pose * chain base * the DH
//   transforms up to that link's last joint), i.e. Robot::chainEndPose.
// - Error: e = [p_target - p_end; 1/2 sum_i a_i(end) x a_i(target)], where a_i are the frame
//   axes (the columns of our rotation matrices; GraspIt! writes the same vectors as the rows of
//   its row-vector matrices). Millimetres and radians are mixed, as in GraspIt!.
// - Step: dq = J+ e, with J the 6 x n geometric Jacobian of the end frame in world coordinates,
//   taken in DOF space (column of DOF d = sum over its joints in the chain of ratio * joint
//   column) over the n DOFs that drive the chain's joints; the least-squares solve is a
//   rank-revealing QR (complete orthogonal decomposition, so it is also minimum-norm when the
//   chain has more DOFs than 6 or sits at a singularity). Other DOFs never move.
// - After each step a revolute DOF is wrapped mod 2 pi toward zero, into (-2 pi, 2 pi).
// - Convergence: max |dq| < 1e-4; at most request.maxIterations steps.
// - Rejection, as GraspIt!: a DOF that ends more than 0.2 rad from its starting value (the
//   solver jumped to another branch), or a joint driven by a moved DOF outside its limits.
// Where graspkit differs, deliberately:
// - GraspIt! builds its Jacobian once, at the robot's current pose, and reuses it for every
//   step (its links are not moved while it iterates); graspkit recomputes it at each iterate
//   (plain Gauss-Newton). Both stop at the same fixed points; Newton converges faster and from
//   further away.
// - GraspIt!'s convergence test reads only the first DOF's step (a loop over the columns of a
//   column vector); graspkit tests every DOF, as the intent reads.
// - GraspIt! wraps every DOF, prismatic ones too; graspkit wraps DOFs whose joints are all
//   revolute.
// - GraspIt! reports success at any fixed point, including the least-squares nearest pose of an
//   unreachable target; graspkit also requires the final pose error to be within
//   request.positionTolerance / orientationTolerance.

#include "graspkit/model/inverse_kinematics.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <fmt/format.h>
#include <Eigen/QR>

#include "graspkit/base/error.hpp"
#include "graspkit/model/robot.hpp"

namespace graspkit {

namespace {

using Vector6 = Eigen::Matrix<double, 6, 1>;
using Jacobian = Eigen::Matrix<double, 6, Eigen::Dynamic>;

constexpr double kStepTolerance = 1e-4;  // GraspIt!'s epsilon on max |dq|
constexpr double kMaxMotion = 0.2;       // GraspIt!'s upperBound on |q_final - q_start|
constexpr double kLimitSlack = 1e-9;     // round-off allowed at a joint limit

// The DOFs that drive at least one joint of the chain (through a non-zero ratio), ascending.
std::vector<int> drivingDofs(const RobotModel& model, const KinematicChain& chain) {
  std::vector<bool> drives(model.dofs.size(), false);
  for (const Joint& joint : chain.joints)
    if (joint.ratio != 0.0) drives[joint.dof] = true;
  std::vector<int> dofs;
  for (std::size_t d = 0; d < drives.size(); ++d)
    if (drives[d]) dofs.push_back(static_cast<int>(d));
  return dofs;
}

// Joint values of the chain for given DOF values (joint = ratio * DOF; breakaway ignored, as
// GraspIt!'s solver moves the DOFs as if every joint followed its DOF).
std::vector<double> chainJointValues(const KinematicChain& chain, const std::vector<double>& dofs) {
  std::vector<double> values(chain.joints.size());
  for (std::size_t j = 0; j < chain.joints.size(); ++j)
    values[j] = chain.joints[j].ratio * dofs[chain.joints[j].dof];
  return values;
}

// The pose error [dp; dw] that moves `current` onto `target` to first order.
Vector6 poseError(const Transform& current, const Transform& target) {
  Vector3 rotation_error = Vector3::Zero();
  for (int i = 0; i < 3; ++i)
    rotation_error += current.linear().col(i).cross(target.linear().col(i));
  Vector6 error;
  error << target.translation() - current.translation(), 0.5 * rotation_error;
  return error;
}

struct EndState {
  Transform pose;
  Jacobian jacobian;  // 6 x driving DOFs
};

// The end frame of the chain and its world-frame DOF-space Jacobian at DOF values `dofs`.
EndState endState(const Robot& robot, const KinematicChain& chain, const std::vector<int>& driving,
                  const std::vector<double>& dofs) {
  const Transform chain_base = robot.pose() * chain.base;
  const std::vector<double> joint_values = chainJointValues(chain, dofs);
  const std::vector<Transform> frames = jointFrames(chain, chain_base, joint_values);
  const int last_joint = chain.links.back().lastJoint;  // joints after it do not move the end
  EndState state{(last_joint < 0 ? chain_base : frames[last_joint]) * chain.links.back().frame,
                 Jacobian::Zero(6, static_cast<Eigen::Index>(driving.size()))};
  for (int j = 0; j <= last_joint; ++j) {
    const Joint& joint = chain.joints[j];
    // A DH joint moves about / along the z axis of the frame before it.
    const Transform& before = j == 0 ? chain_base : frames[j - 1];
    const Vector3 axis = before.linear().col(2);
    Vector6 column;
    if (joint.type == JointType::Revolute)
      column << axis.cross(state.pose.translation() - before.translation()), axis;
    else
      column << axis, Vector3::Zero();
    for (std::size_t k = 0; k < driving.size(); ++k)
      if (driving[k] == joint.dof)
        state.jacobian.col(static_cast<Eigen::Index>(k)) += joint.ratio * column;
  }
  return state;
}

bool allRevolute(const RobotModel& model, const Dof& dof) {
  for (int j : dof.joints)
    if (model.joint(j).type != JointType::Revolute) return false;
  return true;
}

// GraspIt!'s wrap: subtract whole turns, truncating toward zero.
double wrapTurns(double value) {
  return value - std::trunc(value / (2.0 * M_PI)) * 2.0 * M_PI;
}

// Empty when every DOF stayed within kMaxMotion of its start, else why not.
std::string motionFailure(const std::vector<int>& driving, const std::vector<double>& start,
                          const std::vector<double>& q) {
  for (int d : driving)
    if (std::abs(q[d] - start[d]) > kMaxMotion)
      return fmt::format(
          "DOF {} would move {:.6g} rad (from {:.6g} to {:.6g}), more than GraspIt!'s 0.2 rad "
          "limit: the solution is on another branch",
          d, std::abs(q[d] - start[d]), start[d], q[d]);
  return {};
}

// Empty when every joint driven by a moved DOF is within its limits, else why not.
std::string rangeFailure(const RobotModel& model, const std::vector<int>& driving,
                         const std::vector<double>& q) {
  for (std::size_t c = 0; c < model.chains.size(); ++c) {
    const KinematicChain& chain = model.chains[c];
    for (std::size_t j = 0; j < chain.joints.size(); ++j) {
      const Joint& joint = chain.joints[j];
      if (std::find(driving.begin(), driving.end(), joint.dof) == driving.end()) continue;
      const double value = joint.ratio * q[joint.dof];
      if (value < joint.min - kLimitSlack || value > joint.max + kLimitSlack)
        return fmt::format(
            "out of range: joint {} of chain {} would be at {:.6g}, outside [{:.6g}, {:.6g}]", j, c,
            value, joint.min, joint.max);
    }
  }
  return {};
}

}  // namespace

IkResult iterativeInverseKinematics(const Robot& robot, const Transform& target,
                                    const IkRequest& request) {
  const RobotModel& model = robot.model();
  if (request.chain < 0 || request.chain >= static_cast<int>(model.chains.size()))
    throw Error(fmt::format("robot '{}': inverse kinematics of chain {}, robot has {} chains",
                            robot.name(), request.chain, model.chains.size()));
  const KinematicChain& chain = model.chains[request.chain];
  const std::vector<int> driving = drivingDofs(model, chain);
  const std::vector<double> start(robot.dofValues().begin(), robot.dofValues().end());
  std::vector<double> q = start;

  IkResult result;
  bool converged = false;
  while (!converged && result.iterations < request.maxIterations) {
    const EndState state = endState(robot, chain, driving, q);
    const Eigen::VectorXd step =
        Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd>(state.jacobian)
            .solve(poseError(state.pose, target));
    ++result.iterations;
    for (std::size_t k = 0; k < driving.size(); ++k) {
      const int d = driving[k];
      q[d] += step[static_cast<Eigen::Index>(k)];
      if (allRevolute(model, model.dofs[d])) q[d] = wrapTurns(q[d]);
    }
    converged = step.size() == 0 || step.cwiseAbs().maxCoeff() < kStepTolerance;
    if (!step.allFinite()) break;
  }
  if (!converged) {
    result.failure = fmt::format("no convergence after {} iterations (max |dq| stayed >= {})",
                                 result.iterations, kStepTolerance);
    return result;
  }
  result.failure = motionFailure(driving, start, q);
  if (result.failure.empty()) result.failure = rangeFailure(model, driving, q);
  if (result.failure.empty()) {
    const Vector6 error = poseError(endState(robot, chain, driving, q).pose, target);
    const double position_error = error.head<3>().norm();
    const double orientation_error = error.tail<3>().norm();
    if (position_error > request.positionTolerance ||
        orientation_error > request.orientationTolerance)
      result.failure = fmt::format(
          "converged {:.6g} mm and {:.6g} rad away from the target (tolerances {} mm, {} rad): "
          "the target is out of the chain's reach",
          position_error, orientation_error, request.positionTolerance,
          request.orientationTolerance);
  }
  if (!result.failure.empty()) return result;
  result.success = true;
  result.dofValues = std::move(q);
  return result;
}

}  // namespace graspkit
