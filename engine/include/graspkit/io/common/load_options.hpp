#pragma once
// Options shared by the file readers.

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "graspkit/model/material.hpp"

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
  // URDF robots (io/urdf_file.hpp): folders holding the packages `package://` paths name (a
  // package's folder itself, or the folder it sits in), the link to take as the palm (empty:
  // the URDF's root), the material of every link, and per link (by URDF link name) another.
  std::vector<std::filesystem::path> packagePaths;
  std::string urdfPalm;
  Material urdfMaterial = Material::Rubber;
  std::map<std::string, Material> urdfLinkMaterials;
  // URDF and MJCF hands: switch off the link pairs that collide at rest and in most postures,
  // or always (graspkit/collision/self_collision_setup.hpp). GraspIt!'s robot files never are.
  bool switchOffInherentCollisions = true;
  // Closing directions that override the hand's (graspkit/model/closing_direction.hpp): DOF index
  // -> +1 (closes towards the upper limit) or -1. Any robot file; an index past the DOFs is an
  // error.
  std::map<int, int> closingDirections;
  // URDF and MJCF hands: infer each DOF's closing direction from the geometry (else every DOF
  // closes towards its upper limit, as before).
  bool inferClosingDirections = true;
  // MJCF hands: each mesh geom collides as its convex hull, as in MuJoCo (mass and inertia still
  // come from the mesh itself); false keeps every triangle of the mesh.
  bool mjcfMeshHulls = true;
  // URDF: an SRDF whose <disable_collisions> pairs are never checked. Empty: the .srdf beside
  // the URDF (same stem), when there is one.
  std::filesystem::path srdf;
};

// The folders a world's <filename> is resolved against, in order, each once (a folder named
// twice, by --root and as a parent of the world file, is searched where it first comes). Names
// starting with `./` or `../` are looked for beside the world file before these
// (io/graspit/world_file.hpp).
std::vector<std::filesystem::path> searchRoots(const std::filesystem::path& world_file,
                                               const LoadOptions& options);

}  // namespace graspkit
