#pragma once
// Robots written as MJCF, so that MuJoCo can load GraspIt!'s hands (and act as a second method
// for their dynamics).

#include <filesystem>

#include "graspkit/robot.hpp"

namespace graspkit {

// Writes `robot` as FOLDER/<name>.xml with its link meshes as binary STL in FOLDER/meshes
// (metres, kilograms), and returns the MJCF's path. The palm is a fixed body; each link is a
// body at its frame with a hinge or slide joint on its DH axis and the joint's limits, its mesh
// as a geom and its mass properties as <inertial> (inertiafromgeom is off; an inertia MuJoCo
// would refuse, not positive definite, becomes a solid sphere's of the body's radius); a DOF's other joints
// follow its first joint through <equality><joint polycoef>. MuJoCo joint values are graspkit's
// joint values (ratio x DOF value). Controllers, materials and contacts are not written.
std::filesystem::path saveMjcf(const RobotModel& robot, const std::filesystem::path& folder);

}  // namespace graspkit
