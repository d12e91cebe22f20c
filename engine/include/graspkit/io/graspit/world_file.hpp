#pragma once
// World files: read any GraspIt! world; write one as GraspIt! does (same tag order,
// fullTransform, breakaway dofValues encoding), atomically.

#include <filesystem>

#include "graspkit/io/common/load_options.hpp"
#include "graspkit/io/common/model_cache.hpp"
#include "graspkit/model/world.hpp"

namespace graspkit {

World loadWorldFile(const std::filesystem::path& file, const LoadOptions& options = {},
                    ModelCache* cache = nullptr);

// Loads a body, robot or world file by its root element into a world: a Body file becomes one
// graspable body, a Robot file one robot, a World file itself.
World loadAnyFile(const std::filesystem::path& file, const LoadOptions& options = {},
                  ModelCache* cache = nullptr);

struct SaveOptions {
  // Paths of files added without a world-file name are written relative to this folder when
  // they lie below it, absolute otherwise.
  std::filesystem::path root;
};

// Writes to a temporary file beside `file`, then renames it over `file`: a failed save never
// leaves a truncated world. Throws graspkit::Error on I/O failure.
void saveWorldFile(const World& world, const std::filesystem::path& file,
                   const SaveOptions& options = {});

// The dofValues text GraspIt! writes for a robot: rigid DOFs as their value, breakaway DOFs as
// their value followed by `0` or `1 <value>` per coupled joint.
std::string formatDofValues(const Robot& robot);

// The <fullTransform> text: (+w +x +y +z)[+x +y +z].
std::string formatFullTransform(const Transform& transform);

}  // namespace graspkit
