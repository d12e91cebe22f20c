#include "graspkit/quality.hpp"

#include <algorithm>
#include <limits>
#include <map>
#include <mutex>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "graspkit/error.hpp"

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

struct Registry {
  std::mutex mutex;
  std::map<std::string, QualityMeasureFactory> factories;

  Registry() {
    factories["epsilon"] = [] { return std::make_unique<EpsilonMeasure>(); };
    factories["volume"] = [] { return std::make_unique<VolumeMeasure>(); };
  }
};

Registry& registry() {
  static Registry instance;
  return instance;
}

}  // namespace

void registerQualityMeasure(const std::string& name, QualityMeasureFactory factory) {
  if (name.empty()) throw Error("a quality measure needs a name");
  if (!factory) throw Error(fmt::format("quality measure '{}' has no factory", name));
  Registry& r = registry();
  std::lock_guard lock(r.mutex);
  if (!r.factories.emplace(name, std::move(factory)).second)
    throw Error(fmt::format("a quality measure named '{}' is already registered", name));
}

std::unique_ptr<QualityMeasure> makeQualityMeasure(const std::string& name) {
  QualityMeasureFactory factory;
  {
    Registry& r = registry();
    std::lock_guard lock(r.mutex);
    auto it = r.factories.find(name);
    if (it != r.factories.end()) factory = it->second;
  }
  if (!factory)
    throw Error(fmt::format("no quality measure named '{}' (known: {})", name,
                            fmt::join(qualityMeasureNames(), ", ")));
  std::unique_ptr<QualityMeasure> measure = factory();
  if (!measure) throw Error(fmt::format("the factory of quality measure '{}' made nothing", name));
  return measure;
}

std::vector<std::string> qualityMeasureNames() {
  Registry& r = registry();
  std::lock_guard lock(r.mutex);
  std::vector<std::string> names;
  for (const auto& entry : r.factories) names.push_back(entry.first);
  return names;  // std::map keeps them sorted
}

bool isForceClosure(const GraspWrenchSpace& gws) {
  if (!gws.built || gws.hyperplanes.empty()) return false;
  return std::all_of(gws.hyperplanes.begin(), gws.hyperplanes.end(),
                     [](const WrenchHyperplane& h) { return h.offset < 0.0; });
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

double volumeQuality(const GraspWrenchSpace& gws) {
  if (gws.originOutside) return std::numeric_limits<double>::quiet_NaN();  // hull skipped
  return gws.built ? gws.volume : 0.0;
}

}  // namespace graspkit
