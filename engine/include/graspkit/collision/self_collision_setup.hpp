#pragma once
// Which link pairs of a published hand never need a collision check, decided when the hand is
// loaded, as MoveIt's setup assistant decides it for an SRDF. Published meshes overlap where
// links meet (a palm box through a thumb base, a linkage's bars), so without this every state
// of such a hand counts as a collision and no grasp is ever found.
//
// A pair is switched off (added to RobotModel::disabledCollisions, with its reason) when it is
//   - always in collision: at every one of `samples` DOF vectors drawn uniformly in the ranges;
//   - in collision at rest (the DOFs at their default values) and in at least half the samples:
//     meshes that overlap at a joint. A pair that meets only near rest (fingertips touching at
//     the zero posture) stays checked: the planner must not pass fingers through each other.
// Pairs the robot's own rules already exclude (one chain's links, the palm and each chain's first
// link, the file's own exclusions: SRDF <disable_collisions>, MJCF <contact><exclude>) are not
// looked at. GraspIt!'s robot files are never given to this: they keep GraspIt!'s rules exactly.

#include "graspkit/model/robot.hpp"

namespace graspkit {

struct SelfCollisionSetup {
  int samples = 64;          // random DOF vectors
  unsigned seed = 20261126;  // the same hand always gets the same pairs
};

// Returns how many pairs it switched off.
int disableInherentSelfCollisions(RobotModel& robot, const SelfCollisionSetup& setup = {});

}  // namespace graspkit
