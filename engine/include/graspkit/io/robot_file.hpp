#pragma once
// Robot files (<robot type=...>), with the eigengrasp and virtual-contact files they name.

#include <filesystem>
#include <memory>

#include "graspkit/io/load_options.hpp"
#include "graspkit/io/model_cache.hpp"
#include "graspkit/robot.hpp"

namespace graspkit {

// Bounds on one robot. GraspIt!'s hands have at most a few dozen DOFs and links; the bounds keep
// a hostile file from costing memory out of proportion to its size (a robot's eigengrasp matrix,
// identity by default, holds DOFs x DOFs numbers) while leaving room for whole humanoids.
inline constexpr int kMaxRobotDofs = 1024;
inline constexpr int kMaxRobotJoints = 4096;  // over all chains, and as many links

// Throws graspkit::Error naming file, line and element. The <robot type> is looked up in the
// registry (loading the plugin that provides it); an unknown type is an error listing the
// available types and the plugin search path, unless options.genericRobotFallback asks for a
// generic Hand instead.
std::shared_ptr<const RobotModel> loadRobotFile(const std::filesystem::path& file,
                                                const LoadOptions& options = {},
                                                ModelCache* cache = nullptr);

// Writes `robot` as GraspIt! XML: FOLDER/<name>.xml, and a Body XML with an OFF mesh per body
// in FOLDER/iv (where the robot file looks for them), so that GraspIt! itself can load a robot
// graspkit read (a URDF hand). A link's own frame (Link::frame, a URDF link's) is baked into its
// mesh and mass properties, GraspIt!'s links sitting at their DH frames. Returns the robot
// file's path. Eigengrasps, virtual contacts and the robot type's extras are not written.
std::filesystem::path saveRobotFile(const RobotModel& robot, const std::filesystem::path& folder);

// An <EigenGrasps dimensions=N> file for a robot with `dof_count` DOFs.
EigengraspSet loadEigengraspFile(const std::filesystem::path& file, int dof_count);

// Identity eigengrasps: one per DOF, for a robot with no eigengrasp file.
EigengraspSet identityEigengrasps(int dof_count);

std::vector<VirtualContact> loadVirtualContactFile(const std::filesystem::path& file);

}  // namespace graspkit
