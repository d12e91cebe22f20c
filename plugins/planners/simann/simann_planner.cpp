#include "simann_planner.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <set>
#include <thread>

#include <fmt/format.h>

#include "annealing_chain.hpp"
#include "graspkit/base/error.hpp"
#include "graspkit/base/parallel_for.hpp"
#include "graspkit/planning/planning_scene.hpp"
#include "graspkit/plugin/registry.hpp"
#include "restart_planner.hpp"

namespace graspkit::simann {

namespace {

struct Settings {
  ChainSettings search;
  bool restarts = false;
  RestartSettings restart;
};

const AnnealingParameters& preset(const std::string& name) {
  for (const AnnealingParameters& p : kPresets)
    if (p.name == name) return p;
  throw Error(
      fmt::format("simann: unknown preset '{}'; expected DEFAULT, LOOP, MODIFIED, "
                  "STRICT or ONLINE",
                  name));
}

double number(const std::string& key, const std::string& text, double min) {
  try {
    std::size_t used = 0;
    const double value = std::stod(text, &used);
    if (used == text.size() && std::isfinite(value) && value >= min) return value;
  } catch (const std::exception&) {
  }
  throw Error(fmt::format("simann: option {} = '{}' is not a number >= {}", key, text, min));
}

std::int64_t whole(const std::string& key, const std::string& text, double min, double max) {
  const double value = number(key, text, min);
  if (value != std::floor(value) || value > max)
    throw Error(fmt::format("simann: option {} = '{}' is not a whole number in [{}, {}]", key, text,
                            min, max));
  return static_cast<std::int64_t>(value);
}

RestartStart parseStart(const std::string& text) {
  if (text == "around") return RestartStart::Around;
  if (text == "random") return RestartStart::Random;
  if (text == "world") return RestartStart::World;
  throw Error(fmt::format("simann: start '{}' unknown; expected around, random or world", text));
}

Settings settingsFrom(const PlanningRequest& request) {
  Settings s;
  s.search.bestListSize = request.bestListSize;
  RestartSettings& r = s.restart;
  r.search.bestListSize = 4;
  r.refine.parameters = preset("STRICT");
  r.refine.distanceThreshold = 0.3;  // GraspIt!'s guided planner's children
  r.refine.jumpScale = 0.1;
  r.refine.bestListSize = 1;
  for (const auto& [key, value] : request.options) {
    if (key == "preset") {
      s.search.parameters = preset(value);
      r.search.parameters = s.search.parameters;
    } else if (key == "mode") {
      if (value != "anneal" && value != "restarts")
        throw Error(fmt::format("simann: mode '{}' unknown; expected anneal or restarts", value));
      s.restarts = value == "restarts";
    } else if (key == "threshold") {
      s.search.distanceThreshold = number(key, value, 0.0);
      r.threshold = s.search.distanceThreshold;
    } else if (key == "restart-steps")
      r.searchSteps = whole(key, value, 1, 1e9);
    else if (key == "restart-grasps")
      r.search.bestListSize = static_cast<int>(whole(key, value, 1, 1000));
    else if (key == "stride")
      r.stride = static_cast<long>(whole(key, value, 1, 1e9));
    else if (key == "start")
      r.start = parseStart(value);
    else if (key == "refine-steps")
      r.refineSteps = whole(key, value, 0, 1e9);
    else if (key == "centring-moves")
      r.centring.moves = static_cast<int>(whole(key, value, 0, 100));
    else if (key == "refine-preset")
      r.refine.parameters = preset(value);
    else if (key == "refine-energy")
      r.refineEnergy = value;
    else if (key == "refine-jump")
      r.refine.jumpScale = number(key, value, 0.0);
    else if (key == "collision-order") {
      if (value != "graspit" && value != "lazy")
        throw Error(
            fmt::format("simann: collision-order '{}' unknown; expected lazy or graspit", value));
      s.search.checkCollisionsLast = value == "lazy";
      r.search.checkCollisionsLast = s.search.checkCollisionsLast;
    } else
      throw Error(fmt::format(
          "simann: unknown option '{}'; known: preset, mode, threshold, "
          "collision-order, restart-steps, restart-grasps, stride, start, centring-moves, "
          "refine-steps, refine-preset, refine-energy, refine-jump",
          key));
  }
  return s;
}

class SimAnnPlanner final : public Planner {
 public:
  explicit SimAnnPlanner(const PlanningRequest& request)
      : request_(request), settings_(settingsFrom(request)), space_(makeSearchSpace(request)) {
    if (request.threads < 1)
      throw Error(fmt::format("simann: {} threads is not valid", request.threads));
    if (request.bestListSize < 1)
      throw Error(fmt::format("simann: a best list of {} is not valid", request.bestListSize));
    for (int c = 0; c < request.threads; ++c) {
      auto scene = makePlanningScene(request, space_);
      SearchState start = request.states.empty() ? startState(*scene) : request.states.front();
      if (static_cast<int>(start.values.size()) != space_->size())
        throw Error(fmt::format("simann: the start state has {} values; the {} space has {}",
                                start.values.size(), nameOf(request.position), space_->size()));
      start.energy = kUnevaluatedEnergy;
      chains_.push_back(std::make_unique<AnnealingChain>(
          std::move(scene), makeSearchEnergy(request), settings_.search, chainSeed(request.seed, c),
          std::move(start)));
    }
  }

  void step(std::int64_t steps) override {
    target_ += steps;
    const int count = static_cast<int>(chains_.size());
    // Chain c's share of the total depends only on the total, so a step budget gives the same
    // result however runPlanner chunks it.
    parallelFor({.end = count, .threads = count}, [&](int, std::int64_t c) {
      const std::int64_t share = target_ / count + (c < target_ % count ? 1 : 0);
      chains_[static_cast<std::size_t>(c)]->runTo(share);
    });
  }

  std::int64_t stepsDone() const override {
    std::int64_t total = 0;
    for (const auto& chain : chains_) total += chain->steps();
    return total;
  }

  std::vector<PlannedGrasp> best() const override {
    const std::vector<SearchState> states = mergedStates();
    std::vector<PlannedGrasp> grasps;
    for (const SearchState& s : states) grasps.push_back(plannedGrasp(*space_, s));
    return grasps;
  }

 private:
  BestList emptyList(double threshold) const {
    const double radius = chains_.front()->scene().objectRadius();
    return BestList(request_.bestListSize, threshold,
                    [space = space_, radius](std::span<const double> a, std::span<const double> b) {
                      return space->distance(a, b, radius);
                    });
  }

  std::vector<SearchState> mergedStates() const {
    if (chains_.size() == 1) return chains_.front()->best().states();
    BestList merged = emptyList(settings_.search.distanceThreshold);
    for (const auto& chain : chains_) merged.merge(chain->best());
    return merged.states();
  }

  PlanningRequest request_;
  Settings settings_;
  std::shared_ptr<const SearchSpace> space_;
  std::vector<std::unique_ptr<AnnealingChain>> chains_;
  std::int64_t target_ = 0;
};

}  // namespace

std::unique_ptr<Planner> makeSimAnnPlanner(const PlanningRequest& request) {
  const Settings settings = settingsFrom(request);
  if (settings.restarts) return makeRestartPlanner(request, settings.restart);
  return std::make_unique<SimAnnPlanner>(request);
}

}  // namespace graspkit::simann
