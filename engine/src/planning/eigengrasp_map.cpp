#include "graspkit/planning/eigengrasp_map.hpp"

#include <fmt/format.h>
#include <Eigen/QR>

#include "graspkit/base/error.hpp"
#include "graspkit/model/robot.hpp"

namespace graspkit {

namespace {
// GraspIt!'s amplitude range when an eigengrasp file gives no <Limits>.
constexpr double kDefaultAmplitudeLimit = 4.0;
}  // namespace

EigengraspMap::EigengraspMap(const RobotModel& hand) {
  const int dofs = static_cast<int>(hand.dofs.size());
  const EigengraspSet& set = hand.eigengrasps;
  if (set.grasps.empty())
    throw Error(fmt::format("{}: robot {} has no eigengrasps", hand.file.string(), hand.name));
  directions_.resize(static_cast<Eigen::Index>(set.grasps.size()), dofs);
  min_.resize(directions_.rows());
  max_.resize(directions_.rows());
  for (std::size_t i = 0; i < set.grasps.size(); ++i) {
    const Eigengrasp& grasp = set.grasps[i];
    if (grasp.direction.size() != dofs)
      throw Error(fmt::format("{}: eigengrasp {} has {} values for {} DOFs", hand.file.string(), i,
                              grasp.direction.size(), dofs));
    directions_.row(static_cast<Eigen::Index>(i)) = grasp.direction.transpose();
    min_[static_cast<Eigen::Index>(i)] = grasp.min.value_or(-kDefaultAmplitudeLimit);
    max_[static_cast<Eigen::Index>(i)] = grasp.max.value_or(kDefaultAmplitudeLimit);
  }
  dofMin_.resize(dofs);
  dofMax_.resize(dofs);
  for (int d = 0; d < dofs; ++d) {
    dofMin_[d] = hand.dofs[d].min;
    dofMax_[d] = hand.dofs[d].max;
  }
  origin_ = set.origin.value_or(0.5 * (dofMin_ + dofMax_));
  norm_ = set.norm.value_or(Eigen::VectorXd::Ones(dofs));
  if (origin_.size() != dofs || norm_.size() != dofs)
    throw Error(fmt::format("{}: eigengrasp origin or norm does not have {} values",
                            hand.file.string(), dofs));
  // A hand without an eigengrasp file searches its DOFs one by one: each amplitude spans its
  // DOF's whole range (a fixed +-4 would hold a gripper's 0-40 mm DOF between 16 and 24 mm,
  // never open enough to reach round a box).
  if (set.identity) {
    for (int i = 0; i < directions_.rows(); ++i) {
      const Eigengrasp& grasp = set.grasps[static_cast<std::size_t>(i)];
      Eigen::Index d = 0;
      if (grasp.min || grasp.max || directions_.row(i).cwiseAbs().maxCoeff(&d) != 1.0) continue;
      min_[i] = (dofMin_[d] - origin_[d]) / norm_[d];
      max_[i] = (dofMax_[d] - origin_[d]) / norm_[d];
    }
  }
  projection_ = directions_.transpose().completeOrthogonalDecomposition().pseudoInverse();
}

Eigen::VectorXd EigengraspMap::dofs(const Eigen::VectorXd& amplitudes) const {
  Eigen::VectorXd q = origin_ + norm_.cwiseProduct(directions_.transpose() * amplitudes);
  return q.cwiseMax(dofMin_).cwiseMin(dofMax_);
}

Eigen::VectorXd EigengraspMap::amplitudes(const Eigen::VectorXd& dofs) const {
  return projection_ * (dofs - origin_).cwiseQuotient(norm_);
}

}  // namespace graspkit
