#include "model/dof_ranges.hpp"

#include <algorithm>
#include <limits>

namespace graspkit::model {

std::vector<bool> gatherDofJoints(RobotModel& robot) {
  std::vector<bool> revolute(robot.dofs.size(), true);
  for (Dof& dof : robot.dofs) {
    dof.joints.clear();
    dof.min = -std::numeric_limits<double>::infinity();
    dof.max = std::numeric_limits<double>::infinity();
  }
  for (const KinematicChain& chain : robot.chains) {
    for (std::size_t j = 0; j < chain.joints.size(); ++j) {
      const Joint& joint = chain.joints[j];
      Dof& dof = robot.dofs[joint.dof];
      dof.joints.push_back(chain.firstJoint + static_cast<int>(j));
      revolute[joint.dof] = joint.type == JointType::Revolute;
      double lo = joint.min / joint.ratio, hi = joint.max / joint.ratio;
      if (joint.ratio < 0) std::swap(lo, hi);
      dof.min = std::max(dof.min, lo);
      dof.max = std::min(dof.max, hi);
    }
  }
  return revolute;
}

}  // namespace graspkit::model
