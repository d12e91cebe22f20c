#pragma once
// Grasp quality measures over the grasp wrench space, registered by name so that a plugin can
// add its own. The built-ins are GraspIt!'s:
//   "epsilon"  the radius of the largest ball about the origin inside the wrench space: the
//              smallest distance from the origin to a facet hyperplane (Ferrari & Canny); -1
//              when the grasp is not force closure or the hull could not be built;
//   "volume"   the volume of the wrench space; 0 when the hull could not be built (no force
//              closure check); NaN when HullMethod::SkipNonForceClosure skipped the hull.
// Names are case-sensitive.

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "graspkit/grasp/wrench_space.hpp"

namespace graspkit {

class QualityMeasure {
 public:
  virtual ~QualityMeasure() = default;
  virtual std::string name() const = 0;
  // Larger is better. A measure must not throw for a wrench space that was not built.
  virtual double evaluate(const GraspWrenchSpace& gws) const = 0;
};

using QualityMeasureFactory = std::function<std::unique_ptr<QualityMeasure>()>;

// The engine's own measures, "epsilon" and "volume", with their factories: the Registry
// (plugin/registry.hpp) starts with them, and plugins add more there.
std::vector<std::pair<std::string, QualityMeasureFactory>> builtinQualityMeasures();

// True when the origin lies strictly inside the built wrench space: every facet offset is
// negative (qhull's normal . w + offset <= 0 inside), so the grasp can resist any wrench.
// GraspIt! only looks for offsets > 0; for the measure-zero case of the origin exactly on a
// facet (offset 0) it reports epsilon 0, and so does epsilonQuality(), while this says false.
bool isForceClosure(const GraspWrenchSpace& gws);

// The built-in measures as plain functions.
double epsilonQuality(const GraspWrenchSpace& gws);
double volumeQuality(const GraspWrenchSpace& gws);

}  // namespace graspkit
