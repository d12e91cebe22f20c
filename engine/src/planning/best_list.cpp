#include "graspkit/planning/best_list.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "graspkit/base/error.hpp"

namespace graspkit {

namespace {
// GraspIt!'s bar for entering a list that is not yet full.
constexpr double kEntryBar = 1.0e5;
}  // namespace

BestList::BestList(int capacity, double threshold, Distance distance)
    : capacity_(capacity), threshold_(threshold), distance_(std::move(distance)) {
  if (capacity < 1)
    throw Error(fmt::format("a best list needs room for a state, not {}", capacity));
  if (!(threshold >= 0) || !std::isfinite(threshold))
    throw Error(fmt::format("best-list distance threshold {} is not valid", threshold));
  if (!distance_) throw Error("a best list needs a distance between states");
}

double BestList::entryEnergy() const {
  return full() ? states_.back().energy : kEntryBar;
}

bool BestList::offer(const SearchState& state) {
  if (!(state.energy < entryEnergy())) return false;
  // A listed neighbour at least as good keeps its place; worse neighbours make way.
  std::vector<std::size_t> displaced;
  for (std::size_t i = 0; i < states_.size(); ++i) {
    if (distance_(state.values, states_[i].values) >= threshold_) continue;
    if (states_[i].energy <= state.energy) return false;
    displaced.push_back(i);
  }
  for (auto it = displaced.rbegin(); it != displaced.rend(); ++it)
    states_.erase(states_.begin() + static_cast<std::ptrdiff_t>(*it));
  auto at = std::upper_bound(states_.begin(), states_.end(), state.energy,
                             [](double e, const SearchState& s) { return e < s.energy; });
  states_.insert(at, state);
  if (static_cast<int>(states_.size()) > capacity_) states_.pop_back();
  return true;
}

void BestList::merge(const BestList& other) {
  for (const SearchState& state : other.states()) offer(state);
}

}  // namespace graspkit
