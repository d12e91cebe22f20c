#pragma once
// The one place graspkit calls qhull: the convex hull of packed points, with qhull's messages
// captured in memory and every failure turned into a result.

#include <array>
#include <string>
#include <vector>

#include "graspkit/wrench_space.hpp"

namespace graspkit::detail {

// The hull of `count` points of dimension `dim` packed in `coords` (qhull may joggle a copy;
// `coords` is not changed). `options` are qhull options without the leading "qhull ".
// Fills hyperplanes (expanded to six coordinates by `dimensions`), volume and area of `gws`,
// or sets gws.built = false with qhull's error line in gws.failure.
void qhullHull(std::vector<double>& coords, int dim, const char* options, GraspWrenchSpace& gws);

}  // namespace graspkit::detail
