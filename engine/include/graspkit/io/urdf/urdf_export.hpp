#pragma once
// URDF out: any robot graspkit reads, written as a URDF with STL meshes.

#include <filesystem>
#include "graspkit/model/robot.hpp"

namespace graspkit {

// Writes `robot` as FOLDER/<name>.urdf with its link meshes as binary STL in FOLDER/meshes
// (metres, kilograms), and returns the URDF's path. Each DH joint becomes a movable joint onto
// an empty link on its axis and a fixed joint to its link, whose URDF frame is the link's
// graspkit frame; a DOF's first joint carries it (DOFs in order) and the DOF's other joints
// mimic it. Read back, the robot has the same DOFs (a DOF's value scaled by its first joint's
// coupling ratio), links, link poses and triangles. Materials, controller gains, breakaway and
// the robot type's own behaviour have no URDF form and are not written.
std::filesystem::path saveUrdf(const RobotModel& robot, const std::filesystem::path& folder);

}  // namespace graspkit
