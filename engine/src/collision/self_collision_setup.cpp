#include "graspkit/collision/self_collision_setup.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <memory>
#include <random>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "graspkit/collision/collision.hpp"
#include "graspkit/model/world.hpp"

namespace graspkit {

namespace {

using LinkPair = std::pair<std::pair<int, int>, std::pair<int, int>>;  // (chain, link) twice

LinkPair key(const LinkRef& a, const LinkRef& b) {
  std::pair<int, int> x{a.chain, a.link}, y{b.chain, b.link};
  if (y < x) std::swap(x, y);
  return {x, y};
}

// The robot's own link pairs that collide in `world` (robot 0) at its current DOF values.
std::set<LinkPair> collidingLinks(const World& world) {
  std::set<LinkPair> out;
  for (const CollidingPair& p : collisionReport(world))
    if (p.first.isLink() && p.second.isLink()) out.insert(key(p.first.link, p.second.link));
  return out;
}

}  // namespace

int disableInherentSelfCollisions(RobotModel& robot, const SelfCollisionSetup& setup) {
  if (robot.dofs.empty()) return 0;
  World world;
  world.addRobot(Robot(std::make_shared<const RobotModel>(robot)));
  std::vector<double> values;
  for (const Dof& dof : robot.dofs) values.push_back(dof.defaultValue);
  world.setDofValues(0, values);
  const std::set<LinkPair> at_rest = collidingLinks(world);
  std::map<LinkPair, int> counts;  // samples each pair collides in
  std::mt19937 random(setup.seed);
  for (int s = 0; s < setup.samples; ++s) {
    for (std::size_t d = 0; d < robot.dofs.size(); ++d) {
      const Dof& dof = robot.dofs[d];
      values[d] = dof.min < dof.max
                      ? std::uniform_real_distribution<double>(dof.min, dof.max)(random)
                      : dof.min;
    }
    world.setDofValues(0, values);
    for (const LinkPair& p : collidingLinks(world)) ++counts[p];
  }
  int added = 0;
  for (const auto& [p, count] : counts) {
    std::string reason;
    if (count == setup.samples) {
      reason = fmt::format("always in collision ({} of {} postures)", count, setup.samples);
    } else if (at_rest.count(p) && 2 * count >= setup.samples) {
      // Overlapping meshes at a joint: a pair that meets only near rest (two fingertips
      // touching at the zero posture) stays checked.
      reason = fmt::format("in collision at rest and in {} of {} postures", count, setup.samples);
    } else {
      continue;
    }
    robot.disabledCollisions.push_back(
        {LinkRef{p.first.first, p.first.second}, LinkRef{p.second.first, p.second.second}, reason});
    ++added;
  }
  return added;
}

}  // namespace graspkit
