#include "test_paths.hpp"

#include <atomic>
#include <cstdlib>
#include <iostream>
#include <string>

#include <unistd.h>

namespace graspkit::test {

std::filesystem::path sourceDir() {
  return GRASPKIT_SOURCE_DIR;
}
std::filesystem::path modelsDir() {
  return sourceDir() / "models";
}

std::filesystem::path scratchDir() {
  static std::atomic<int> counter{0};
  auto dir = std::filesystem::path(GRASPKIT_BINARY_DIR) / "test_scratch" /
             (std::to_string(::getpid()) + "_" + std::to_string(counter++));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

std::optional<std::filesystem::path> sharedDir() {
  std::filesystem::path dir = GRASPKIT_SHARED_DEFAULT;
  if (const char* env = std::getenv("GRASPKIT_SHARED"); env && *env) dir = env;
  if (std::filesystem::is_directory(dir / "graspit-data")) return dir;
  static bool warned = false;
  if (!warned) {
    std::cerr << "\n*** WARNING: shared GraspIt! corpus not found at " << dir
              << "; tests that need it are SKIPPED ***\n\n";
    warned = true;
  }
  return std::nullopt;
}

std::optional<std::filesystem::path> graspitDataDir() {
  if (auto shared = sharedDir()) return *shared / "graspit-data";
  return std::nullopt;
}

std::optional<std::filesystem::path> referenceFigures() {
  if (auto shared = sharedDir()) return *shared / "reference" / "graspit-figures.json";
  return std::nullopt;
}

}  // namespace graspkit::test
