#pragma once
// What the sampling planners (list, approach) share besides the engine's ScenePool (which
// evaluates their independent samples on several threads): a ranked list that keeps the best
// states in energy order, merged in sample order so that a run gives the same list however many
// threads it used; and the exact encoding of a hand state in a search space.
// Header-only: each planner plugin compiles its own copy.

#include <algorithm>
#include <cmath>
#include <optional>
#include <span>
#include <vector>

#include "graspkit/planning/planner.hpp"
#include "graspkit/planning/search_space.hpp"
#include "graspkit/planning/search_state.hpp"

namespace graspkit::planners {

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
