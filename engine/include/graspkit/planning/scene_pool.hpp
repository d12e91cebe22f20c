#pragma once
// One PlanningScene (a clone of the request's world) and one SearchEnergy per worker thread,
// made when a worker first needs them and kept from run to run: what a planner searching on
// several threads needs, in-tree or in a plugin (as Pinocchio's ModelPool gives each thread its
// own Data). Work runs on the pool's workers through parallelFor (base/parallel_for.hpp).

#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "graspkit/base/parallel_for.hpp"
#include "graspkit/planning/planner.hpp"
#include "graspkit/planning/planning_scene.hpp"

namespace graspkit {

class ScenePool {
 public:
  // Makes worker 0's scene and energy now, so a bad request (no robot, an unknown energy) fails
  // here and not inside a worker.
  ScenePool(const PlanningRequest& request, std::shared_ptr<const SearchSpace> space);

  // The workers a run may use: the request's threads, but one for a custom energy (a Lua
  // function need not be thread-safe).
  int capacity() const { return capacity_; }
  // Scenes made so far.
  int size() const { return static_cast<int>(scenes_.size()); }
  PlanningScene& scene(int worker);
  // The same scene, for what keeps a scene alive beyond a call (an annealing chain).
  const std::shared_ptr<PlanningScene>& sharedScene(int worker);
  SearchEnergy& energy(int worker);
  const std::shared_ptr<const SearchSpace>& space() const { return space_; }

  // Runs job(worker, index) for every index in [begin, end) on up to capacity() workers, each
  // with its own scene and energy; stops taking items once keepGoing(worker) is false.
  void run(std::int64_t begin, std::int64_t end,
           const std::function<void(int worker, std::int64_t index)>& job,
           const std::function<bool(int worker)>& keepGoing = {});

 private:
  void grow(int count);

  PlanningRequest request_;
  std::shared_ptr<const SearchSpace> space_;
  int capacity_;
  std::vector<std::shared_ptr<PlanningScene>> scenes_;
  std::vector<std::unique_ptr<SearchEnergy>> energies_;
};

}  // namespace graspkit
