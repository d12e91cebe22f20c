#include "graspkit/model/eigengrasp.hpp"

namespace graspkit {

EigengraspSet identityEigengrasps(int dof_count) {
  EigengraspSet set;
  set.identity = true;
  for (int d = 0; d < dof_count; ++d) {
    Eigengrasp grasp;
    grasp.direction = Eigen::VectorXd::Unit(dof_count, d);
    set.grasps.push_back(std::move(grasp));
  }
  return set;
}

}  // namespace graspkit
