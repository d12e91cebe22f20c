#pragma once
// Robot files (<robot type=...>) in: the reader for every robot format graspkit knows (GraspIt!
// XML, URDF, MJCF), chosen by the file. The eigengrasp and virtual-contact files a GraspIt! robot
// names are read by eigengrasp_file.hpp and virtual_contact_file.hpp; robot_export.hpp writes.

#include <filesystem>
#include <memory>

#include "graspkit/io/common/load_options.hpp"
#include "graspkit/io/common/model_cache.hpp"
#include "graspkit/model/robot.hpp"

namespace graspkit {

// Throws graspkit::Error naming file, line and element. The <robot type> is looked up in the
// registry (loading the plugin that provides it); an unknown type is an error listing the
// available types and the plugin search path, unless options.genericRobotFallback asks for a
// generic Hand instead.
std::shared_ptr<const RobotModel> loadRobotFile(const std::filesystem::path& file,
                                                const LoadOptions& options = {},
                                                ModelCache* cache = nullptr);

}  // namespace graspkit
