#pragma once
// Which robot a command works on.

#include <string>

namespace graspkit {
class World;
}

namespace graspkit::cli {

// --robot names a robot by its name or its 0-based index (as the JSON lists robots and the C ABI
// counts them; Lua counts from 1, as Lua does). Throws graspkit::Error naming the world's robots
// when there is no such robot.
int robotByNameOrIndex(const World& world, const std::string& robot);
// The robot grasp and plan work on: --robot when given, else the world's first hand, as
// GraspIt! picks its current hand. Throws graspkit::Error when there is none.
int chooseHand(const World& world, const std::string& robot);

}  // namespace graspkit::cli
