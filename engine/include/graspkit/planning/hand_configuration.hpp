#pragma once
// Everything that says where a hand is and how it is shaped: its base pose, its DOF values and
// the breakaway state of its joints (which joints stopped following their DOF during a close,
// and where). A grasp's closed hand is one of these; putting it back into a world reproduces
// the grasp exactly, where the DOF values alone would not (a broken-away Barrett finger).

#include <vector>

#include "graspkit/math/transform.hpp"
#include "graspkit/model/robot.hpp"

namespace graspkit {

class World;

struct HandConfiguration {
  Transform pose = Transform::Identity();
  std::vector<double> dofs;
  std::vector<BreakawayState> breakaway;  // one per joint, robot-wide order
};

// The configuration robot `robot` of `world` has now.
HandConfiguration handConfigurationOf(const World& world, int robot);
// Puts robot `robot` of `world` into `configuration` (DOFs applied as given, no clamping: they
// came from the same robot). Throws graspkit::Error when the sizes do not match the robot.
void applyHandConfiguration(World& world, int robot, const HandConfiguration& configuration);

}  // namespace graspkit
