#pragma once
// What the sampling planners (list, approach) share: a pool of workers, each with its own
// PlanningScene (a clone of the world) and its own energy, that evaluates independent samples
// on up to `threads` threads; and a ranked list that keeps the best states in energy order.
// Results are merged in sample order, so a run gives the same list however many threads it used.
// Header-only: each planner plugin compiles its own copy.

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <exception>
#include <memory>
#include <optional>
#include <span>
#include <thread>
#include <vector>

#include "graspkit/planning/planner.hpp"
#include "graspkit/planning/planning_scene.hpp"

namespace graspkit::planners {

class SampleWorkers {
 public:
  // A custom energy (a Lua function, say) need not be thread-safe, so it gets one worker.
  SampleWorkers(const PlanningRequest& request, const std::shared_ptr<const SearchSpace>& space) {
    const int count = request.customEnergy ? 1 : std::max(request.threads, 1);
    for (int w = 0; w < count; ++w) {
      scenes_.push_back(makePlanningScene(request, space));
      energies_.push_back(makeSearchEnergy(request));
    }
  }

  int size() const { return static_cast<int>(scenes_.size()); }
  PlanningScene& scene(int worker) { return *scenes_[static_cast<std::size_t>(worker)]; }
  SearchEnergy& energy(int worker) { return *energies_[static_cast<std::size_t>(worker)]; }

  // Runs job(worker, i) for every i in [begin, end), each i once, on all workers; rethrows the
  // first error a worker raised.
  template <typename Job>
  void run(std::int64_t begin, std::int64_t end, Job job) {
    std::atomic<std::int64_t> next{begin};
    std::vector<std::exception_ptr> errors(scenes_.size());
    auto work = [&](int w) {
      try {
        for (std::int64_t i = next++; i < end; i = next++) job(w, i);
      } catch (...) {
        errors[static_cast<std::size_t>(w)] = std::current_exception();
      }
    };
    const int workers =
        static_cast<int>(std::min<std::int64_t>(size(), std::max<std::int64_t>(end - begin, 1)));
    std::vector<std::thread> pool;
    for (int w = 1; w < workers; ++w) pool.emplace_back(work, w);
    work(0);
    for (std::thread& t : pool) t.join();
    for (const auto& e : errors)
      if (e) std::rethrow_exception(e);
  }

 private:
  std::vector<std::unique_ptr<PlanningScene>> scenes_;
  std::vector<std::unique_ptr<SearchEnergy>> energies_;
};

// The best `capacity` states by energy, lowest first. No distance rule: every sample is its own
// grasp. Equal energies keep the order they were offered in (GraspIt!'s list planner sorts its
// list stably).
class RankedStates {
 public:
  explicit RankedStates(int capacity) : capacity_(capacity) {}

  void offer(SearchState state) {
    const auto at = std::upper_bound(
        states_.begin(), states_.end(), state.energy,
        [](double energy, const SearchState& listed) { return energy < listed.energy; });
    if (static_cast<int>(states_.size()) >= capacity_ && at == states_.end()) return;
    states_.insert(at, std::move(state));
    if (static_cast<int>(states_.size()) > capacity_) states_.pop_back();
  }

  const std::vector<SearchState>& states() const { return states_; }

 private:
  int capacity_;
  std::vector<SearchState> states_;
};

// The values that put the hand exactly at `pose` with `dofs`, or nullopt when the space cannot
// represent that state: outside its ranges (encode clamps), off the eigengrasp subspace, or a
// pose the approach space has no variables for. Round-trip tolerances: 1e-6 mm, rad.
inline std::optional<std::vector<double>> encodeExactly(const SearchSpace& space,
                                                        const Transform& pose,
                                                        std::span<const double> dofs) {
  std::vector<double> values = space.encode(pose, dofs);
  const Transform back = space.handPose(values);
  const std::vector<double> backDofs = space.dofs(values);
  constexpr double kTolerance = 1e-6;
  if ((back.translation() - pose.translation()).norm() > kTolerance) return std::nullopt;
  if ((back.linear() - pose.linear()).cwiseAbs().maxCoeff() > kTolerance) return std::nullopt;
  for (std::size_t d = 0; d < dofs.size(); ++d)
    if (std::abs(backDofs[d] - dofs[d]) > kTolerance) return std::nullopt;
  return values;
}

}  // namespace graspkit::planners
