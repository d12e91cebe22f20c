#pragma once
// The grasps a planner has closed and measured, kept distinct: no two within `threshold` of each
// other by the search space's distance (GraspIt!'s rule between best-list states, 0.2). Unlike
// the BestList, a newcomer never evicts more than one grasp, and only a worse one, so offering
// more grasps never lowers the number of force-closure grasps kept nor the best epsilon: a plan
// given more budget offers a superset of candidates and can only do better.
//
//   - a grasp farther than `threshold` from every kept grasp is kept;
//   - a grasp within `threshold` of exactly one kept grasp replaces it when it ranks better
//     (betterGrasp: force closure, epsilon, volume, energy);
//   - otherwise it is refused.
//
// Grasps may come with their volume deferred (finishGrasp()'s deferVolume). `measure` then
// measures one (measureVolume() on the request's world), only where the ranking reads it: a
// replacement weighed between two grasps that are not force closure, and best() when fewer force
// closure grasps are kept than it is asked for. A grasp's volume is measured at most once, and
// the grasps kept and their order are what measuring every volume at once would give.

#include <functional>
#include <span>
#include <vector>

#include "graspkit/planning/best_list.hpp"
#include "graspkit/planning/planner.hpp"

namespace graspkit {

class DistinctGrasps {
 public:
  using MeasureVolume = std::function<void(PlannedGrasp&)>;

  DistinctGrasps(double threshold, BestList::Distance distance, MeasureVolume measure = {});

  // Offers a finished grasp (PlannedGrasp::evaluated); returns whether it was kept.
  bool offer(const PlannedGrasp& grasp);

  // The best `count` grasps, best first (their deferred volumes measured, when there is a
  // `measure`). It may write those volumes into the kept grasps: one thread at a time, as offer().
  std::vector<PlannedGrasp> best(std::size_t count) const;
  // Measures now the deferred volumes best(count) would measure, so that best(count) then
  // measures none. A planner on a time budget calls it as it goes: the volumes are paid for
  // inside the budget, not after it (they cost half a second for 50 grasps in a sanitizer build).
  void measureForBest(std::size_t count);
  std::size_t size() const { return grasps_.size(); }
  int forceClosureCount() const;

 private:
  // Whether best(count) ranks grasps that are not force closure, and so reads their volumes.
  bool bestReadsVolumes(std::size_t count) const;

  double threshold_;
  BestList::Distance distance_;
  MeasureVolume measure_;
  mutable std::vector<PlannedGrasp> grasps_;  // mutable: best() measures deferred volumes
};

}  // namespace graspkit
