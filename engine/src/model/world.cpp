#include "graspkit/model/world.hpp"

#include <fmt/format.h>

#include "graspkit/base/error.hpp"

namespace graspkit {

const Body* World::findBody(const std::string& name) const {
  for (const Body& body : bodies_)
    if (body.name == name) return &body;
  return nullptr;
}

const Robot& World::robot(int index) const {
  return worldRobot(index).robot;
}

const WorldRobot& World::worldRobot(int index) const {
  if (index < 0 || index >= robotCount()) {
    throw Error(fmt::format("the world has {} robots, robot {} requested", robotCount(), index));
  }
  return robots_[index];
}

Robot& World::mutableRobot(int index) {
  worldRobot(index);  // range check
  return robots_[index].robot;
}

std::optional<int> World::findRobot(const std::string& name) const {
  for (int i = 0; i < robotCount(); ++i)
    if (robots_[i].robot.name() == name) return i;
  return std::nullopt;
}

std::optional<int> World::firstHand() const {
  for (int i = 0; i < robotCount(); ++i)
    if (robots_[i].robot.model().isHand) return i;
  return std::nullopt;
}

std::optional<int> World::firstGraspable() const {
  for (int i = 0; i < static_cast<int>(bodies_.size()); ++i)
    if (bodies_[i].isDynamic()) return i;
  return std::nullopt;
}

int World::addBody(Body body) {
  if (body.name.empty() && body.model) body.name = body.model->name;
  // GraspIt! names bodies after their files; two copies of one file get a numbered suffix.
  if (findBody(body.name)) {
    const std::string base = body.name;
    int& n = next_suffix_.try_emplace(base, 2).first->second;
    do {
      body.name = fmt::format("{}_{}", base, n++);
    } while (findBody(body.name));
  }
  bodies_.push_back(std::move(body));
  return static_cast<int>(bodies_.size()) - 1;
}

void World::removeBody(int index) {
  if (index < 0 || index >= static_cast<int>(bodies_.size()))
    throw Error(fmt::format("body {} requested, the world has {}", index, bodies_.size()));
  bodies_.erase(bodies_.begin() + index);
  collision_filter_.bodyRemoved(index);
}

int World::addRobot(Robot robot, std::filesystem::path filename) {
  robots_.push_back(WorldRobot{std::move(robot), std::move(filename)});
  return robotCount() - 1;
}

void World::connect(Connection connection) {
  const Robot& parent = worldRobot(connection.parentRobot).robot;
  worldRobot(connection.childRobot);
  const int chains = static_cast<int>(parent.model().chains.size());
  if (connection.parentChain < 0 || connection.parentChain >= chains) {
    throw Error(fmt::format("robot '{}' has {} chains, connection names chain {}", parent.name(),
                            chains, connection.parentChain));
  }
  if (connection.childRobot == connection.parentRobot) {
    throw Error("a robot cannot be mounted on itself");
  }
  for (const Connection& existing : connections_) {
    if (existing.childRobot == connection.childRobot) {
      throw Error(fmt::format("robot {} is already mounted", connection.childRobot));
    }
  }
  // Walk up from the parent: reaching the child would close a cycle.
  for (int up = connection.parentRobot;;) {
    if (up == connection.childRobot) throw Error("connection would make a cycle of robots");
    auto it = std::find_if(connections_.begin(), connections_.end(),
                           [&](const Connection& c) { return c.childRobot == up; });
    if (it == connections_.end()) break;
    up = it->parentRobot;
  }
  connections_.push_back(std::move(connection));
  updateChildren(connections_.back().parentRobot);
}

void World::setRobotPose(int robot, const Transform& pose) {
  mutableRobot(robot).setPose(pose);
  updateChildren(robot);
}

void World::setBreakaway(int robot, int joint, BreakawayState state) {
  mutableRobot(robot).setBreakaway(joint, state);
  updateChildren(robot);
}

void World::releaseBreakawayNotLagging(int robot) {
  mutableRobot(robot).releaseBreakawayNotLagging();
  updateChildren(robot);
}

void World::setDofValues(int robot, std::span<const double> values, LimitPolicy policy) {
  mutableRobot(robot).setDofValues(values, policy);
  updateChildren(robot);
}

void World::setRobotPoseAndDofValues(int robot, const Transform& pose,
                                     std::span<const double> values, LimitPolicy policy) {
  mutableRobot(robot).setPoseAndDofValues(pose, values, policy);
  updateChildren(robot);
}

void World::setDofVelocities(int robot, std::span<const double> velocities) {
  mutableRobot(robot).setDofVelocities(velocities);
}

void World::setDofTargets(int robot, std::span<const double> targets) {
  mutableRobot(robot).setDofTargets(targets);
}

void World::setDofReferences(int robot, std::span<const double> references) {
  mutableRobot(robot).setDofReferences(references);
}

Transform World::mountPose(const Connection& connection) const {
  return robot(connection.parentRobot).chainEndPose(connection.parentChain) * connection.offset;
}

void World::updateChildren(int parent) {
  for (const Connection& connection : connections_) {
    if (connection.parentRobot != parent) continue;
    robots_[connection.childRobot].robot.setPose(mountPose(connection));
    updateChildren(connection.childRobot);
  }
}

}  // namespace graspkit
