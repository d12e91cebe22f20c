#pragma once
// The list planner (GraspIt!'s ListPlanner): evaluates a given list of hand states with the
// request's energy, one state per step, and ranks them by energy. The states are the request's
// `states` (values in its search space) followed by those of the option
//
//   file   a JSON file of hand poses and DOFs (hand_state_file.hpp)
//
// As in GraspIt!, an illegal state (the hand collides) is dropped, and so is a state whose
// energy is not below GraspIt!'s entry bar of 1e5 (e.g. strict-autograsp's 1e8 for "no grasp").
// The rest are kept best first, up to the request's best-list size, with no distance rule
// (equal energies keep their input order). done() once every state is evaluated.

#include <memory>

#include "graspkit/planning/planner.hpp"

namespace graspkit::list {

std::unique_ptr<Planner> makeListPlanner(const PlanningRequest& request);

}  // namespace graspkit::list
