#pragma once
// One handle for every rigid piece of a world that has geometry: a free body (obstacle or
// graspable), a robot link or base, or the mount piece of a connection. Collision, contacts,
// rays and grasps all speak of bodies through BodyRef, so none of them cares which it is.

#include <compare>
#include <optional>
#include <string>
#include <vector>

#include "graspkit/math/transform.hpp"
#include "graspkit/model/body.hpp"
#include "graspkit/model/link.hpp"

namespace graspkit {

class World;

struct BodyRef {
  enum class Kind { Body, Link, Mount };
  Kind kind = Kind::Body;
  int index = 0;  // body index, robot index (links) or connection index (mounts)
  LinkRef link;   // Kind::Link only: the link of robot `index`; {-1, -1} is the base

  static BodyRef body(int body_index) { return {Kind::Body, body_index, {}}; }
  static BodyRef robotLink(int robot, LinkRef link) { return {Kind::Link, robot, link}; }
  static BodyRef robotBase(int robot) { return {Kind::Link, robot, {}}; }
  static BodyRef mount(int connection) { return {Kind::Mount, connection, {}}; }

  bool isLink() const { return kind == Kind::Link; }
  friend bool operator==(const BodyRef& a, const BodyRef& b) {
    return a.kind == b.kind && a.index == b.index && a.link == b.link;
  }
  friend auto operator<=>(const BodyRef& a, const BodyRef& b) {
    if (auto c = a.kind <=> b.kind; c != 0) return c;
    if (auto c = a.index <=> b.index; c != 0) return c;
    if (auto c = a.link.chain <=> b.link.chain; c != 0) return c;
    return a.link.link <=> b.link.link;
  }
};

// Each throws graspkit::Error when `ref` names nothing in `world`.
const BodyModel& bodyModel(const World& world, const BodyRef& ref);
Transform bodyPose(const World& world, const BodyRef& ref);
// Body names; link names <robot>_chain<c>_link<l> and <robot>_palm for the base, as GraspIt!
// names them; "<child robot>_mount" for mount pieces.
std::string bodyName(const World& world, const BodyRef& ref);
bool isValid(const World& world, const BodyRef& ref);

// The solid named `name` (bodyName's names: a body, "<robot>_palm", "<robot>_chain<c>_link<l>",
// "<child robot>_mount"); nullopt when none has it.
std::optional<BodyRef> findBodyRef(const World& world, const std::string& name);

// Every body of the world with a mesh, in a stable order: free bodies, then each robot's base
// and links chain by chain, then mount pieces.
std::vector<BodyRef> worldBodies(const World& world);

// One of worldBodies() with its model and pose, found in one walk of the world.
struct PlacedBody {
  BodyRef ref;
  const BodyModel* model = nullptr;  // never null; owned by the world
  Transform pose;
};

// worldBodies(), each with its model and pose, into `out` (cleared first). Queries that place
// every body at each call (a collision report at each step of a close) take this walk instead of
// looking each ref up again, and keep `out` between calls so that a call allocates nothing.
void placeWorldBodies(const World& world, std::vector<PlacedBody>& out);

}  // namespace graspkit
