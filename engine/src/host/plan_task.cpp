#include "graspkit/host/plan_task.hpp"

#include <algorithm>
#include <thread>

#include <fmt/format.h>

#include "graspkit/base/error.hpp"
#include "graspkit/host/invalid_setting.hpp"
#include "graspkit/model/virtual_contact.hpp"
#include "graspkit/model/world.hpp"
#include "graspkit/plugin/registry.hpp"

namespace graspkit::host {

int resolveThreads(int threads) {
  if (threads < 0)
    throw InvalidSetting(fmt::format("threads {} is not valid: 0 (every core) or more", threads));
  if (threads > 0) return threads;
  return static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

PlanningRequest planningRequest(std::shared_ptr<const World> world, int robot, BodyRef object,
                                const PlanSettings& settings) {
  if (!world) throw Error("planning needs a world");
  if (robot < 0 || robot >= world->robotCount())
    throw Error(fmt::format("robot {} out of range: the world has {} robot(s)", robot,
                            world->robotCount()));
  if (object.kind != BodyRef::Kind::Body || object.index < 0 ||
      object.index >= static_cast<int>(world->bodies().size()))
    throw Error("the object to grasp must be a free body of the world, not a robot link");
  if (settings.top < 1)
    throw InvalidSetting(fmt::format("top {} is not valid: 1 or more", settings.top));
  PlanningRequest request;
  request.world = std::move(world);
  request.robot = robot;
  request.object = object;
  request.position = settings.space;
  request.posture = settings.posture;
  request.energy = settings.energy;
  request.seed = settings.seed;
  request.threads = resolveThreads(settings.threads);
  request.bestListSize = settings.top;
  request.options = settings.options;
  if (settings.planner == "simann")
    request.options["mode"] = settings.mode.value_or(kDefaultMode);
  else if (settings.mode)
    throw InvalidSetting(
        fmt::format("mode is a simann setting; planner '{}' has none", settings.planner));
  if (!settings.preset.empty()) request.options["preset"] = settings.preset;
  Registry::global().makeSearchEnergy(request.energy);  // an unknown name fails before planning
  return request;
}

PlanningBudget planningBudget(const PlanSettings& settings) {
  if (settings.steps && settings.seconds) throw InvalidSetting("give steps or seconds, not both");
  if (settings.steps && *settings.steps < 1)
    throw InvalidSetting(fmt::format("steps {} is not valid: 1 or more", *settings.steps));
  if (settings.seconds && !(*settings.seconds > 0))
    throw InvalidSetting(fmt::format("seconds {} is not valid: more than 0", *settings.seconds));
  PlanningBudget budget;
  if (settings.seconds)
    budget.seconds = *settings.seconds;
  else
    budget.steps = settings.steps.value_or(kDefaultPlanSteps);
  return budget;
}

PlanningContacts planningContacts(const World& world, int robot) {
  const Robot& hand = world.robot(robot);
  PlanningContacts contacts;
  contacts.derived = hand.model().virtualContacts.empty();
  contacts.count =
      contacts.derived ? deriveVirtualContacts(hand).size() : hand.model().virtualContacts.size();
  if (contacts.derived && contacts.count == 0)
    throw Error(
        fmt::format("{} has no virtual contacts and none could be derived from its "
                    "geometry: no link moves when it closes",
                    hand.name()));
  return contacts;
}

PlanResult planGrasps(std::shared_ptr<const World> world, int robot, BodyRef object,
                      const PlanSettings& settings,
                      std::function<bool(const PlannerProgress&)> progress) {
  auto request =
      std::make_shared<PlanningRequest>(planningRequest(std::move(world), robot, object, settings));
  PlanResult result;
  result.contacts = planningContacts(*request->world, robot);
  PlanningBudget budget = planningBudget(settings);
  budget.progress = [&](const PlannerProgress& p) {
    if (!progress || progress(p)) return true;
    result.stopped = true;
    return false;
  };
  auto planner = Registry::global().makePlanner(settings.planner, *request);
  PlanningRun run = runPlanner(*planner, budget);
  finishGrasps(*request, run.grasps, request->threads);
  result.grasps = std::move(run.grasps);
  result.steps = run.steps;
  result.seconds = run.seconds;
  result.request = std::move(request);
  return result;
}

}  // namespace graspkit::host
