#include "graspkit/model/collision_filter.hpp"

#include <algorithm>
#include <string>

#include <fmt/format.h>

#include "graspkit/base/error.hpp"
#include "graspkit/model/world.hpp"

namespace graspkit {
namespace {

template <typename T>
void setMember(std::vector<T>& sorted, const T& value, bool present) {
  auto it = std::lower_bound(sorted.begin(), sorted.end(), value);
  const bool found = it != sorted.end() && *it == value;
  if (present && !found) sorted.insert(it, value);
  if (!present && found) sorted.erase(it);
}

template <typename T>
bool contains(const std::vector<T>& sorted, const T& value) {
  return std::binary_search(sorted.begin(), sorted.end(), value);
}

std::pair<BodyRef, BodyRef> ordered(const BodyRef& a, const BodyRef& b) {
  return a < b ? std::pair{a, b} : std::pair{b, a};
}

// The robot a body belongs to: its own for links, the child robot for a mount piece.
int owningRobot(const World& world, const BodyRef& ref) {
  switch (ref.kind) {
    case BodyRef::Kind::Link:
      return ref.index;
    case BodyRef::Kind::Mount:
      return world.connections()[ref.index].childRobot;
    case BodyRef::Kind::Body:
      break;
  }
  return -1;
}

const Link* linkOf(const World& world, const BodyRef& ref) {
  if (!ref.isLink() || ref.link.isBase()) return nullptr;
  return &world.robot(ref.index).model().chains[ref.link.chain].links[ref.link.link];
}

bool isLastLink(const World& world, const BodyRef& ref, int robot, int chain) {
  if (!ref.isLink() || ref.index != robot || ref.link.chain != chain) return false;
  const auto& links = world.robot(robot).model().chains[chain].links;
  return ref.link.link == static_cast<int>(links.size()) - 1;
}

// Rules between two bodies of one robot.
bool sameRobotAllows(const RobotModel& model, const LinkRef& a, const LinkRef& b) {
  if (!a.isBase() && !b.isBase() && a.chain == b.chain) return false;  // one chain
  if (a.isBase() && b.link == 0) return false;  // base and a chain's first link
  if (b.isBase() && a.link == 0) return false;
  auto overlaps = [&](const LinkRef& from, const LinkRef& to) {
    if (from.isBase()) return false;
    const Link& link = model.chains[from.chain].links[from.link];
    if (link.collisionRule != CollisionRule::OverlappingPair || !link.overlapTarget) return false;
    const LinkRef& target = *link.overlapTarget;
    return target.isBase() ? to.isBase() : target == to;
  };
  if (overlaps(a, b) || overlaps(b, a)) return false;
  auto same = [](const LinkRef& x, const LinkRef& y) {
    return x.isBase() ? y.isBase() : x == y;  // chain -1 means the base whatever the link
  };
  for (const CollisionPair& pair : model.disabledCollisions) {
    if ((same(pair.first, a) && same(pair.second, b)) ||
        (same(pair.first, b) && same(pair.second, a)))
      return false;
  }
  return true;
}

// Rules of one connection for the pair (a, b), in either order.
bool connectionAllows(const World& world, const Connection& c, int mount_index, const BodyRef& a,
                      const BodyRef& b) {
  const BodyRef mount = BodyRef::mount(mount_index);
  const BodyRef child_base = BodyRef::robotBase(c.childRobot);
  auto parent_end = [&](const BodyRef& x) {
    return isLastLink(world, x, c.parentRobot, c.parentChain);
  };
  for (const auto& [x, y] : {std::pair{a, b}, std::pair{b, a}}) {
    if (x == mount && (y == child_base || parent_end(y))) return false;
    if (x == child_base && parent_end(y)) return false;
  }
  return true;
}

std::string describe(const BodyRef& ref) {
  switch (ref.kind) {
    case BodyRef::Kind::Body:
      return fmt::format("body {}", ref.index);
    case BodyRef::Kind::Link:
      return fmt::format("robot {} chain {} link {}", ref.index, ref.link.chain, ref.link.link);
    case BodyRef::Kind::Mount:
      break;
  }
  return fmt::format("the mount piece of connection {}", ref.index);
}

}  // namespace

void CollisionFilter::setBodyEnabled(const BodyRef& body, bool enabled) {
  setMember(disabled_bodies_, body, !enabled);
}

void CollisionFilter::setPairEnabled(const BodyRef& a, const BodyRef& b, bool enabled) {
  setMember(disabled_pairs_, ordered(a, b), !enabled);
}

void CollisionFilter::setRobotEnabled(int robot, bool enabled) {
  setMember(disabled_robots_, robot, !enabled);
}

void CollisionFilter::bodyRemoved(int index) {
  auto gone = [index](const BodyRef& r) {
    return r.kind == BodyRef::Kind::Body && r.index == index;
  };
  auto renumber = [index](BodyRef r) {
    if (r.kind == BodyRef::Kind::Body && r.index > index) --r.index;
    return r;
  };
  std::vector<BodyRef> bodies;
  for (const BodyRef& r : disabled_bodies_)
    if (!gone(r)) bodies.push_back(renumber(r));
  std::vector<std::pair<BodyRef, BodyRef>> pairs;
  for (const auto& [a, b] : disabled_pairs_)
    if (!gone(a) && !gone(b)) pairs.push_back(ordered(renumber(a), renumber(b)));
  std::sort(bodies.begin(), bodies.end());  // renumbering keeps the order; sorted to be sure
  std::sort(pairs.begin(), pairs.end());
  disabled_bodies_ = std::move(bodies);
  disabled_pairs_ = std::move(pairs);
}

bool CollisionFilter::bodyEnabled(const BodyRef& body) const {
  return !contains(disabled_bodies_, body);
}

bool CollisionFilter::pairEnabled(const BodyRef& a, const BodyRef& b) const {
  return !contains(disabled_pairs_, ordered(a, b));
}

bool CollisionFilter::robotEnabled(int robot) const {
  return !contains(disabled_robots_, robot);
}

bool robotRulesAllow(const World& world, const BodyRef& a, const BodyRef& b) {
  const Link* link_a = linkOf(world, a);
  const Link* link_b = linkOf(world, b);
  if (link_a && link_a->collisionRule == CollisionRule::Off) return false;
  if (link_b && link_b->collisionRule == CollisionRule::Off) return false;
  if (a.isLink() && b.isLink() && a.index == b.index &&
      !sameRobotAllows(world.robot(a.index).model(), a.link, b.link))
    return false;
  if (a.kind == BodyRef::Kind::Body || b.kind == BodyRef::Kind::Body) return true;
  const auto& connections = world.connections();
  for (int c = 0; c < static_cast<int>(connections.size()); ++c)
    if (!connectionAllows(world, connections[c], c, a, b)) return false;
  return true;
}

bool CollisionFilter::isActive(const World& world, const BodyRef& a, const BodyRef& b) const {
  for (const BodyRef* ref : {&a, &b}) {
    if (!isValid(world, *ref)) {
      throw Error(fmt::format("collision filter: {} is not in the world", describe(*ref)));
    }
  }
  if (a == b) return false;
  if (!disabled_bodies_.empty() && (!bodyEnabled(a) || !bodyEnabled(b))) return false;
  if (!disabled_pairs_.empty() && !pairEnabled(a, b)) return false;
  if (!disabled_robots_.empty()) {
    const int ra = owningRobot(world, a), rb = owningRobot(world, b);
    if ((ra >= 0 && !robotEnabled(ra)) || (rb >= 0 && !robotEnabled(rb))) return false;
  }
  if (!static_pairs_ && a.kind == BodyRef::Kind::Body && b.kind == BodyRef::Kind::Body &&
      !world.bodies()[a.index].isDynamic() && !world.bodies()[b.index].isDynamic())
    return false;
  return robotRulesAllow(world, a, b);
}

}  // namespace graspkit
