#pragma once
// GraspIt!'s eigengrasp files (<EigenGrasps>), read for a robot.

#include <filesystem>
#include "graspkit/model/eigengrasp.hpp"

namespace graspkit {

// An <EigenGrasps dimensions=N> file for a robot with `dof_count` DOFs.
EigengraspSet loadEigengraspFile(const std::filesystem::path& file, int dof_count);

}  // namespace graspkit
