#include "graspkit/model/robot.hpp"

#include <cmath>

#include <fmt/format.h>

#include "graspkit/base/error.hpp"

namespace graspkit {

Transform ApproachDirection::frame() const {
  const Vector3 z = direction.normalized();
  Vector3 x = std::abs(z.dot(Vector3::UnitX())) > 0.9 ? Vector3::UnitY() : Vector3::UnitX();
  const Vector3 y = z.cross(x).normalized();
  x = y.cross(z).normalized();
  Transform t = Transform::Identity();
  t.linear().col(0) = x;
  t.linear().col(1) = y;
  t.linear().col(2) = z;
  t.translation() = referenceLocation;
  return t;
}

bool RobotModel::hasLink(const LinkRef& ref) const {
  if (ref.isBase()) return true;
  return ref.chain < static_cast<int>(chains.size()) && ref.link >= 0 &&
         ref.link < static_cast<int>(chains[ref.chain].links.size());
}

void RobotModel::disableCollision(const LinkRef& a, const LinkRef& b) {
  for (const LinkRef& ref : {a, b}) {
    if (!hasLink(ref))
      throw Error(SourceLocation{file.string()},
                  fmt::format("robot type {} excludes chain {} link {} from collisions, but the "
                              "robot has no such link",
                              type, ref.chain, ref.link));
  }
  disabledCollisions.push_back(CollisionPair{a, b});
}

int RobotModel::jointCount() const {
  int count = 0;
  for (const KinematicChain& chain : chains) count += static_cast<int>(chain.joints.size());
  return count;
}

int RobotModel::linkCount() const {
  int count = 0;
  for (const KinematicChain& chain : chains) count += static_cast<int>(chain.links.size());
  return count;
}

const Joint& RobotModel::joint(int robot_joint_index) const {
  for (const KinematicChain& chain : chains) {
    const int local = robot_joint_index - chain.firstJoint;
    if (local >= 0 && local < static_cast<int>(chain.joints.size())) return chain.joints[local];
  }
  throw Error(fmt::format("robot '{}' has no joint {}", name, robot_joint_index));
}

std::size_t RobotModel::triangleCount() const {
  std::size_t count = palm && palm->mesh ? palm->mesh->triangleCount() : 0;
  for (const KinematicChain& chain : chains)
    for (const Link& link : chain.links)
      if (link.body && link.body->mesh) count += link.body->mesh->triangleCount();
  return count;
}

Robot::Robot(std::shared_ptr<const RobotModel> model) : model_(std::move(model)) {
  if (!model_) throw Error("a robot needs a model");
  dof_values_.resize(model_->dofs.size());
  for (std::size_t d = 0; d < model_->dofs.size(); ++d) {
    dof_values_[d] = model_->dofs[d].clamp(model_->dofs[d].defaultValue);
  }
  joint_values_.assign(model_->jointCount(), 0.0);
  breakaway_.assign(model_->jointCount(), BreakawayState{});
  dof_velocities_.assign(model_->dofs.size(), 0.0);
  link_poses_.resize(model_->chains.size());
  updateJoints();
  updateLinkPoses();
}

namespace {
void checkDofVector(const Robot& robot, std::span<const double> values, const char* what) {
  if (values.size() != static_cast<std::size_t>(robot.dofCount())) {
    throw Error(fmt::format("robot '{}' has {} DOFs, {} {} given", robot.name(), robot.dofCount(),
                            values.size(), what));
  }
  for (std::size_t d = 0; d < values.size(); ++d) {
    if (!std::isfinite(values[d])) {
      throw Error(
          fmt::format("robot '{}': DOF {} {} is not a finite number", robot.name(), d, what));
    }
  }
}
}  // namespace

void Robot::setDofVelocities(std::span<const double> velocities) {
  checkDofVector(*this, velocities, "velocities");
  dof_velocities_.assign(velocities.begin(), velocities.end());
}

void Robot::setDofTargets(std::span<const double> targets) {
  if (targets.empty()) {
    dof_targets_.clear();
    return;
  }
  checkDofVector(*this, targets, "targets");
  dof_targets_.assign(targets.begin(), targets.end());
}

void Robot::setDofReferences(std::span<const double> references) {
  if (references.empty()) {
    dof_references_.clear();
    return;
  }
  checkDofVector(*this, references, "references");
  dof_references_.assign(references.begin(), references.end());
}

void Robot::setPose(const Transform& pose) {
  pose_ = pose;
  updateLinkPoses();
}

void Robot::setDofValues(std::span<const double> values, LimitPolicy policy) {
  takeDofValues(values, policy);
  updateJoints();
  updateLinkPoses();
}

void Robot::setPoseAndDofValues(const Transform& pose, std::span<const double> values,
                                LimitPolicy policy) {
  takeDofValues(values, policy);
  pose_ = pose;
  updateJoints();
  updateLinkPoses();
}

void Robot::takeDofValues(std::span<const double> values, LimitPolicy policy) {
  if (values.size() != dof_values_.size()) {
    throw Error(fmt::format("robot '{}' has {} DOFs, {} values given", name(), dof_values_.size(),
                            values.size()));
  }
  for (std::size_t d = 0; d < values.size(); ++d) {
    if (!std::isfinite(values[d])) {
      throw Error(fmt::format("robot '{}': DOF {} value is not a finite number", name(), d));
    }
  }
  for (std::size_t d = 0; d < values.size(); ++d) {
    dof_values_[d] = policy == LimitPolicy::Clamp ? model_->dofs[d].clamp(values[d]) : values[d];
  }
}

void Robot::setDofValue(int dof, double value, LimitPolicy policy) {
  if (dof < 0 || dof >= dofCount()) {
    throw Error(fmt::format("robot '{}' has {} DOFs, DOF {} requested", name(), dofCount(), dof));
  }
  std::vector<double> values(dof_values_);
  values[dof] = value;
  setDofValues(values, policy);
}

void Robot::setBreakaway(int joint, BreakawayState state) {
  if (joint < 0 || joint >= static_cast<int>(breakaway_.size())) {
    throw Error(fmt::format("robot '{}' has {} joints, joint {} requested", name(),
                            breakaway_.size(), joint));
  }
  breakaway_[joint] = state;
  updateJoints();
  updateLinkPoses();
}

void Robot::releaseBreakawayNotLagging() {
  bool released = false;
  for (int j = 0; j < static_cast<int>(breakaway_.size()); ++j) {
    BreakawayState& state = breakaway_[j];
    if (state.engaged &&
        std::abs(dof_values_[model_->joint(j).dof] - state.value) <= kBreakawayLag) {
      state = {};
      released = true;
    }
  }
  if (!released) return;
  updateJoints();
  updateLinkPoses();
}

const Transform& Robot::linkPose(const LinkRef& ref) const {
  return ref.isBase() ? pose_ : link_poses_[ref.chain][ref.link];
}

// Joint value = ratio * DOF value; a joint that broke away stays where its DOF was when it
// stopped. Values outside the joint limits come only from LimitPolicy::Ignore.
void Robot::updateJoints() {
  for (const KinematicChain& chain : model_->chains) {
    for (std::size_t local = 0; local < chain.joints.size(); ++local) {
      const Joint& joint = chain.joints[local];
      const std::size_t j = chain.firstJoint + local;
      const double dof_value = breakaway_[j].engaged ? breakaway_[j].value : dof_values_[joint.dof];
      joint_values_[j] = joint.ratio * dof_value;
    }
  }
}

void Robot::updateLinkPoses() {
  for (std::size_t c = 0; c < model_->chains.size(); ++c) {
    const KinematicChain& chain = model_->chains[c];
    std::span<const double> values(joint_values_.data() + chain.firstJoint, chain.joints.size());
    graspkit::linkPoses(chain, pose_ * chain.base, values, link_poses_[c]);
  }
}

}  // namespace graspkit
