#include "support/robot_choice.hpp"

#include <charconv>
#include <string>
#include <system_error>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "graspkit/base/error.hpp"
#include "graspkit/model/world.hpp"

namespace graspkit::cli {

int robotByNameOrIndex(const World& world, const std::string& robot) {
  if (const auto found = world.findRobot(robot)) return *found;
  std::vector<std::string> names;
  for (int r = 0; r < world.robotCount(); ++r) names.push_back(world.robot(r).name());
  const std::string known = names.empty() ? "the world has no robot"
                                          : fmt::format("its robots are {} (0-based: 0..{})",
                                                        fmt::join(names, ", "), names.size() - 1);
  int index = -1;
  const auto [end, ec] = std::from_chars(robot.data(), robot.data() + robot.size(), index);
  if (ec != std::errc{} || end != robot.data() + robot.size())
    throw Error(fmt::format("--robot '{}': no robot of that name; {}", robot, known));
  if (index < 0 || index >= world.robotCount())
    throw Error(fmt::format("--robot {}: no robot with that index; {}", robot, known));
  return index;
}

int chooseHand(const World& world, const std::string& robot) {
  if (!robot.empty()) return robotByNameOrIndex(world, robot);
  if (const auto hand = world.firstHand()) return *hand;
  throw Error(world.robotCount() == 0
                  ? "the world has no robot to grasp with"
                  : "no robot of the world is a hand; name the one to use with --robot");
}

}  // namespace graspkit::cli
