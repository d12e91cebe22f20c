#pragma once
// GraspIt! robot files out: any robot graspkit reads, written as GraspIt! XML.

#include <filesystem>
#include "graspkit/model/robot.hpp"

namespace graspkit {

// Writes `robot` as GraspIt! XML: FOLDER/<name>.xml, and a Body XML with an OFF mesh per body
// in FOLDER/iv (where the robot file looks for them), so that GraspIt! itself can load a robot
// graspkit read (a URDF hand). A link's own frame (Link::frame, a URDF link's) is baked into its
// mesh and mass properties, GraspIt!'s links sitting at their DH frames. Returns the robot
// file's path. Eigengrasps, virtual contacts and the robot type's extras are not written.
std::filesystem::path saveRobotFile(const RobotModel& robot, const std::filesystem::path& folder);

}  // namespace graspkit
