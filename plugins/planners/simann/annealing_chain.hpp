#pragma once
// One simulated-annealing search (GraspIt!'s SimAnn with SimAnnPlanner's main loop) on its own
// PlanningScene: draw a neighbour of the current state until a legal one is found (up to 11
// tries), evaluate it, move there by the Metropolis rule, and offer accepted states to the
// chain's best list.

#include <cstdint>
#include <functional>
#include <memory>
#include <random>

#include "annealing_schedule.hpp"
#include "graspkit/planning/best_list.hpp"
#include "graspkit/planning/planning_scene.hpp"
#include "graspkit/planning/search_energy.hpp"

namespace graspkit::simann {

struct ChainSettings {
  AnnealingParameters parameters = kPresets[0];
  int bestListSize = 20;
  double distanceThreshold = 0.2;  // GraspIt!'s best-list neighbourhood
  double jumpScale = 1.0;          // multiplies every variable's largest jump
  // GraspIt! checks a neighbour for collisions before evaluating it. For a cheap energy
  // (SearchEnergy::expensive() false) the chain may instead evaluate first and check only the
  // neighbours the Metropolis test would move to; rejected neighbours then cost no collision
  // check. Off: GraspIt!'s order for every energy.
  bool checkCollisionsLast = true;
  // How far the schedule advances per step: 1 is GraspIt!'s; simann's restarts pass the whole
  // schedule (steps K0 .. K0 + 40000) in their few hundred steps.
  long scheduleStride = 1;
};

class AnnealingChain {
 public:
  // The scene may be shared with other work of the same thread (simann's restarts run one
  // chain after another in one scene); the chain places the hand on every step.
  AnnealingChain(std::shared_ptr<PlanningScene> scene, std::unique_ptr<SearchEnergy> energy,
                 const ChainSettings& settings, std::uint64_t seed, SearchState start);

  // One annealing step. Returns false when no legal neighbour was found in 11 tries
  // (GraspIt!'s FAIL): the step is counted, so budgets end, but the schedule does not advance.
  bool step();
  // Steps until `target` steps have been taken.
  void runTo(std::int64_t target);
  // The same, asking `keepGoing` before each step; returns false when it said stop.
  bool runTo(std::int64_t target, const std::function<bool()>& keepGoing);

  std::int64_t steps() const { return steps_; }
  const SearchState& current() const { return current_; }
  const BestList& best() const { return best_; }
  PlanningScene& scene() { return *scene_; }

 private:
  double uniform();
  std::vector<double> neighbour(double t);
  bool stepCheckingFirst(double tNeighbour, double tAccept);
  bool stepCheckingLast(double tNeighbour, double tAccept);
  void moveTo(std::vector<double> values, double energy);

  std::shared_ptr<PlanningScene> scene_;
  std::unique_ptr<SearchEnergy> energy_;
  ChainSettings settings_;
  std::mt19937_64 random_;
  SearchState current_;
  BestList best_;
  long schedule_step_;
  std::int64_t steps_ = 0;
};

// A seed for chain `index` of a search seeded with `seed` (splitmix64, so neighbouring seeds
// give unrelated streams).
std::uint64_t chainSeed(std::uint64_t seed, int index);

}  // namespace graspkit::simann
