#pragma once
// Which hand and which object a request works on. Every front end (the graspkit program, Lua,
// Python, the C ABI) asks here, so that "the hand" and "the object" mean the same everywhere:
// the world's first hand, as GraspIt! picks its current hand when a world loads, and its first
// graspable body.

#include <string_view>

#include "graspkit/model/body_ref.hpp"

namespace graspkit {
class World;
}

namespace graspkit::host {

// The world's first hand. Throws graspkit::Error when the world has no robot, or none is a hand.
int defaultHand(const World& world);
// The world's first graspable body. Throws graspkit::Error when there is none.
BodyRef defaultObject(const World& world);

// A robot by its name or its 0-based index (as the JSON lists robots and the C ABI counts them;
// Lua counts from 1 and converts first); empty: defaultHand. Throws graspkit::Error naming the
// world's robots when there is no such robot.
int handNamed(const World& world, std::string_view robot);
// A free body by name; empty: defaultObject. Throws graspkit::Error naming the world's bodies.
BodyRef objectNamed(const World& world, std::string_view object);

}  // namespace graspkit::host
