#pragma once
// The simulated-annealing planner: one annealing chain per thread, each on its own clone of
// the world, their best lists merged under GraspIt!'s distance rule. Options (all optional):
//
//   preset      DEFAULT (GraspIt!'s), LOOP, MODIFIED, STRICT or ONLINE
//   mode        anneal (one search) or two-stage: the search (contact energy by default) seeds
//               a short refinement of each of its best states with refine-energy
//   threshold   the best list's distance rule (GraspIt!: 0.2)
//   collision-order
//               lazy (default): for cheap energies, check collisions only on neighbours the
//               Metropolis test accepts; graspit: check every neighbour first, as GraspIt! does
//   refine-steps, refine-preset, refine-energy, refine-jump
//               the refinement: steps per seed (40), its schedule (STRICT), its energy
//               (autograsp-quality) and the fraction of each variable's jump it uses (0.1)

#include <memory>

#include "graspkit/planning/planner.hpp"

namespace graspkit::simann {

std::unique_ptr<Planner> makeSimAnnPlanner(const PlanningRequest& request);

}  // namespace graspkit::simann
