#include "graspkit/planning/distinct_grasps.hpp"

#include <algorithm>

namespace graspkit {

DistinctGrasps::DistinctGrasps(double threshold, BestList::Distance distance, MeasureVolume measure)
    : threshold_(threshold), distance_(std::move(distance)), measure_(std::move(measure)) {}

bool DistinctGrasps::offer(const PlannedGrasp& grasp) {
  std::size_t near = grasps_.size();
  for (std::size_t i = 0; i < grasps_.size(); ++i) {
    if (distance_(grasp.values, grasps_[i].values) >= threshold_) continue;
    if (near != grasps_.size()) return false;  // near two kept grasps: replacing one is not enough
    near = i;
  }
  if (near == grasps_.size()) {
    grasps_.push_back(grasp);
    return true;
  }
  if (measure_ && orderNeedsVolume(grasp, grasps_[near])) {
    PlannedGrasp measured = grasp;
    measure_(measured);
    measure_(grasps_[near]);
    if (!betterGrasp(measured, grasps_[near])) return false;
    grasps_[near] = std::move(measured);
    return true;
  }
  if (!betterGrasp(grasp, grasps_[near])) return false;
  grasps_[near] = grasp;
  return true;
}

std::vector<PlannedGrasp> DistinctGrasps::best(std::size_t count) const {
  measureTies(count);
  std::vector<PlannedGrasp> sorted;
  for (const PlannedGrasp* g : candidates(count)) sorted.push_back(*g);
  std::stable_sort(sorted.begin(), sorted.end(), betterGrasp);
  if (sorted.size() > count) sorted.resize(count);
  return sorted;
}

std::vector<PlannedGrasp*> DistinctGrasps::candidates(std::size_t count) const {
  // Force closure ranks first whatever the volumes: with enough of it kept, no grasp that is not
  // force closure makes the list, and their volumes are never read.
  const bool closureFills =
      static_cast<std::size_t>(forceClosureCount()) >= std::min(count, grasps_.size());
  std::vector<PlannedGrasp*> out;
  for (PlannedGrasp& g : grasps_)
    if (g.forceClosure || !closureFills) out.push_back(&g);
  return out;
}

void DistinctGrasps::measureTies(std::size_t count) const {
  if (!measure_) return;
  auto ranked = candidates(count);
  const auto before = [](const PlannedGrasp* a, const PlannedGrasp* b) {
    if (a->forceClosure != b->forceClosure) return a->forceClosure;
    return a->epsilon > b->epsilon;
  };
  std::sort(ranked.begin(), ranked.end(), before);
  // A run of grasps that force closure and epsilon cannot order (all the grasps that are not
  // force closure, usually) is ordered by volume, where it reaches into the best `count`.
  for (std::size_t first = 0; first < ranked.size() && first < count;) {
    std::size_t end = first + 1;
    while (end < ranked.size() && orderNeedsVolume(*ranked[first], *ranked[end])) ++end;
    if (end - first > 1)
      for (std::size_t k = first; k < end; ++k) measure_(*ranked[k]);
    first = end;
  }
}

int DistinctGrasps::forceClosureCount() const {
  return static_cast<int>(std::count_if(grasps_.begin(), grasps_.end(),
                                        [](const PlannedGrasp& g) { return g.forceClosure; }));
}

}  // namespace graspkit
