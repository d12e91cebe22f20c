#pragma once
// Closing the hand with a compliant wrist.
//
// Autograsp stops a DOF when any link it drives touches the object. When several fingers share
// one DOF (a parallel-jaw gripper, the PR2 gripper), the first finger to touch stops them all:
// unless the hand was centred on the object to a fraction of a millimetre, the other finger
// stays clear and the grasp is not force closure. A real gripper gets there because its wrist or
// the object gives way. closeCentred() imitates that give: after the close, for each kinematic
// chain that touches nothing, it finds the chain's gap to the object (the FCL distance from its
// nearest link) and moves the open hand by half of it towards the object, then closes again.
// Where the hand's virtual contacts sit on some chains, only those count: the others are a
// linkage's inner bars, which close with the fingers but never reach the object.
// The moved grasp replaces the first only when betterGrasp() ranks it higher, so the rule never
// makes a grasp worse.

#include <functional>

#include "graspkit/planning/planner.hpp"

namespace graspkit {

class PlanningScene;

struct CentringSettings {
  int moves = 3;  // the most moves of the open hand (0: a plain finishGrasp)
  // Asked before each move and each step of a close; false stops there (a time budget running
  // out), leaving the grasp unevaluated when its first close was stopped.
  std::function<bool()> keepGoing;
  // How each close is measured (finishGrasp()). With CloseMeasure::Ranking, volumes stay
  // unknown except where a move is weighed against the grasp it would replace.
  CloseMeasure measure = CloseMeasure::GraspIt;
};

// finishGrasp(), then up to `settings.moves` centring moves while the grasp is not force
// closure and some chain touches nothing. The grasp's pose and values follow the accepted moves
// (the search space must be invertible: not the ellipsoid space, whose moves are skipped).
void closeCentred(PlanningScene& scene, PlannedGrasp& grasp, const CentringSettings& settings = {});

}  // namespace graspkit
