#pragma once
// MJCF out: any robot graspkit reads, written as an MJCF model with STL meshes.

#include <filesystem>
#include "graspkit/model/robot.hpp"

namespace graspkit {

// Writes `robot` as FOLDER/<name>.xml with its link meshes as binary STL in FOLDER/meshes
// (metres, kilograms), and returns the MJCF's path. The palm is a fixed body; each link is a
// body at its frame with a hinge or slide joint on its DH axis and the joint's limits, its mesh
// as a geom and its mass properties as <inertial> (inertiafromgeom is off; an inertia MuJoCo
// would refuse, not positive definite, becomes a solid sphere's of the body's radius); a DOF's
// other joints follow its first joint through <equality><joint polycoef>, and a position actuator
// drives each DOF's first joint, so the file reads back (loadMjcfFile) with the same DOFs. The
// pairs graspkit never checks (one chain's links, the robot's exclusions) are <contact><exclude>s.
// MuJoCo joint values are graspkit's joint values (ratio x DOF value). Materials and tendons are
// not written.
std::filesystem::path saveMjcf(const RobotModel& robot, const std::filesystem::path& folder);

}  // namespace graspkit
