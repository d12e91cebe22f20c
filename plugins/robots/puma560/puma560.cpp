// The Unimation Puma 560 arm, whose GraspIt! subclass replaces the generic iterative inverse
// kinematics with the closed form (GraspIt!'s robots/puma560.cpp).
//
// Frames and conventions (standard DH, T_i = Rz(theta_i) Tz(d_i) Tx(a_i) Rx(alpha_i), as in
// GraspIt!'s Puma560.xml):
//   joint  1: alpha  90          joint 4: d 431.8 (d4), alpha  90
//   joint  2: a 431.8 (a2)       joint 5: alpha -90
//   joint  3: d 149 (d3), a 20.3 (a3), alpha -90
//   joint  6: nothing
// Frames 4, 5 and 6 share their origin (the wrist centre), so the target's position fixes
// theta1..theta3 and its rotation theta4..theta6.
// - The target is the world pose of the last link's frame (frame 6). It is brought into the
//   chain's base frame with the robot's pose and the chain's <transform> (GraspIt! applies only
//   the robot's pose; the chain transform of its Puma560.xml is the identity, so both agree).
// - Position (GraspIt!'s formulas): theta1 = atan2(py,px) + asin(d3/r) or + pi - asin(d3/r);
//   with u = px c1 + py s1, cos Psi = (a2^2 - d4^2 - a3^2 + u^2 + pz^2) / (2 a2 sqrt(u^2+pz^2)),
//   theta2 = atan2(pz,u) -+ Psi; theta3 = atan2(a3,d4) - atan2(c2 u + s2 pz - a2, c2 pz - s2 u).
// - Wrist (derived here): R36 = R03^T R = Rz(theta4) Ry(-theta5) Rz(theta6), a ZYZ Euler
//   decomposition with two branches (the wrist flip). At the wrist singularity (theta5 = 0,
//   where only theta4 + theta6 is determined) theta4 keeps the robot's current value.
// - 8 candidates, index bits: 4 = shoulder (+asin), 2 = elbow (+Psi), 1 = wrist flip (theta5 <=
//   0). Each angle is shifted by one turn into its DOF range if outside; if that fails, the
//   candidate is invalid. An unreachable position (asin or acos out of [-1, 1]) is invalid too.
// - Selection, as GraspIt!: by joint from 1 to 6, keep the candidates whose distance from the
//   current value is within 0.05 rad of the nearest one; stop when one is left; the lowest index
//   among the last ones left wins. (GraspIt! compares against a running minimum, which makes
//   its tie set depend on candidate order; graspkit compares against the true minimum.)

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "graspkit/base/error.hpp"
#include "graspkit/model/robot.hpp"
#include "graspkit/plugin/plugin.hpp"
#include "graspkit/plugin/registry.hpp"

namespace {

using graspkit::IkRequest;
using graspkit::IkResult;
using graspkit::Matrix3;
using graspkit::Robot;
using graspkit::RobotModel;
using graspkit::Transform;
using graspkit::Vector3;

constexpr double kA2 = 431.8;
constexpr double kA3 = 20.3;
constexpr double kD3 = 149.0;
constexpr double kD4 = 431.8;
constexpr int kCandidateCount = 8;
constexpr double kTieEpsilon = 0.05;      // GraspIt!'s JOINT_DIST_EPSILON (rad)
constexpr double kRoundOff = 1e-9;        // slack on acos/asin arguments and DOF limits
constexpr double kSingularWrist = 1e-12;  // |sin theta5| below which theta4 is free

using Angles = std::array<double, 6>;

struct Candidate {
  Angles angle{};
  bool valid = true;
  std::string invalid;  // why, when !valid
};

Matrix3 rotZ(double angle) {
  return Eigen::AngleAxisd(angle, Vector3::UnitZ()).toRotationMatrix();
}
Matrix3 rotY(double angle) {
  return Eigen::AngleAxisd(angle, Vector3::UnitY()).toRotationMatrix();
}
Matrix3 rotX(double angle) {
  return Eigen::AngleAxisd(angle, Vector3::UnitX()).toRotationMatrix();
}

// asin / acos argument within round-off of [-1, 1] clamped in, else nullopt (unreachable).
std::optional<double> unitArgument(double x) {
  if (!std::isfinite(x) || std::abs(x) > 1.0 + kRoundOff) return std::nullopt;
  return std::clamp(x, -1.0, 1.0);
}

// theta1..theta3 placing the wrist centre at p, for one shoulder and elbow branch.
std::optional<std::array<double, 3>> armAngles(const Vector3& p, bool shoulder_plus,
                                               bool elbow_plus) {
  const double r = std::hypot(p.x(), p.y());
  const std::optional<double> sin_offset = unitArgument(kD3 / r);
  if (!sin_offset) return std::nullopt;
  const double azimuth = std::atan2(p.y(), p.x());
  const double offset = std::asin(*sin_offset);
  const double theta1 = shoulder_plus ? azimuth + offset : azimuth + M_PI - offset;
  const double u = p.x() * std::cos(theta1) + p.y() * std::sin(theta1);
  const double r1 = std::hypot(u, p.z());
  const std::optional<double> cos_psi =
      unitArgument((kA2 * kA2 - kD4 * kD4 - kA3 * kA3 + u * u + p.z() * p.z()) / (2.0 * kA2 * r1));
  if (!cos_psi) return std::nullopt;
  const double psi = std::acos(*cos_psi);
  const double theta2 = std::atan2(p.z(), u) + (elbow_plus ? psi : -psi);
  const double c2 = std::cos(theta2);
  const double s2 = std::sin(theta2);
  const double theta3 =
      std::atan2(kA3, kD4) - std::atan2(c2 * u + s2 * p.z() - kA2, c2 * p.z() - s2 * u);
  return std::array<double, 3>{theta1, theta2, theta3};
}

// theta4..theta6 with R03^T R = Rz(theta4) Ry(-theta5) Rz(theta6). `flip` takes the branch with
// theta5 <= 0; `current4` is theta4 at the singularity.
std::array<double, 3> wristAngles(const Matrix3& r36, bool flip, double current4) {
  const double axis_x = r36(0, 2);  // third column = Rz(theta4) (sin b, 0, cos b), b = -theta5
  const double axis_y = r36(1, 2);
  double theta4 =
      std::hypot(axis_x, axis_y) < kSingularWrist ? current4 : std::atan2(axis_y, axis_x);
  if (flip) theta4 = std::remainder(theta4 + M_PI, 2.0 * M_PI);
  const double sin_b = std::cos(theta4) * axis_x + std::sin(theta4) * axis_y;
  const double b = std::atan2(sin_b, r36(2, 2));
  const Matrix3 r6 = rotY(b).transpose() * rotZ(theta4).transpose() * r36;  // = Rz(theta6)
  return {theta4, -b, std::atan2(r6(1, 0), r6(0, 0))};
}

Matrix3 baseToFrame3(double theta1, double theta2, double theta3) {
  return rotZ(theta1) * rotX(M_PI / 2) * rotZ(theta2) * rotZ(theta3) * rotX(-M_PI / 2);
}

// Shifts each angle by at most one turn into its DOF range; invalidates the candidate if none.
void shiftIntoRange(Candidate& candidate, const RobotModel& model) {
  for (int i = 0; i < 6 && candidate.valid; ++i) {
    double& angle = candidate.angle[i];
    const graspkit::Dof& dof = model.dofs[i];
    if (angle < dof.min - kRoundOff)
      angle += 2.0 * M_PI;
    else if (angle > dof.max + kRoundOff)
      angle -= 2.0 * M_PI;
    if (angle < dof.min - kRoundOff || angle > dof.max + kRoundOff) {
      candidate.valid = false;
      candidate.invalid = fmt::format("joint {} out of range", i + 1);
    }
    angle = dof.clamp(angle);
  }
}

std::array<Candidate, kCandidateCount> candidates(const RobotModel& model, const Transform& target,
                                                  double current4) {
  std::array<Candidate, kCandidateCount> all;
  for (int i = 0; i < kCandidateCount; ++i) {
    Candidate& candidate = all[i];
    const auto arm = armAngles(target.translation(), i & 4, i & 2);
    if (!arm) {
      candidate.valid = false;
      candidate.invalid = "position out of reach";
      continue;
    }
    const auto [t1, t2, t3] = *arm;
    const Matrix3 r36 = baseToFrame3(t1, t2, t3).transpose() * target.linear();
    const auto [t4, t5, t6] = wristAngles(r36, i & 1, current4);
    candidate.angle = {t1, t2, t3, t4, t5, t6};
    shiftIntoRange(candidate, model);
  }
  return all;
}

// GraspIt!'s lexicographic choice: nearest the current value of joint 1, ties within
// kTieEpsilon passed on to joint 2, and so on; then the lowest index. -1 when none is valid.
int chooseCandidate(const std::array<Candidate, kCandidateCount>& all,
                    std::span<const double> current) {
  std::vector<int> left;
  for (int i = 0; i < kCandidateCount; ++i)
    if (all[i].valid) left.push_back(i);
  if (left.empty()) return -1;
  for (int j = 0; j < 6 && left.size() > 1; ++j) {
    double nearest = INFINITY;
    for (int i : left) nearest = std::min(nearest, std::abs(all[i].angle[j] - current[j]));
    std::erase_if(left, [&](int i) {
      return std::abs(all[i].angle[j] - current[j]) - nearest >= kTieEpsilon;
    });
  }
  return left.front();
}

std::string noSolution(const std::array<Candidate, kCandidateCount>& all, const Transform& target) {
  std::string reasons;
  for (int i = 0; i < kCandidateCount; ++i)
    reasons += fmt::format("{}{}: {}", i ? "; " : "", i, all[i].invalid);
  const Vector3 p = target.translation();
  return fmt::format(
      "no valid solution among the 8 candidates for the wrist centre at ({:.6g}, "
      "{:.6g}, {:.6g}) mm in the base frame ({})",
      p.x(), p.y(), p.z(), reasons);
}

class Puma560 final : public graspkit::RobotType {
 public:
  // The closed form hard-codes the arm's geometry, so a file that differs is refused.
  void configure(RobotModel& model) const override {
    const std::string problem = shapeProblem(model);
    if (!problem.empty())
      throw graspkit::Error(graspkit::SourceLocation{model.file.string()},
                            "a Puma560 robot needs GraspIt!'s Puma 560 kinematics: " + problem);
    model.isHand = false;  // an arm: GraspIt!'s Puma560 derives from Robot, not Hand
  }

  IkResult inverseKinematics(const Robot& robot, const Transform& target,
                             const IkRequest& request) const override {
    const RobotModel& model = robot.model();
    const Transform local = (robot.pose() * model.chains[request.chain].base).inverse() * target;
    const auto all = candidates(model, local, robot.dofValues()[3]);
    IkResult result;
    const int chosen = chooseCandidate(all, robot.dofValues());
    if (chosen < 0) {
      result.failure = noSolution(all, local);
      return result;
    }
    result.success = true;
    result.dofValues.assign(all[chosen].angle.begin(), all[chosen].angle.end());
    return result;
  }

 private:
  static std::string shapeProblem(const RobotModel& model) {
    if (model.dofs.size() != 6 || model.chains.size() != 1 || model.chains[0].joints.size() != 6)
      return fmt::format("6 DOFs and one chain of 6 joints, this file has {} DOFs and {} chains",
                         model.dofs.size(), model.chains.size());
    // (d, a, alpha) per joint, from the DH table in the header comment.
    const std::array<std::array<double, 3>, 6> dh{{{0, 0, M_PI / 2},
                                                   {0, kA2, 0},
                                                   {kD3, kA3, -M_PI / 2},
                                                   {kD4, 0, M_PI / 2},
                                                   {0, 0, -M_PI / 2},
                                                   {0, 0, 0}}};
    for (int j = 0; j < 6; ++j) {
      const graspkit::Joint& joint = model.chains[0].joints[j];
      const bool same =
          joint.type == graspkit::JointType::Revolute && joint.dof == j && joint.ratio == 1.0 &&
          std::abs(joint.theta) < 1e-9 && std::abs(joint.d - dh[j][0]) < 1e-6 &&
          std::abs(joint.a - dh[j][1]) < 1e-6 && std::abs(joint.alpha - dh[j][2]) < 1e-9;
      if (!same)
        return fmt::format("joint {} differs from theta=d{}, d={}, a={}, alpha={} deg", j + 1, j,
                           dh[j][0], dh[j][1], graspkit::radiansToDegrees(dh[j][2]));
    }
    if (model.chains[0].links.back().lastJoint != 5) return "the last link must follow joint 6";
    return {};
  }
};

void registerPuma560(graspkit::Registrar& registrar) {
  registrar.addRobotType("Puma560", [] { return std::make_shared<const Puma560>(); });
}

}  // namespace

GRASPKIT_PLUGIN("puma560", "1.0.0", registerPuma560)
