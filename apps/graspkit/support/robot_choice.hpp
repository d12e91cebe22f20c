#pragma once
// Which robot and which body a command works on: the host layer chooses (graspkit/host/
// subject.hpp), and the errors name the flag.

#include <string>

#include "graspkit/model/body_ref.hpp"

namespace graspkit {
class World;
}

namespace graspkit::cli {

// --robot: a robot's name or 0-based index; the world's first hand when empty. Throws
// graspkit::Error naming --robot and the world's robots.
int chooseHand(const World& world, const std::string& robot);
// --object: a body's name; the world's first graspable body when empty.
BodyRef chooseObject(const World& world, const std::string& object);

}  // namespace graspkit::cli
