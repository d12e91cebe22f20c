#pragma once
// A grasp: the contacts between a hand and one graspable body, and what they can do to it. The
// wrench space is built from the object-side mates of the hand's contacts (mounted robots'
// links included), about the object's centre of gravity, torques divided by its max radius.

#include <vector>

#include "graspkit/collision/contact.hpp"
#include "graspkit/grasp/wrench_space.hpp"

namespace graspkit {

class World;

struct GraspRequest {
  WrenchSpaceOptions wrenchSpace;  // L1 by default, GraspIt!'s qhull options
};

struct Grasp {
  int robot = 0;
  BodyRef object;
  std::vector<Contact> contacts;  // seen from the hand's links (normal into the link)
  GraspWrenchSpace wrenchSpace;
  double epsilon = -1.0;  // -1 without force closure or when the hull fails
  double volume = 0.0;    // 0 when the hull fails
  bool forceClosure = false;
};

// The hand's contacts with `object` as the world stands, then the wrench space and the built-in
// measures. Throws graspkit::Error for a bad robot index or an object that is not a body of the
// world.
Grasp analyzeGrasp(const World& world, int robot, const BodyRef& object,
                   const GraspRequest& request = {});

// The same for contacts already found (seen from the hand: their mates lie on the object).
Grasp analyzeGrasp(const World& world, int robot, const BodyRef& object,
                   std::vector<Contact> contacts, const GraspRequest& request = {});

}  // namespace graspkit
