#include "graspkit/planning/search_space.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "graspkit/base/error.hpp"
#include "graspkit/model/robot.hpp"

namespace graspkit {

namespace {

// The ellipsoid space's semi-axes (mm), GraspIt!'s fixed parameters a, b, c.
constexpr double kEllipsoidA = 80.0;
constexpr double kEllipsoidB = 80.0;
constexpr double kEllipsoidC = 160.0;

std::vector<SearchVariable> positionVariables(PositionSpace space) {
  switch (space) {
    case PositionSpace::Complete:
      return {{"Tx", -250, 250, 100}, {"Ty", -250, 250, 100}, {"Tz", -250, 250, 100},
              {"Qw", -5, 5, 1},       {"Qx", -5, 5, 1},       {"Qy", -5, 5, 1},
              {"Qz", -5, 5, 1}};
    case PositionSpace::AxisAngle:
      return {{"Tx", -250, 250, 150},
              {"Ty", -250, 250, 150},
              {"Tz", -250, 350, 150},
              {"theta", 0, M_PI, M_PI / 5},
              {"phi", -M_PI, M_PI, M_PI / 2, true},
              {"alpha", 0, M_PI, M_PI / 2}};
    case PositionSpace::Ellipsoid:
      return {{"beta", -M_PI / 2, M_PI / 2, M_PI / 2},
              {"gamma", -M_PI, M_PI, M_PI, true},
              {"tau", -M_PI, M_PI, M_PI, true},
              {"dist", -50, 100, 50}};
    case PositionSpace::Approach:
      return {{"dist", -30, 200, 100},
              {"wrist 1", -M_PI / 3, M_PI / 3, M_PI / 6},
              {"wrist 2", -M_PI / 3, M_PI / 3, M_PI / 6}};
  }
  return {};
}

Transform translation(const Vector3& t) {
  Transform pose = Transform::Identity();
  pose.translation() = t;
  return pose;
}

Transform rotation(double angle, const Vector3& axis) {
  Transform pose = Transform::Identity();
  pose.linear() = Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
  return pose;
}

// The hand frame on the ellipsoid at (beta, gamma), `dist` outside it, its z along the inward
// normal, turned by tau about the object's z.
Transform ellipsoidPose(double beta, double gamma, double tau, double dist) {
  const Vector3 point(kEllipsoidA * std::cos(beta) * std::cos(gamma),
                      kEllipsoidB * std::cos(beta) * std::sin(gamma), kEllipsoidC * std::sin(beta));
  const Vector3 du(-kEllipsoidA * std::sin(beta) * std::cos(gamma),
                   -kEllipsoidB * std::sin(beta) * std::sin(gamma), kEllipsoidC * std::cos(beta));
  const Vector3 dv(-kEllipsoidA * std::cos(beta) * std::sin(gamma),
                   kEllipsoidB * std::cos(beta) * std::cos(gamma), 0.0);
  Vector3 normal = du.normalized().cross(dv.normalized());
  if (normal.squaredNorm() < 1e-24) normal = Vector3::UnitZ() * (beta > 0 ? -1.0 : 1.0);
  normal.normalize();
  Vector3 y = normal.cross(Vector3::UnitX());
  if (y.squaredNorm() < 1e-12) y = normal.cross(Vector3::UnitY());
  y.normalize();
  const Vector3 x = y.cross(normal);
  Transform on = Transform::Identity();
  on.linear().col(0) = x;
  on.linear().col(1) = y;
  on.linear().col(2) = normal;
  on.translation() = point - dist * normal;
  return rotation(tau, Vector3::UnitZ()) * on;
}

}  // namespace

std::span<const EnumName<PostureSpace>> enumNames(std::type_identity<PostureSpace>) {
  static constexpr EnumName<PostureSpace> kNames[] = {{PostureSpace::Eigen, "eigen"},
                                                      {PostureSpace::Dof, "dof"},
                                                      {PostureSpace::Eigen, "POSE_EIGEN"},
                                                      {PostureSpace::Dof, "POSE_DOF"}};
  return kNames;
}

std::span<const EnumName<PositionSpace>> enumNames(std::type_identity<PositionSpace>) {
  static constexpr EnumName<PositionSpace> kNames[] = {
      {PositionSpace::Complete, "complete"},         {PositionSpace::AxisAngle, "axis-angle"},
      {PositionSpace::Ellipsoid, "ellipsoid"},       {PositionSpace::Approach, "approach"},
      {PositionSpace::Complete, "SPACE_COMPLETE"},   {PositionSpace::AxisAngle, "SPACE_AXIS_ANGLE"},
      {PositionSpace::Ellipsoid, "SPACE_ELLIPSOID"}, {PositionSpace::Approach, "SPACE_APPROACH"}};
  return kNames;
}

SearchSpace::SearchSpace(const RobotModel& hand, PositionSpace position, PostureSpace posture,
                         const Transform& reference)
    : position_(position),
      posture_(posture),
      reference_(reference),
      approach_(hand.approachFrame()),
      eigengrasps_(hand) {
  for (const Dof& dof : hand.dofs) {
    dofMin_.push_back(dof.min);
    dofMax_.push_back(dof.max);
  }
  if (posture == PostureSpace::Eigen) {
    for (int i = 0; i < eigengrasps_.size(); ++i) {
      const double min = eigengrasps_.minAmplitude(i), max = eigengrasps_.maxAmplitude(i);
      variables_.push_back({fmt::format("EG {}", i), min, max, (max - min) / 4.0});
    }
  } else {
    for (std::size_t d = 0; d < hand.dofs.size(); ++d)
      variables_.push_back({fmt::format("DOF {}", d), dofMin_[d], dofMax_[d],
                            0.5 * (dofMax_[d] - dofMin_[d]), false, dofMax_[d] <= dofMin_[d]});
  }
  posture_count_ = static_cast<int>(variables_.size());
  for (SearchVariable& variable : positionVariables(position))
    variables_.push_back(std::move(variable));
}

std::optional<int> SearchSpace::find(std::string_view name) const {
  for (int i = 0; i < size(); ++i)
    if (variables_[i].name == name) return i;
  return std::nullopt;
}

void SearchSpace::setVariable(int index, const SearchVariable& variable) {
  if (index < 0 || index >= size())
    throw Error(fmt::format("search variable {} out of range (the space has {})", index, size()));
  if (!std::isfinite(variable.min) || !std::isfinite(variable.max) ||
      !std::isfinite(variable.jump) || variable.max < variable.min)
    throw Error(fmt::format("search variable '{}': range [{}, {}] with jump {} is not valid",
                            variables_[index].name, variable.min, variable.max, variable.jump));
  variables_[index] = variable;
}

Transform SearchSpace::corePose(std::span<const double> p) const {
  const Transform approachInverse = approach_.inverse();
  switch (position_) {
    case PositionSpace::Complete: {
      Quaternion q(p[3], p[4], p[5], p[6]);
      if (q.squaredNorm() < 1e-24) q = Quaternion::Identity();
      return makeTransform(Vector3(p[0], p[1], p[2]), q.normalized());
    }
    case PositionSpace::AxisAngle: {
      const double theta = p[3], phi = p[4], alpha = p[5];
      const Vector3 axis(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                         std::cos(theta));
      return translation(Vector3(p[0], p[1], p[2])) * rotation(alpha, axis) * approachInverse;
    }
    case PositionSpace::Ellipsoid:
      return ellipsoidPose(p[0], p[1], p[2], p[3]) * approachInverse;
    case PositionSpace::Approach:
      return approach_ * rotation(p[2], Vector3::UnitY()) * rotation(p[1], Vector3::UnitX()) *
             translation(Vector3(0, 0, p[0])) * approachInverse;
  }
  return Transform::Identity();
}

Transform SearchSpace::handPose(std::span<const double> values) const {
  return reference_ * corePose(values.subspan(posture_count_));
}

std::vector<double> SearchSpace::dofs(std::span<const double> values) const {
  std::vector<double> result(dofMin_.size());
  if (posture_ == PostureSpace::Eigen) {
    const Eigen::VectorXd a = Eigen::Map<const Eigen::VectorXd>(values.data(), eigengrasps_.size());
    const Eigen::VectorXd q = eigengrasps_.dofs(a);
    std::copy(q.data(), q.data() + q.size(), result.begin());
  } else {
    for (std::size_t d = 0; d < result.size(); ++d)
      result[d] = std::clamp(values[d], dofMin_[d], dofMax_[d]);
  }
  return result;
}

std::vector<double> SearchSpace::encode(const Transform& handPose,
                                        std::span<const double> dofs) const {
  if (dofs.size() != dofMin_.size())
    throw Error(fmt::format("{} DOF values given for a hand with {}", dofs.size(), dofMin_.size()));
  std::vector<double> values(variables_.size());
  if (posture_ == PostureSpace::Eigen) {
    const Eigen::VectorXd a = eigengrasps_.amplitudes(
        Eigen::Map<const Eigen::VectorXd>(dofs.data(), static_cast<Eigen::Index>(dofs.size())));
    for (int i = 0; i < posture_count_; ++i) values[i] = a[i];
  } else {
    for (int i = 0; i < posture_count_; ++i) values[i] = dofs[i];
  }
  double* p = values.data() + posture_count_;
  const Transform relative = reference_.inverse() * handPose;
  switch (position_) {
    case PositionSpace::Complete: {
      const Quaternion q(relative.rotation());
      const Vector3 t = relative.translation();
      p[0] = t.x(), p[1] = t.y(), p[2] = t.z();
      p[3] = q.w(), p[4] = q.x(), p[5] = q.y(), p[6] = q.z();
      break;
    }
    case PositionSpace::AxisAngle: {
      const Transform core = relative * approach_;
      const Vector3 t = core.translation();
      p[0] = t.x(), p[1] = t.y(), p[2] = t.z();
      Eigen::AngleAxisd aa(core.rotation());
      double angle = aa.angle();
      Vector3 axis = aa.axis();
      if (angle < 0) angle = -angle, axis = -axis;
      if (angle > M_PI) angle = 2 * M_PI - angle, axis = -axis;
      p[5] = angle;
      if (std::abs(axis.x()) > 1e-7 || std::abs(axis.y()) > 1e-7) {
        p[4] = std::atan2(axis.y(), axis.x());
        p[3] = std::atan2(std::hypot(axis.x(), axis.y()), axis.z());
      } else {
        p[4] = 0.0;
        p[3] = axis.z() >= 0 ? 0.0 : M_PI;
      }
      break;
    }
    case PositionSpace::Approach: {
      // Only the distance along the approach direction is recovered; the wrist angles are 0.
      const Transform core = approach_.inverse() * relative * approach_;
      p[0] = core.translation().z();
      p[1] = p[2] = 0.0;
      break;
    }
    case PositionSpace::Ellipsoid:
      throw Error("the ellipsoid search space cannot encode a given hand pose");
  }
  for (int i = 0; i < size(); ++i)
    values[i] = std::clamp(values[i], variables_[i].min, variables_[i].max);
  return values;
}

double SearchSpace::distance(std::span<const double> a, std::span<const double> b,
                             double lengthScale) const {
  const Transform frameA = handPose(a) * approach_;
  const Transform frameB = handPose(b) * approach_;
  const double scale = lengthScale > 0 ? lengthScale : 200.0;
  const double d = (frameA.translation() - frameB.translation()).norm() / scale;
  const Eigen::AngleAxisd turn(frameA.rotation() * frameB.rotation().transpose());
  const double q = 0.5 * std::abs(turn.angle()) / M_PI;
  return std::max(d, q);
}

}  // namespace graspkit
