#pragma once
// One world as a front end holds it: the world, the file it came from, and the model cache its
// files are read through (a robot or mesh used by several worlds is read once). The graspkit
// program, Lua's World, Python's World and the C ABI's graspkit_world are each one of these, so
// that loading, adding files, removing bodies and saving behave the same everywhere.

#include <filesystem>
#include <memory>
#include <utility>
#include <vector>

#include "graspkit/io/common/load_options.hpp"
#include "graspkit/io/common/model_cache.hpp"
#include "graspkit/math/transform.hpp"
#include "graspkit/model/body.hpp"
#include "graspkit/model/world.hpp"

namespace graspkit::host {

struct WorldSession {
  World world;
  std::filesystem::path file;  // where it was loaded from or last saved; empty for a new world
  // Shared by the sessions one host makes (a Lua script's worlds share one), and by clones.
  std::shared_ptr<ModelCache> cache = std::make_shared<ModelCache>();
  // Free-body indices removed by removeBody, in order: a front end's handle to a body records
  // how many it has seen and follows them (followRemovals) when it is next used.
  std::vector<int> removedBodies;

  // A World, Robot or Body file (loadAnyFile), URDF and MJCF included.
  static WorldSession load(const std::filesystem::path& file, const LoadOptions& options = {},
                           std::shared_ptr<ModelCache> cache = nullptr);

  // Adds one body from a Body file (or a mesh) as `kind`; returns its index.
  int addBody(const std::filesystem::path& file, BodyKind kind,
              const Transform& pose = Transform::Identity());
  // Adds one robot (any robot format); returns its index.
  int addRobot(const std::filesystem::path& file, const LoadOptions& options = {},
               const Transform& pose = Transform::Identity());
  // Adds every body and robot of a World, Robot or Body file; returns the indices of the first
  // body and the first robot added (the counts before the call).
  std::pair<int, int> addFile(const std::filesystem::path& file, const LoadOptions& options = {});
  // Removes free body `index`; the bodies after it move down one. Throws graspkit::Error for a
  // bad index.
  void removeBody(int index);
  // Brings a body index up to date with the removals since `seen` (which it advances). False
  // when the body itself was removed.
  bool followRemovals(int& index, std::size_t& seen) const;
  // Saves as GraspIt! writes world files, atomically, and remembers the file.
  void save(const std::filesystem::path& file);
  // A copy sharing the meshes and the cache: cheap.
  WorldSession clone() const;
};

}  // namespace graspkit::host
