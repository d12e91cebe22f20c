#pragma once
// The simulated-annealing planner, in two modes (option "mode"):
//
//   anneal      GraspIt!'s search (the default): one annealing chain per thread, each on its
//               own clone of the world, their best lists merged under GraspIt!'s distance rule
//   restarts    many short searches, each closing and measuring its best states, feeding one
//               list of distinct grasps: any-time, thread-count independent (restart_planner.hpp)
//
// Options (all optional): preset (DEFAULT, LOOP, MODIFIED, STRICT or ONLINE), threshold (the
// distance rule, GraspIt!'s 0.2), collision-order (lazy, the default: for cheap energies, check
// collisions only on neighbours the Metropolis test accepts; graspit: every neighbour first);
// for restarts also restart-steps, restart-grasps, stride, start, refine-steps, refine-preset,
// refine-energy and refine-jump (see restart_planner.hpp and plugins/planners/README.md).

#include <memory>

#include "graspkit/planning/planner.hpp"

namespace graspkit::simann {

std::unique_ptr<Planner> makeSimAnnPlanner(const PlanningRequest& request);

}  // namespace graspkit::simann
