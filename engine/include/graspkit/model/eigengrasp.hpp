#pragma once
// Eigengrasps: a low-dimensional basis of hand postures (Ciocarlie). q = origin + norm .* (E^T a).

#include <optional>
#include <vector>

#include <Eigen/Core>

namespace graspkit {

struct Eigengrasp {
  Eigen::VectorXd direction;  // normalised, one entry per DOF
  double eigenValue = 0.5;
  std::optional<double> min;  // fixed amplitude range, when the file gives <Limits>
  std::optional<double> max;
};

struct EigengraspSet {
  std::vector<Eigengrasp> grasps;
  std::optional<Eigen::VectorXd> origin;  // default: the DOF-range midpoint
  std::optional<Eigen::VectorXd> norm;    // default: all ones
  bool identity = false;                  // true when made up for a robot with no file
};

// Identity eigengrasps: one per DOF, for a robot with no eigengrasp file.
EigengraspSet identityEigengrasps(int dof_count);

}  // namespace graspkit
