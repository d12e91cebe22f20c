#include "restart_planner.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <limits>
#include <map>
#include <mutex>
#include <optional>
#include <random>
#include <set>
#include <thread>

#include <fmt/format.h>

#include "graspkit/base/error.hpp"
#include "graspkit/planning/distinct_grasps.hpp"
#include "graspkit/planning/planning_scene.hpp"
#include "graspkit/planning/scene_pool.hpp"

namespace graspkit::simann {

namespace {

using Clock = std::chrono::steady_clock;

// How far outside the object's bounding sphere an "around" start puts the approach frame, mm.
constexpr double kStandoff = 10.0;
// How many starts a restart draws looking for one where the hand collides with nothing.
constexpr int kStartAttempts = 20;

double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

class RestartPlanner final : public Planner {
 public:
  RestartPlanner(const PlanningRequest& request, const RestartSettings& settings)
      : request_(request),
        settings_(settings),
        space_(makeSearchSpace(request)),
        kept_(settings.threshold, {}) {
    if (request.threads < 1)
      throw Error(fmt::format("simann: {} threads is not valid", request.threads));
    if (request.bestListSize < 1)
      throw Error(fmt::format("simann: a best list of {} is not valid", request.bestListSize));
    // Worker 0's scene and energy: checks the robot, the object and the energy now, not inside
    // a worker.
    pool_ = std::make_unique<ScenePool>(request, space_);
    const double radius = pool_->scene(0).objectRadius();
    // Closes are measured for ranking (CloseMeasure::Ranking: no hull, no volume): the kept list
    // measures the volumes its ranking reads, and best() GraspIt!'s figures of the grasps it
    // returns, on the request's world (which no worker changes).
    kept_ = DistinctGrasps(
        settings.threshold,
        [space = space_, radius](std::span<const double> a, std::span<const double> b) {
          return space->distance(a, b, radius);
        },
        [this](PlannedGrasp& g) {
          if (std::isnan(g.volume)) g.volume = graspItFigures(g).volume;
        });
    worldStart_ = request.states.empty() ? startState(pool_->scene(0)) : request.states.front();
    if (static_cast<int>(worldStart_.values.size()) != space_->size())
      throw Error(fmt::format("simann: the start state has {} values; the {} space has {}",
                              worldStart_.values.size(), nameOf(request.position), space_->size()));
    if (settings.refineSteps > 0) makeSearchEnergy(refineRequest());
  }

  void step(std::int64_t steps) override {
    PlanningBudget budget;
    budget.steps = steps;
    run(budget);
  }

  void run(const PlanningBudget& budget) override;

  std::int64_t stepsDone() const override { return merged_ * settings_.cost(); }

  std::vector<PlannedGrasp> best() const override;

 private:
  PlanningRequest refineRequest() const {
    PlanningRequest stage = request_;
    stage.energy = settings_.refineEnergy;
    stage.customEnergy = nullptr;
    return stage;
  }

  SearchState startOf(PlanningScene& scene, std::mt19937_64& random) const;
  SearchState uniformState(std::mt19937_64& random) const;
  SearchState aroundTheObject(const PlanningScene& scene, std::mt19937_64& random) const;
  SearchState refined(const std::shared_ptr<PlanningScene>& scene, const SearchState& seed,
                      std::uint64_t streamSeed) const;
  // Restart `index`: its grasps, closed and measured, or nullopt when keepGoing said stop.
  std::optional<std::vector<PlannedGrasp>> restart(const std::shared_ptr<PlanningScene>& scene,
                                                   std::int64_t index,
                                                   const std::function<bool()>& keepGoing) const;

  // The grasp with GraspIt!'s figures (measureAsGraspIt), each kept grasp measured once.
  PlannedGrasp reported(const PlannedGrasp& grasp) const;
  struct Figures;
  // GraspIt!'s figures of a kept grasp, measured at its first need: a volume that breaks a tie
  // needs GraspIt!'s whole hull, which gives its epsilon too, so a grasp measured for a tie and
  // then returned is measured once.
  const Figures& graspItFigures(const PlannedGrasp& grasp) const;

  PlanningRequest request_;
  RestartSettings settings_;
  std::shared_ptr<const SearchSpace> space_;
  std::unique_ptr<ScenePool> pool_;  // a scene per worker thread
  SearchState worldStart_;
  DistinctGrasps kept_;
  std::int64_t merged_ = 0;  // restarts 0 .. merged_ - 1 are in kept_
  // GraspIt!'s epsilon, force closure and volume of the grasps best() returned or whose volume
  // broke a tie, by their values (kept_'s volumes are measured under run()'s lock, as best() is).
  struct Figures {
    double epsilon;
    bool forceClosure;
    double volume;
  };
  mutable std::map<std::vector<double>, Figures> reported_;
};

// The best grasps by the closes' ranking figures, measured, ordered and returned with GraspIt!'s.
// A grasp in force closure by the exact hull may not be by GraspIt!'s merged one (a
// near-degenerate grasp, epsilon near 0): it then ranks after every force-closure grasp, and the
// next force-closure grasps by ranking are measured to take its place.
std::vector<PlannedGrasp> RestartPlanner::best() const {
  const auto count = static_cast<std::size_t>(request_.bestListSize);
  const auto rankedClosures = static_cast<std::size_t>(kept_.forceClosureCount());
  std::vector<PlannedGrasp> grasps;
  for (std::size_t n = count;;) {
    grasps = kept_.best(n);
    std::size_t closures = 0;
    for (PlannedGrasp& g : grasps) {
      g = reported(g);
      closures += g.forceClosure;
    }
    if (closures >= count || n >= rankedClosures) break;
    n += count - closures;
  }
  std::stable_sort(grasps.begin(), grasps.end(), betterGrasp);
  if (grasps.size() > count) grasps.resize(count);
  return grasps;
}

const RestartPlanner::Figures& RestartPlanner::graspItFigures(const PlannedGrasp& grasp) const {
  auto it = reported_.find(grasp.values);
  if (it == reported_.end()) {
    if (reported_.size() > 2 * kept_.size() + 256) {
      // Grasps that kept_ has since replaced are never asked about again.
      std::set<std::vector<double>> kept;
      for (const PlannedGrasp& g : kept_.grasps()) kept.insert(g.values);
      std::erase_if(reported_, [&](const auto& entry) { return !kept.contains(entry.first); });
    }
    PlannedGrasp measured = grasp;
    measureAsGraspIt(*request_.world, request_.robot, request_.object, measured);
    it = reported_
             .emplace(grasp.values,
                      Figures{measured.epsilon, measured.forceClosure, measured.volume})
             .first;
  }
  return it->second;
}

PlannedGrasp RestartPlanner::reported(const PlannedGrasp& grasp) const {
  PlannedGrasp out = grasp;
  const Figures& figures = graspItFigures(grasp);
  out.epsilon = figures.epsilon;
  out.forceClosure = figures.forceClosure;
  out.volume = figures.volume;
  return out;
}

double uniform(std::mt19937_64& random) {
  return static_cast<double>(random() >> 11) * 0x1.0p-53;
}

Vector3 randomDirection(std::mt19937_64& random) {
  // Uniform on the sphere: z uniform in [-1, 1], azimuth uniform (Archimedes).
  const double z = 2.0 * uniform(random) - 1.0;
  const double azimuth = 2.0 * M_PI * uniform(random);
  const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
  return {r * std::cos(azimuth), r * std::sin(azimuth), z};
}

SearchState RestartPlanner::aroundTheObject(const PlanningScene& scene,
                                            std::mt19937_64& random) const {
  const Vector3 cog =
      bodyPose(scene.world(), scene.object()) * bodyModel(scene.world(), scene.object()).cog;
  const Vector3 outward = randomDirection(random);
  const Vector3 z = -outward;  // the approach direction points at the centre
  const Vector3 helper = std::abs(z.x()) < 0.9 ? Vector3::UnitX() : Vector3::UnitY();
  const Vector3 x0 = z.cross(helper).normalized();
  const double roll = 2.0 * M_PI * uniform(random);
  const Vector3 x = std::cos(roll) * x0 + std::sin(roll) * z.cross(x0);
  Transform approach = Transform::Identity();
  approach.linear().col(0) = x;
  approach.linear().col(1) = z.cross(x);
  approach.linear().col(2) = z;
  approach.translation() = cog + outward * (scene.objectRadius() + kStandoff);
  const Transform palm = approach * space_->approachFrame().inverse();
  const auto& dofs = scene.hand().dofValues();
  SearchState state;
  state.values = space_->encode(palm, {dofs.begin(), dofs.end()});
  // The posture the request starts from, and every value inside its range.
  const auto variables = space_->variables();
  for (int i = 0; i < space_->size(); ++i) {
    if (i < space_->postureSize() || variables[i].fixed) state.values[i] = worldStart_.values[i];
    state.values[i] = std::clamp(state.values[i], variables[i].min, variables[i].max);
  }
  return state;
}

SearchState RestartPlanner::startOf(PlanningScene& scene, std::mt19937_64& random) const {
  RestartStart start = settings_.start;
  // "around" needs a space that can encode a pose relative to the object.
  if (start == RestartStart::Around && space_->positionSpace() == PositionSpace::Ellipsoid)
    start = RestartStart::Random;
  if (start == RestartStart::Around && space_->positionSpace() == PositionSpace::Approach)
    start = RestartStart::World;
  if (start == RestartStart::World) return worldStart_;
  // A start where the hand collides (inside the object, under a floor) leaves the chain no
  // legal neighbour at low temperature: draw again, a bounded number of times.
  SearchState state;
  for (int attempt = 0; attempt < kStartAttempts; ++attempt) {
    state = start == RestartStart::Around ? aroundTheObject(scene, random) : uniformState(random);
    scene.place(state.values);
    if (!scene.handCollides()) break;
  }
  return state;
}

SearchState RestartPlanner::uniformState(std::mt19937_64& random) const {
  SearchState state = worldStart_;
  const auto variables = space_->variables();
  for (int i = 0; i < space_->size(); ++i)
    if (!variables[i].fixed)
      state.values[i] = variables[i].min + uniform(random) * variables[i].range();
  return state;
}

// GraspIt!'s refinement of a seed: a short, narrow annealing search on the refine energy; the
// seed itself competes, so refining never makes a state worse by that energy.
SearchState RestartPlanner::refined(const std::shared_ptr<PlanningScene>& scene,
                                    const SearchState& seed, std::uint64_t streamSeed) const {
  auto energy = makeSearchEnergy(refineRequest());
  SearchState best = seed;
  best.energy = evaluateState(*scene, *energy, best.values).value_or(kUnevaluatedEnergy);
  AnnealingChain chain(scene, std::move(energy), settings_.refine, streamSeed, best);
  chain.runTo(settings_.refineSteps);
  if (!chain.best().states().empty() && chain.best().states().front().energy < best.energy)
    best = chain.best().states().front();
  return best;
}

std::optional<std::vector<PlannedGrasp>> RestartPlanner::restart(
    const std::shared_ptr<PlanningScene>& scene, std::int64_t index,
    const std::function<bool()>& keepGoing) const {
  const auto at = static_cast<int>(index % std::numeric_limits<int>::max());
  std::mt19937_64 random(chainSeed(request_.seed ^ 0x57A27ull, at));
  SearchState start = startOf(*scene, random);
  start.energy = kUnevaluatedEnergy;
  ChainSettings search = settings_.search;
  search.scheduleStride = settings_.scheduleStride();
  AnnealingChain chain(scene, makeSearchEnergy(request_), search, chainSeed(request_.seed, at),
                       std::move(start));
  if (!chain.runTo(settings_.searchSteps, keepGoing)) return std::nullopt;
  std::vector<PlannedGrasp> grasps;
  std::vector<SearchState> seeds = chain.best().states();
  // Restart 0 also closes the hand where the request starts it: a plan is never worse than
  // the hand the user placed (a centred parallel gripper, say).
  if (index == 0) {
    SearchState given = worldStart_;
    auto energy = makeSearchEnergy(request_);
    if (const auto e = evaluateState(*scene, *energy, given.values)) {  // nullopt: it collides
      given.energy = *e;
      seeds.insert(seeds.begin(), given);
    }
  }
  for (std::size_t k = 0; k < seeds.size(); ++k) {
    if (!keepGoing()) return std::nullopt;
    const SearchState state =
        settings_.refineSteps > 0
            ? refined(scene, seeds[k], chainSeed(request_.seed ^ 0x5EEDull, at) + k)
            : seeds[k];
    PlannedGrasp grasp = plannedGrasp(*space_, state);
    CentringSettings centring = settings_.centring;
    centring.keepGoing = keepGoing;
    centring.measure = CloseMeasure::Ranking;
    closeCentred(*scene, grasp, centring);
    if (!grasp.evaluated) return std::nullopt;  // stopped inside its close
    grasps.push_back(std::move(grasp));
  }
  return grasps;
}

void RestartPlanner::run(const PlanningBudget& budget) {
  if (!budget.steps && !budget.seconds)
    throw Error("a planning budget needs a number of steps or of seconds");
  const auto start = Clock::now();
  const std::int64_t first = merged_;
  // A step budget buys whole restarts: as many as it takes to spend it (so a plan takes at most
  // one restart's cost more than asked, and 0 steps take none).
  const std::int64_t cost = settings_.cost();
  const std::int64_t end =
      budget.steps ? first + (std::max<std::int64_t>(*budget.steps, 0) + cost - 1) / cost
                   : std::numeric_limits<std::int64_t>::max();
  if (end <= first) return;
  std::atomic<bool> stop{false};
  std::mutex mutex;  // guards pending, kept_ and merged_
  std::map<std::int64_t, std::vector<PlannedGrasp>> pending;
  double lastReport = 0.0;

  // Merges finished restarts in restart order, whichever thread finished them.
  auto merge = [&](std::int64_t index, std::vector<PlannedGrasp> grasps) {
    std::lock_guard lock(mutex);
    pending.emplace(index, std::move(grasps));
    while (!pending.empty() && pending.begin()->first == merged_) {
      for (const PlannedGrasp& g : pending.begin()->second) kept_.offer(g);
      pending.erase(pending.begin());
      ++merged_;
    }
    // On a time budget, what the final best list measures is measured inside it.
    if (budget.seconds) best();
  };
  auto progress = [&](double elapsed) {
    PlannerProgress p;
    {
      std::lock_guard lock(mutex);
      p.steps = stepsDone();
      p.forceClosure = std::min(kept_.forceClosureCount(), request_.bestListSize);
      p.states = static_cast<int>(std::min<std::size_t>(kept_.size(), request_.bestListSize));
      const auto top = kept_.best(1);
      if (!top.empty()) p.bestEnergy = top.front().energy;
      p.fraction = budget.steps          ? static_cast<double>(merged_ - first) / (end - first)
                   : *budget.seconds > 0 ? std::min(1.0, elapsed / *budget.seconds)
                                         : 1.0;
    }
    p.seconds = elapsed;
    return budget.progress(p);
  };
  // Asked before every annealing step and every grasp closed; only worker 0 (the caller's
  // thread) reports progress.
  auto keepGoing = [&](int worker) {
    if (stop) return false;
    if (budget.seconds && secondsSince(start) >= *budget.seconds) {
      stop = true;
      return false;
    }
    if (worker == 0 && budget.progress) {
      const double elapsed = secondsSince(start);
      if (elapsed - lastReport >= budget.reportEvery) {
        lastReport = elapsed;
        if (!progress(elapsed)) {
          stop = true;
          return false;
        }
      }
    }
    return true;
  };
  // The pool gives each worker its scene (a custom energy, which need not be thread-safe, gets
  // one worker: the caller); a worker whose restart was cut short takes no more.
  auto job = [&](int w, std::int64_t i) {
    const std::function<bool()> going = [&keepGoing, w] { return keepGoing(w); };
    auto grasps = restart(pool_->sharedScene(w), i, going);
    if (!grasps) {
      stop = true;
      return;
    }
    merge(i, std::move(*grasps));
  };
  pool_->run(first, end, job, keepGoing);
}

}  // namespace

std::unique_ptr<Planner> makeRestartPlanner(const PlanningRequest& request,
                                            const RestartSettings& settings) {
  return std::make_unique<RestartPlanner>(request, settings);
}

}  // namespace graspkit::simann
