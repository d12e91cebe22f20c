#pragma once
// Internal: what the robot readers (GraspIt! XML, URDF) derive from a model's chains.

#include <vector>

#include "graspkit/model/robot.hpp"

namespace graspkit::model {

// Lists each DOF's joints (robot-wide indices) and sets its range to the intersection of its
// joints' limits divided by their coupling ratios; a DOF that drives no joint keeps an infinite
// range. Returns, per DOF, whether its (last) joint is revolute.
std::vector<bool> gatherDofJoints(RobotModel& robot);

}  // namespace graspkit::model
