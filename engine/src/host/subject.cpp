#include "graspkit/host/subject.hpp"

#include <charconv>
#include <string>
#include <system_error>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "graspkit/base/error.hpp"
#include "graspkit/model/world.hpp"

namespace graspkit::host {

int defaultHand(const World& world) {
  if (const auto hand = world.firstHand()) return *hand;
  throw Error(world.robotCount() == 0
                  ? "the world has no hand (it has no robot)"
                  : "the world has no hand: none of its robots is one; name the robot to use");
}

BodyRef defaultObject(const World& world) {
  if (const auto body = world.firstGraspable()) return BodyRef::body(*body);
  throw Error("the world has no graspable body; name the body to grasp");
}

int handNamed(const World& world, std::string_view robot) {
  if (robot.empty()) return defaultHand(world);
  if (const auto found = world.findRobot(std::string(robot))) return *found;
  std::vector<std::string> names;
  for (int r = 0; r < world.robotCount(); ++r) names.push_back(world.robot(r).name());
  const std::string known = names.empty() ? "the world has no robot"
                                          : fmt::format("its robots are {} (0-based: 0..{})",
                                                        fmt::join(names, ", "), names.size() - 1);
  int index = -1;
  const auto [end, ec] = std::from_chars(robot.data(), robot.data() + robot.size(), index);
  if (ec != std::errc{} || end != robot.data() + robot.size())
    throw Error(fmt::format("'{}': no robot of that name; {}", robot, known));
  if (index < 0 || index >= world.robotCount())
    throw Error(fmt::format("{}: no robot with that index; {}", robot, known));
  return index;
}

BodyRef objectNamed(const World& world, std::string_view object) {
  if (object.empty()) return defaultObject(world);
  if (const Body* found = world.findBody(std::string(object)))
    return BodyRef::body(static_cast<int>(found - world.bodies().data()));
  std::vector<std::string> names;
  for (const Body& b : world.bodies()) names.push_back(b.name);
  throw Error(fmt::format("'{}': no body of that name in the world (bodies: {})", object,
                          names.empty() ? "none" : fmt::format("{}", fmt::join(names, ", "))));
}

}  // namespace graspkit::host
