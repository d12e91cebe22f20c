#include "graspkit/grasp/quality.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <mutex>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "graspkit/base/error.hpp"

namespace graspkit {
namespace {

class EpsilonMeasure final : public QualityMeasure {
 public:
  std::string name() const override { return "epsilon"; }
  double evaluate(const GraspWrenchSpace& gws) const override { return epsilonQuality(gws); }
};

class VolumeMeasure final : public QualityMeasure {
 public:
  std::string name() const override { return "volume"; }
  double evaluate(const GraspWrenchSpace& gws) const override { return volumeQuality(gws); }
};

class WeightMeasure final : public QualityMeasure {
 public:
  std::string name() const override { return "weight"; }
  double evaluate(const GraspWrenchSpace& gws) const override { return weightQuality(gws); }
};

}  // namespace

std::vector<std::pair<std::string, QualityMeasureFactory>> builtinQualityMeasures() {
  return {{"epsilon", [] { return std::make_unique<EpsilonMeasure>(); }},
          {"volume", [] { return std::make_unique<VolumeMeasure>(); }},
          {"weight", [] { return std::make_unique<WeightMeasure>(); }}};
}

bool isForceClosure(double epsilon) {
  return epsilon >= kForceClosureEpsilon;  // false for NaN
}

bool isForceClosure(const GraspWrenchSpace& gws) {
  return isForceClosure(epsilonQuality(gws));
}

double epsilonQuality(const GraspWrenchSpace& gws) {
  if (!gws.built || gws.hyperplanes.empty()) return -1.0;
  double smallest = std::numeric_limits<double>::infinity();
  for (const WrenchHyperplane& h : gws.hyperplanes) {
    if (h.offset > 0.0) return -1.0;  // the origin is outside this facet
    smallest = std::min(smallest, -h.offset);
  }
  return smallest;
}

double weightQuality(const GraspWrenchSpace& gws) {
  if (gws.originOutside || !gws.built || gws.hyperplanes.empty()) return -1.0;
  if (std::isnan(gws.volume)) return std::numeric_limits<double>::quiet_NaN();  // one facet only
  double smallest = std::numeric_limits<double>::infinity();
  for (const WrenchHyperplane& h : gws.hyperplanes) {
    if (h.offset > 0.0) return -1.0;  // the origin is outside this facet
    const double force = h.normal.head<3>().norm();
    if (force > 0.0) smallest = std::min(smallest, -h.offset / force);
  }
  // A space built without force coordinates has no facet that bounds a force.
  return std::isinf(smallest) ? std::numeric_limits<double>::quiet_NaN() : smallest;
}

double volumeQuality(const GraspWrenchSpace& gws) {
  if (gws.originOutside) return std::numeric_limits<double>::quiet_NaN();  // hull skipped
  return gws.built ? gws.volume : 0.0;
}

}  // namespace graspkit
