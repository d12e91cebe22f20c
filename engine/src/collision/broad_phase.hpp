#pragma once
// The broad phase: which pairs of world boxes overlap. Every pairwise query (collision report,
// contact search, a hand's closing) asks it first, so their cost follows the bodies and the pairs
// that are near, not the square of the bodies: a robot with 4,000 links must not make each step
// of a close test 8 million pairs.

#include <algorithm>
#include <cstddef>
#include <limits>
#include <span>
#include <utility>
#include <vector>

#include "collision/collision_geometry.hpp"

namespace graspkit::collision {

// Up to this many boxes every pair is tested directly: no allocation, no sort, the fastest way
// for a hand, an object and a few obstacles (the planner's every step).
inline constexpr std::size_t kDirectPairLimit = 48;

// Calls visit(i, j) for each pair i < j of `boxes` that overlap, in increasing (i, j) order,
// until visit returns false. Above kDirectPairLimit boxes, a sweep along x (sort the boxes by
// their lowest x, then scan each box's followers while they start before it ends) finds the
// overlapping pairs in O(n log n + pairs tested); they are sorted so the order does not depend
// on the method. A box with a NaN coordinate overlaps nothing, either way.
template <class Visit>
void forEachOverlappingPair(std::span<const WorldBox> boxes, Visit&& visit) {
  const std::size_t n = boxes.size();
  if (n <= kDirectPairLimit) {
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i + 1; j < n; ++j)
        if (boxes[i].overlaps(boxes[j]) && !visit(i, j)) return;
    return;
  }
  auto low = [&](std::size_t i) {
    const double x = boxes[i].center.x() - boxes[i].halfSize.x();
    return x == x ? x : -std::numeric_limits<double>::infinity();  // NaN sorts first, meets none
  };
  std::vector<std::size_t> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return low(a) < low(b) || (low(a) == low(b) && a < b);
  });
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t a = order[k];
    const double high = boxes[a].center.x() + boxes[a].halfSize.x();
    for (std::size_t m = k + 1; m < n && low(order[m]) <= high; ++m) {
      const std::size_t b = order[m];
      if (boxes[a].overlaps(boxes[b])) pairs.emplace_back(std::min(a, b), std::max(a, b));
    }
  }
  std::sort(pairs.begin(), pairs.end());
  for (const auto& [i, j] : pairs)
    if (!visit(i, j)) return;
}

// `box` grown by `margin` mm on every side.
inline WorldBox grown(WorldBox box, double margin) {
  box.halfSize.array() += margin;
  return box;
}

}  // namespace graspkit::collision
