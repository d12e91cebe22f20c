#pragma once
// The planner's list of the best distinct states found, GraspIt!'s rule: a state enters when it
// beats the worst state in the list (or, while the list is not full, an entry bar of 1e5); it
// displaces every listed state within `threshold` of it that has a higher energy, and is
// refused when a listed state within `threshold` is at least as good. So no two states in the
// list are ever within the threshold of each other.

#include <functional>
#include <span>
#include <vector>

#include "graspkit/planning/search_state.hpp"

namespace graspkit {

class BestList {
 public:
  using Distance = std::function<double(std::span<const double>, std::span<const double>)>;

  // GraspIt!'s simulated-annealing planner keeps 20 states 0.2 apart.
  BestList(int capacity, double threshold, Distance distance);

  // Offers a state; returns whether it entered.
  bool offer(const SearchState& state);
  // Offers every state of another list (merging the best lists of concurrent searches).
  void merge(const BestList& other);

  // Best first.
  const std::vector<SearchState>& states() const { return states_; }
  int capacity() const { return capacity_; }
  double threshold() const { return threshold_; }
  bool full() const { return static_cast<int>(states_.size()) >= capacity_; }
  // The energy a state must beat to enter.
  double entryEnergy() const;

 private:
  int capacity_;
  double threshold_;
  Distance distance_;
  std::vector<SearchState> states_;
};

}  // namespace graspkit
