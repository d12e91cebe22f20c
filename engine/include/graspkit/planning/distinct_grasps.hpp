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

#include <span>
#include <vector>

#include "graspkit/planning/best_list.hpp"
#include "graspkit/planning/planner.hpp"

namespace graspkit {

class DistinctGrasps {
 public:
  DistinctGrasps(double threshold, BestList::Distance distance);

  // Offers a finished grasp (PlannedGrasp::evaluated); returns whether it was kept.
  bool offer(const PlannedGrasp& grasp);

  // The best `count` grasps, best first.
  std::vector<PlannedGrasp> best(std::size_t count) const;
  std::size_t size() const { return grasps_.size(); }
  int forceClosureCount() const;

 private:
  double threshold_;
  BestList::Distance distance_;
  std::vector<PlannedGrasp> grasps_;
};

}  // namespace graspkit
