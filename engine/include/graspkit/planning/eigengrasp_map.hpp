#pragma once
// The map between a hand's DOF values and its eigengrasp amplitudes (Ciocarlie's posture
// subspace): dofs = origin + norm .* (E^T a), where the rows of E are the eigengrasp directions.
// The way back is the least-squares projection, exact when the DOFs lie in the subspace.

#include <Eigen/Core>

#include "graspkit/model/eigengrasp.hpp"

namespace graspkit {

struct RobotModel;

class EigengraspMap {
 public:
  // Throws graspkit::Error when the set's directions do not match the model's DOF count.
  explicit EigengraspMap(const RobotModel& hand);

  int size() const { return static_cast<int>(directions_.rows()); }
  int dofCount() const { return static_cast<int>(directions_.cols()); }

  // DOF values for amplitudes `a`, clamped into each DOF's range (as GraspIt! does before it
  // applies an eigen posture).
  Eigen::VectorXd dofs(const Eigen::VectorXd& amplitudes) const;
  // The amplitudes whose DOF values are nearest (least squares) to `dofs`.
  Eigen::VectorXd amplitudes(const Eigen::VectorXd& dofs) const;

  // The search range of amplitude i: the file's <Limits>, or GraspIt!'s default of [-4, 4]; for a
  // hand without an eigengrasp file (identity eigengrasps), its DOF's whole range.
  double minAmplitude(int i) const { return min_[i]; }
  // The posture the amplitudes are measured from, and the per-DOF scale (the file's, or the
  // DOF-range midpoint and ones).
  const Eigen::VectorXd& origin() const { return origin_; }
  const Eigen::VectorXd& norm() const { return norm_; }
  // Eigengrasp i's direction, one value per DOF.
  Eigen::VectorXd direction(int i) const { return directions_.row(i).transpose(); }
  double maxAmplitude(int i) const { return max_[i]; }

 private:
  Eigen::MatrixXd directions_;  // one eigengrasp per row
  Eigen::MatrixXd projection_;  // pseudo-inverse of directions_^T
  Eigen::VectorXd origin_;
  Eigen::VectorXd norm_;
  Eigen::VectorXd dofMin_;
  Eigen::VectorXd dofMax_;
  Eigen::VectorXd min_;
  Eigen::VectorXd max_;
};

}  // namespace graspkit
