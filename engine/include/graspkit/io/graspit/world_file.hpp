#pragma once
// World files: read any GraspIt! world; write one as GraspIt! does (same tag order,
// fullTransform, breakaway dofValues encoding), atomically.

#include <filesystem>

#include "graspkit/io/common/load_options.hpp"
#include "graspkit/io/common/model_cache.hpp"
#include "graspkit/model/world.hpp"

namespace graspkit {

// How a <filename> (or <mountFilename>) is found:
// - an absolute name is that file;
// - a name starting with `./` or `../` (what saveWorldFile writes) is first looked for relative
//   to the world file's own folder, so no --root can shadow it;
// - any other name (GraspIt!'s `models/objects/mug.xml`, relative to its root), and a `./` or
//   `../` name not found beside the world file (`../shared/hands/...` relative to a root), is
//   looked up under LoadOptions::roots (--root), then $GRASPKIT_ROOT, then $GRASPIT, then the
//   world file's folder and each of its parents, the first holding it winning (searchRoots, each
//   folder once). The "not found" error lists the folders searched.
World loadWorldFile(const std::filesystem::path& file, const LoadOptions& options = {},
                    ModelCache* cache = nullptr);

// Loads a body, robot or world file by its root element into a world: a Body file becomes one
// graspable body, a Robot file one robot, a World file itself.
World loadAnyFile(const std::filesystem::path& file, const LoadOptions& options = {},
                  ModelCache* cache = nullptr);

// Writes to a temporary file beside `file`, then renames it over `file`: a failed save never
// leaves a truncated world. Throws graspkit::Error on I/O failure.
//
// Each <filename> (and <mountFilename>) is written so that the saved world loads again from any
// working folder without --root (the search rule is loadWorldFile's, above): the name the model
// was loaded by when the saved world's folder or one of its parents holds that very file (a world
// saved into its own tree keeps GraspIt!'s root-relative names), else the model's path relative
// to the saved world's folder, starting with `./` or `../`, else (no folder in common below the
// file system's root) its absolute path (base/file_reference.hpp).
void saveWorldFile(const World& world, const std::filesystem::path& file);

// The dofValues text GraspIt! writes for a robot: rigid DOFs as their value, breakaway DOFs as
// their value followed by `0` or `1 <value>` per coupled joint.
std::string formatDofValues(const Robot& robot);

// The <fullTransform> text: (+w +x +y +z)[+x +y +z].
std::string formatFullTransform(const Transform& transform);

}  // namespace graspkit
