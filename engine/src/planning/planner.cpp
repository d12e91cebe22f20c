#include "graspkit/planning/planner.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <thread>

#include <fmt/format.h>

#include "graspkit/base/error.hpp"
#include "graspkit/base/parallel_for.hpp"
#include "graspkit/grasp/autograsp.hpp"
#include "graspkit/grasp/grasp.hpp"
#include "graspkit/planning/planning_scene.hpp"

namespace graspkit {

namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// How many steps to take between looks at the clock: about a hundredth of a second's worth,
// once the planner's speed is known.
std::int64_t chunkFor(std::int64_t done, double seconds) {
  if (done <= 0 || seconds <= 0) return 16;
  const double perSecond = static_cast<double>(done) / seconds;
  return std::clamp<std::int64_t>(static_cast<std::int64_t>(perSecond / 100.0), 1, 100000);
}

PlannerProgress progressOf(const Planner& planner, double seconds,
                           const std::vector<PlannedGrasp>& best) {
  PlannerProgress p;
  p.steps = planner.stepsDone();
  p.seconds = seconds;
  p.states = static_cast<int>(best.size());
  if (!best.empty()) p.bestEnergy = best.front().energy;
  return p;
}

}  // namespace

bool finishGrasp(PlanningScene& scene, PlannedGrasp& grasp, const std::function<bool()>& keepGoing,
                 CloseMeasure measure) {
  scene.setHand(grasp.pose, grasp.dofs);
  AutoGraspOptions close;
  close.keepGoing = keepGoing;
  const AutoGraspResult closed = autoGrasp(scene.world(), scene.robot(), close);
  if (closed.end == MotionEnd::Stopped) return false;
  GraspRequest request;
  if (measure == CloseMeasure::Ranking) request.wrenchSpace.method = HullMethod::NearestFacet;
  Grasp measured = analyzeGrasp(scene.world(), scene.robot(), scene.object(),
                                contactsWith(closed.contacts, scene.object()), request);
  grasp.closed = scene.handConfiguration();
  grasp.epsilon = measured.epsilon;
  grasp.volume = measured.volume;
  grasp.contacts = static_cast<int>(measured.contacts.size());
  grasp.contactList = std::move(measured.contacts);
  grasp.forceClosure = measured.forceClosure;
  grasp.evaluated = true;
  return true;
}

void measureVolume(const World& world, int robot, const BodyRef& object, PlannedGrasp& grasp) {
  if (!std::isnan(grasp.volume)) return;
  grasp.volume = analyzeGrasp(world, robot, object, grasp.contactList).volume;
}

void measureAsGraspIt(const World& world, int robot, const BodyRef& object, PlannedGrasp& grasp) {
  const Grasp measured = analyzeGrasp(world, robot, object, grasp.contactList);
  grasp.epsilon = measured.epsilon;
  grasp.forceClosure = measured.forceClosure;
  grasp.volume = measured.volume;
}

bool orderNeedsVolume(const PlannedGrasp& a, const PlannedGrasp& b) {
  return a.forceClosure == b.forceClosure && a.epsilon == b.epsilon;
}

bool betterGrasp(const PlannedGrasp& a, const PlannedGrasp& b) {
  if (a.forceClosure != b.forceClosure) return a.forceClosure;
  if (a.epsilon != b.epsilon) return a.epsilon > b.epsilon;
  if (a.volume != b.volume) return a.volume > b.volume;
  return a.energy < b.energy;
}

World graspWorld(const PlanningRequest& request, const PlannedGrasp& grasp) {
  if (!request.world) throw Error("a planning request needs a world");
  World world = request.world->clone();
  if (grasp.evaluated) {
    applyHandConfiguration(world, request.robot, grasp.closed);
  } else {
    for (int j = 0; j < static_cast<int>(world.robot(request.robot).breakaway().size()); ++j)
      world.setBreakaway(request.robot, j, BreakawayState{});
    world.setRobotPose(request.robot, grasp.pose);
    world.setDofValues(request.robot, grasp.dofs, LimitPolicy::Clamp);
  }
  return world;
}

namespace {

void checkBudget(const PlanningBudget& budget) {
  if (!budget.steps && !budget.seconds)
    throw Error("a planning budget needs a number of steps or of seconds");
  if (budget.steps && *budget.steps < 0)
    throw Error(fmt::format("a planning budget of {} steps is not valid", *budget.steps));
  if (budget.seconds && !(*budget.seconds >= 0))
    throw Error(fmt::format("a planning budget of {} seconds is not valid", *budget.seconds));
}

}  // namespace

void Planner::run(const PlanningBudget& budget) {
  checkBudget(budget);
  const auto start = Clock::now();
  const std::int64_t first = stepsDone();
  double lastReport = 0.0;
  auto fraction = [&](std::int64_t done, double elapsed) {
    if (budget.steps) return *budget.steps > 0 ? static_cast<double>(done) / *budget.steps : 1.0;
    return *budget.seconds > 0 ? elapsed / *budget.seconds : 1.0;
  };
  while (!done()) {
    const std::int64_t taken = stepsDone() - first;
    const double elapsed = secondsSince(start);
    if (budget.steps && taken >= *budget.steps) break;
    if (budget.seconds && elapsed >= *budget.seconds) break;
    std::int64_t chunk = chunkFor(taken, elapsed);
    if (budget.steps) chunk = std::min(chunk, *budget.steps - taken);
    step(chunk);
    if (budget.progress && secondsSince(start) - lastReport >= budget.reportEvery) {
      lastReport = secondsSince(start);
      PlannerProgress p = progressOf(*this, lastReport, best());
      p.fraction = std::min(1.0, fraction(stepsDone() - first, lastReport));
      if (!budget.progress(p)) break;
    }
  }
}

PlanningRun runPlanner(Planner& planner, const PlanningBudget& budget) {
  checkBudget(budget);
  const auto start = Clock::now();
  const std::int64_t first = planner.stepsDone();
  planner.run(budget);
  planner.finish();
  PlanningRun run;
  run.grasps = planner.best();
  run.steps = planner.stepsDone() - first;
  run.seconds = secondsSince(start);
  if (budget.progress) {
    PlannerProgress p = progressOf(planner, run.seconds, run.grasps);
    p.fraction = 1.0;
    if (std::all_of(run.grasps.begin(), run.grasps.end(),
                    [](const PlannedGrasp& g) { return g.evaluated; }))
      p.forceClosure =
          static_cast<int>(std::count_if(run.grasps.begin(), run.grasps.end(),
                                         [](const PlannedGrasp& g) { return g.forceClosure; }));
    budget.progress(p);
  }
  return run;
}

void finishGrasps(const PlanningRequest& request, std::vector<PlannedGrasp>& grasps, int threads) {
  if (grasps.empty()) return;
  const auto space = makeSearchSpace(request);
  // A fresh clone per grasp: nothing one autograsp leaves in the world (broken-away joints,
  // anything a robot type keeps) may change the next grasp's measure.
  parallelFor({.end = static_cast<std::int64_t>(grasps.size()), .threads = threads},
              [&](int, std::int64_t i) {
                PlannedGrasp& grasp = grasps[static_cast<std::size_t>(i)];
                if (!grasp.evaluated) finishGrasp(*makePlanningScene(request, space), grasp);
              });
}

std::shared_ptr<const SearchSpace> makeSearchSpace(const PlanningRequest& request) {
  if (!request.world) throw Error("a planning request needs a world");
  const World& world = *request.world;
  if (request.robot < 0 || request.robot >= world.robotCount())
    throw Error(fmt::format("robot {} out of range: the world has {} robot(s)", request.robot,
                            world.robotCount()));
  if (request.object.kind != BodyRef::Kind::Body || !isValid(world, request.object))
    throw Error("the object to grasp must be a body of the world");
  const Transform reference = request.position == PositionSpace::Approach
                                  ? world.robot(request.robot).pose()
                                  : bodyPose(world, request.object);
  return std::make_shared<const SearchSpace>(world.robot(request.robot).model(), request.position,
                                             request.posture, reference);
}

std::unique_ptr<PlanningScene> makePlanningScene(const PlanningRequest& request,
                                                 std::shared_ptr<const SearchSpace> space) {
  if (!request.world) throw Error("a planning request needs a world");
  return std::make_unique<PlanningScene>(request.world->clone(), request.robot, request.object,
                                         std::move(space));
}

std::unique_ptr<SearchEnergy> makeSearchEnergy(const PlanningRequest& request) {
  if (request.customEnergy) {
    auto energy = request.customEnergy();
    if (!energy) throw Error("the custom search energy's factory made nothing");
    return energy;
  }
  if (request.energyByName) return request.energyByName(request.energy);
  const std::string name = canonicalEnergyName(request.energy);
  for (auto& [builtin, factory] : builtinSearchEnergies())
    if (builtin == name) return factory();
  throw Error(
      fmt::format("no search energy is called '{}' (a planner made outside the Registry "
                  "knows only the built-in energies)",
                  request.energy));
}

SearchState startState(const PlanningScene& scene) {
  const SearchSpace& space = scene.space();
  SearchState state;
  if (space.positionSpace() == PositionSpace::Ellipsoid) {
    state.values.resize(static_cast<std::size_t>(space.size()));
    for (int i = 0; i < space.size(); ++i)
      state.values[i] = 0.5 * (space.variables()[i].min + space.variables()[i].max);
    const auto& dofs = scene.hand().dofValues();
    const auto encoded = SearchSpace(scene.hand().model(), PositionSpace::Complete,
                                     space.postureSpace(), space.reference())
                             .encode(scene.hand().pose(), {dofs.begin(), dofs.end()});
    std::copy_n(encoded.begin(), space.postureSize(), state.values.begin());
    return state;
  }
  const auto& dofs = scene.hand().dofValues();
  state.values = space.encode(scene.hand().pose(), {dofs.begin(), dofs.end()});
  return state;
}

PlannedGrasp plannedGrasp(const SearchSpace& space, const SearchState& state) {
  PlannedGrasp grasp;
  grasp.values = state.values;
  grasp.pose = space.handPose(state.values);
  grasp.dofs = space.dofs(state.values);
  grasp.energy = state.energy;
  return grasp;
}

}  // namespace graspkit
