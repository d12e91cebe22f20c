#include "graspkit/host/world_session.hpp"

#include "graspkit/io/graspit/body_file.hpp"
#include "graspkit/io/graspit/robot_file.hpp"
#include "graspkit/io/graspit/world_file.hpp"

namespace fs = std::filesystem;

namespace graspkit::host {
namespace {

// Adds `source`'s bodies, robots and connections to `target` (robot indices shifted).
void mergeInto(World& target, World&& source) {
  const int robotOffset = target.robotCount();
  for (Body& body : source.bodies()) target.addBody(std::move(body));
  for (int r = 0; r < source.robotCount(); ++r) {
    const WorldRobot& robot = source.worldRobot(r);
    target.addRobot(robot.robot, robot.filename);
  }
  for (Connection connection : source.connections()) {
    connection.parentRobot += robotOffset;
    connection.childRobot += robotOffset;
    target.connect(std::move(connection));
  }
}

}  // namespace

WorldSession WorldSession::load(const fs::path& file, const LoadOptions& options,
                                std::shared_ptr<ModelCache> cache) {
  WorldSession session;
  if (cache) session.cache = std::move(cache);
  session.world = loadAnyFile(file, options, session.cache.get());
  session.file = file;
  return session;
}

// Files are held by absolute path, so that a world saved elsewhere names them correctly
// (relative to its own folder when they lie below it, else absolute).
int WorldSession::addBody(const fs::path& file, BodyKind kind, const Transform& pose) {
  Body body;
  body.model = loadBodyFile(fs::absolute(file), cache.get());
  body.kind = kind;
  body.setPose(pose);
  return world.addBody(std::move(body));
}

int WorldSession::addRobot(const fs::path& file, const LoadOptions& options,
                           const Transform& pose) {
  const fs::path absolute = fs::absolute(file);
  Robot robot(loadRobotFile(absolute, options, cache.get()));
  const int index = world.addRobot(std::move(robot), absolute);
  world.setRobotPose(index, pose);
  return index;
}

std::pair<int, int> WorldSession::addFile(const fs::path& file, const LoadOptions& options) {
  World added = loadAnyFile(file, options, cache.get());
  // Merged into a copy, so that a failure half way leaves the world as it was.
  World merged = world.clone();
  const std::pair<int, int> first{static_cast<int>(merged.bodies().size()), merged.robotCount()};
  mergeInto(merged, std::move(added));
  world = std::move(merged);
  return first;
}

void WorldSession::removeBody(int index) {
  world.removeBody(index);
  removedBodies.push_back(index);
}

bool WorldSession::followRemovals(int& index, std::size_t& seen) const {
  for (; seen < removedBodies.size(); ++seen) {
    const int gone = removedBodies[seen];
    if (index == gone) return false;
    if (index > gone) --index;
  }
  return true;
}

void WorldSession::save(const fs::path& target) {
  saveWorldFile(world, target);  // model paths written so that the file loads from anywhere
  file = target;
}

WorldSession WorldSession::clone() const {
  return WorldSession{world.clone(), file, cache, {}};
}

}  // namespace graspkit::host
