#pragma once
// Options shared by the file readers.

#include <filesystem>
#include <vector>

namespace graspkit {

class Registry;

struct LoadOptions {
  // Folders searched first for a world's <filename> paths (GraspIt!'s $GRASPIT). After them
  // come GRASPKIT_ROOT, then GRASPIT (environment), then the world file's folder and each of
  // its parents.
  std::vector<std::filesystem::path> roots;
  bool useEnvironment = true;
  // A robot whose type no plugin provides loads as a generic Hand (with a warning) instead of
  // failing.
  bool genericRobotFallback = false;
  // Where robot types are looked up; null means Registry::global().
  Registry* registry = nullptr;
};

// The folders a world's <filename> is resolved against, in order.
std::vector<std::filesystem::path> searchRoots(const std::filesystem::path& world_file,
                                               const LoadOptions& options);

}  // namespace graspkit
