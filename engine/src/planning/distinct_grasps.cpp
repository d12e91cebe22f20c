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
  // Force closure ranks first whatever the volumes: with enough of it kept, no grasp that is not
  // force closure makes the list, and their deferred volumes are never read.
  std::vector<PlannedGrasp> sorted;
  if (!bestReadsVolumes(count)) {
    std::copy_if(grasps_.begin(), grasps_.end(), std::back_inserter(sorted),
                 [](const PlannedGrasp& g) { return g.forceClosure; });
  } else {
    if (measure_)
      for (PlannedGrasp& g : grasps_) measure_(g);
    sorted = grasps_;
  }
  std::stable_sort(sorted.begin(), sorted.end(), betterGrasp);
  if (sorted.size() > count) sorted.resize(count);
  return sorted;
}

void DistinctGrasps::measureForBest(std::size_t count) {
  if (!measure_ || !bestReadsVolumes(count)) return;
  for (PlannedGrasp& g : grasps_) measure_(g);
}

bool DistinctGrasps::bestReadsVolumes(std::size_t count) const {
  const auto closure = static_cast<std::size_t>(forceClosureCount());
  return closure < std::min(count, grasps_.size());
}

int DistinctGrasps::forceClosureCount() const {
  return static_cast<int>(std::count_if(grasps_.begin(), grasps_.end(),
                                        [](const PlannedGrasp& g) { return g.forceClosure; }));
}

}  // namespace graspkit
