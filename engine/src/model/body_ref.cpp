#include "graspkit/model/body_ref.hpp"

#include <fmt/format.h>

#include "graspkit/base/error.hpp"
#include "graspkit/model/world.hpp"

namespace graspkit {
namespace {

const Link* findLink(const RobotModel& model, const LinkRef& link) {
  if (link.chain < 0 || link.chain >= static_cast<int>(model.chains.size())) return nullptr;
  const auto& links = model.chains[link.chain].links;
  if (link.link < 0 || link.link >= static_cast<int>(links.size())) return nullptr;
  return &links[link.link];
}

[[noreturn]] void throwInvalid(const BodyRef& ref) {
  static constexpr const char* kKinds[] = {"body", "link of robot", "mount of connection"};
  throw Error(fmt::format("no {} {} (chain {}, link {}) in the world",
                          kKinds[static_cast<int>(ref.kind)], ref.index, ref.link.chain,
                          ref.link.link));
}

}  // namespace

bool isValid(const World& world, const BodyRef& ref) {
  switch (ref.kind) {
    case BodyRef::Kind::Body:
      return ref.index >= 0 && ref.index < static_cast<int>(world.bodies().size()) &&
             world.bodies()[ref.index].model;
    case BodyRef::Kind::Link: {
      if (ref.index < 0 || ref.index >= world.robotCount()) return false;
      const RobotModel& model = world.robot(ref.index).model();
      if (ref.link.isBase()) return ref.link.link < 0 && model.palm != nullptr;
      const Link* link = findLink(model, ref.link);
      return link && link->body;
    }
    case BodyRef::Kind::Mount:
      return ref.index >= 0 && ref.index < static_cast<int>(world.connections().size()) &&
             world.connections()[ref.index].mount;
  }
  return false;
}

const BodyModel& bodyModel(const World& world, const BodyRef& ref) {
  if (!isValid(world, ref)) throwInvalid(ref);
  switch (ref.kind) {
    case BodyRef::Kind::Body:
      return *world.bodies()[ref.index].model;
    case BodyRef::Kind::Link: {
      const RobotModel& model = world.robot(ref.index).model();
      return ref.link.isBase() ? *model.palm : *findLink(model, ref.link)->body;
    }
    case BodyRef::Kind::Mount:
      break;
  }
  return *world.connections()[ref.index].mount;
}

Transform bodyPose(const World& world, const BodyRef& ref) {
  if (!isValid(world, ref)) throwInvalid(ref);
  switch (ref.kind) {
    case BodyRef::Kind::Body:
      return world.bodies()[ref.index].pose;
    case BodyRef::Kind::Link: {
      const Robot& robot = world.robot(ref.index);
      return ref.link.isBase() ? robot.pose() : robot.linkPose(ref.link);
    }
    case BodyRef::Kind::Mount:
      break;
  }
  return world.mountPose(world.connections()[ref.index]);
}

std::string bodyName(const World& world, const BodyRef& ref) {
  if (!isValid(world, ref)) throwInvalid(ref);
  switch (ref.kind) {
    case BodyRef::Kind::Body:
      return world.bodies()[ref.index].name;
    case BodyRef::Kind::Link: {
      const RobotModel& model = world.robot(ref.index).model();
      return ref.link.isBase() ? model.name + "_palm" : findLink(model, ref.link)->name;
    }
    case BodyRef::Kind::Mount:
      break;
  }
  return world.robot(world.connections()[ref.index].childRobot).name() + "_mount";
}

void placeWorldBodies(const World& world, std::vector<PlacedBody>& out) {
  out.clear();
  auto add = [&](const BodyRef& ref, const BodyModel* model, const Transform& pose) {
    if (model && model->mesh) out.push_back({ref, model, pose});
  };
  const auto& bodies = world.bodies();
  for (int b = 0; b < static_cast<int>(bodies.size()); ++b)
    add(BodyRef::body(b), bodies[b].model.get(), bodies[b].pose);
  for (int r = 0; r < world.robotCount(); ++r) {
    const Robot& robot = world.robot(r);
    const RobotModel& model = robot.model();
    add(BodyRef::robotBase(r), model.palm.get(), robot.pose());
    for (int c = 0; c < static_cast<int>(model.chains.size()); ++c) {
      const auto& links = model.chains[c].links;
      for (int l = 0; l < static_cast<int>(links.size()); ++l)
        add(BodyRef::robotLink(r, {c, l}), links[l].body.get(), robot.linkPose({c, l}));
    }
  }
  const auto& connections = world.connections();
  for (int m = 0; m < static_cast<int>(connections.size()); ++m)
    if (const BodyModel* mount = connections[m].mount.get())
      add(BodyRef::mount(m), mount, world.mountPose(connections[m]));
}

std::vector<BodyRef> worldBodies(const World& world) {
  std::vector<PlacedBody> placed;
  placeWorldBodies(world, placed);
  std::vector<BodyRef> refs;
  refs.reserve(placed.size());
  for (const PlacedBody& body : placed) refs.push_back(body.ref);
  return refs;
}

std::optional<BodyRef> findBodyRef(const World& world, const std::string& name) {
  // Free bodies first, by their own names (the common case, no string building).
  const auto& bodies = world.bodies();
  for (std::size_t i = 0; i < bodies.size(); ++i)
    if (bodies[i].name == name) return BodyRef::body(static_cast<int>(i));
  for (const BodyRef& ref : worldBodies(world))
    if (ref.kind != BodyRef::Kind::Body && bodyName(world, ref) == name) return ref;
  return std::nullopt;
}

}  // namespace graspkit
