#pragma once
// simann's any-time mode ("restarts", the default of `graspkit plan`): many short, independent
// annealing searches, each closing and measuring its own best states, feeding one list of
// distinct grasps (DistinctGrasps).
//
// Restart i is a pure function of the request and i: its own random stream (chainSeed(seed,
// i)), its own start (a pose around the object, see below), SEARCH steps of annealing on the
// search energy, then each of its SEEDS best states refined by REFINE steps of annealing on
// refine-energy (none by default) and closed with autograsp. Restart 0 also closes the hand
// where the request starts it, so a plan never does worse than the hand as the user placed it. A
// budget is a number of restarts (a step budget buys ceil(steps / cost()) of them; a time budget as
// many as fit), restarts are shared out among the threads, and their grasps are merged in restart
// order, so:
//   - the result depends on the seed and the number of restarts, not on the thread count;
//   - a larger budget runs the same restarts and more, and DistinctGrasps never loses a
//     force-closure grasp to a newcomer: more budget never gives fewer force-closure grasps;
//   - every stage is inside the budget: a time budget stops the restarts under way (they are
//     dropped) and returns.
//
// Why restarts: a single GraspIt! schedule cools for its whole budget and freezes wherever it
// is; measured on plannerMug, short searches find far more force-closure grasps per second
// than long ones.
//
// Starts ("start" option): "around" (default) puts the hand's approach frame on a random point
// of a sphere around the object's centre of gravity, facing the centre, with a random roll and
// the world's posture; "random" draws every variable uniformly in its range (both draw again, up
// to 20 times, while the hand collides there); "world" starts each
// restart where the world has the hand (GraspIt!'s start).

#include <algorithm>
#include <memory>
#include <string>

#include "annealing_chain.hpp"
#include "graspkit/planning/centred_close.hpp"
#include "graspkit/planning/planner.hpp"

namespace graspkit::simann {

enum class RestartStart { Around, Random, World };

struct RestartSettings {
  ChainSettings search;  // each restart's chain; its bestListSize is the seeds it closes
  std::int64_t searchSteps = 600;
  ChainSettings refine;
  std::string refineEnergy = "autograsp-quality";
  std::int64_t refineSteps = 0;
  RestartStart start = RestartStart::Around;
  double threshold = 0.2;  // distinct final grasps (GraspIt!'s best-list distance)
  // Each grasp closes with a compliant wrist (centred_close.hpp): up to this many moves of the
  // open hand towards a finger that closed on nothing.
  CentringSettings centring;

  // Each restart passes through the whole of GraspIt!'s schedule length (40000 steps from K0,
  // hot to frozen) in its searchSteps, unless "stride" sets how far one step advances it.
  long stride = 0;  // 0: 40000 / searchSteps
  long scheduleStride() const {
    return stride > 0
               ? stride
               : std::max<long>(1, kGraspItScheduleSteps / std::max<std::int64_t>(1, searchSteps));
  }
  static constexpr long kGraspItScheduleSteps = 40000;

  // The steps one restart counts for: its search, its refinements, and one per close it may
  // take (the first and each centring move), whether or not it takes them.
  std::int64_t cost() const {
    return searchSteps +
           static_cast<std::int64_t>(search.bestListSize) * (refineSteps + 1 + centring.moves);
  }
};

std::unique_ptr<Planner> makeRestartPlanner(const PlanningRequest& request,
                                            const RestartSettings& settings);

}  // namespace graspkit::simann
