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
// Grasps may come with their volume unknown (NaN: CloseMeasure::Ranking). `measure` then
// measures one (measureVolume() on the request's world), only where the ranking reads it: a
// replacement weighed between two grasps that force closure and epsilon cannot order, and in
// best(count) the runs of such grasps that reach into the best `count` (all the grasps that are
// not force closure, when fewer than `count` force-closure grasps are kept). A grasp's volume is
// measured at most once, and the grasps kept and their order are what measuring every volume at
// once would give.

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

  // The best `count` grasps, best first. The volumes their order reads are measured (when there
  // is a `measure`), the others may stay unknown. It may write those volumes into the kept
  // grasps: one thread at a time, as offer().
  std::vector<PlannedGrasp> best(std::size_t count) const;
  std::size_t size() const { return grasps_.size(); }
  const std::vector<PlannedGrasp>& grasps() const { return grasps_; }  // as kept, unordered
  int forceClosureCount() const;

 private:
  // The kept grasps best(count) ranks: the force-closure ones when there are `count` of them,
  // else all.
  std::vector<PlannedGrasp*> candidates(std::size_t count) const;
  // Measures the volumes of the candidates whose order among the best `count` needs them.
  void measureTies(std::size_t count) const;

  double threshold_;
  BestList::Distance distance_;
  MeasureVolume measure_;
  mutable std::vector<PlannedGrasp> grasps_;  // mutable: best() measures unknown volumes
};

}  // namespace graspkit
