#pragma once
// The flags every command that loads files shares: --root, --generic-robots, --close, and for
// URDF robots --package-path, --palm, --urdf-material, --link-material and --srdf, and for MJCF
// hands --mjcf-exact-meshes.

#include <filesystem>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "graspkit/io/common/load_options.hpp"

namespace graspkit::cli {

struct LoadFlags {
  std::vector<std::filesystem::path> roots;
  bool genericRobots = false;
  std::vector<std::filesystem::path> packagePaths;
  std::string palm;
  std::string material;                    // every URDF link's (empty: rubber)
  std::vector<std::string> linkMaterials;  // LINK=MATERIAL
  std::vector<std::string> closing;        // DOF=+ or DOF=-
  std::filesystem::path srdf;              // URDF: <disable_collisions> pairs
  bool mjcfExactMeshes = false;            // MJCF: collide meshes as they are, not their hulls

  // Throws graspkit::Error naming the option for an unknown material or a malformed pair.
  LoadOptions options() const;
};

// With no --root (and no GRASPKIT_ROOT or GRASPIT), an installed program's root is its own
// models, <prefix>/share/graspkit/models.
void addLoadFlags(CLI::App& command, LoadFlags& flags);

}  // namespace graspkit::cli
