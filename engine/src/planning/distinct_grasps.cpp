#include "graspkit/planning/distinct_grasps.hpp"

#include <algorithm>

namespace graspkit {

DistinctGrasps::DistinctGrasps(double threshold, BestList::Distance distance)
    : threshold_(threshold), distance_(std::move(distance)) {}

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
  if (!betterGrasp(grasp, grasps_[near])) return false;
  grasps_[near] = grasp;
  return true;
}

std::vector<PlannedGrasp> DistinctGrasps::best(std::size_t count) const {
  std::vector<PlannedGrasp> sorted = grasps_;
  std::stable_sort(sorted.begin(), sorted.end(), betterGrasp);
  if (sorted.size() > count) sorted.resize(count);
  return sorted;
}

int DistinctGrasps::forceClosureCount() const {
  return static_cast<int>(std::count_if(grasps_.begin(), grasps_.end(),
                                        [](const PlannedGrasp& g) { return g.forceClosure; }));
}

}  // namespace graspkit
