// Grasp planning: a planner from the registry, run on a budget, each grasp closed and measured.

#include <cmath>
#include <thread>

#include <fmt/format.h>

#include "c_api_support.hpp"
#include "graspkit/plugin/registry.hpp"

using namespace graspkit;
using namespace graspkit::c_api;

namespace {

constexpr std::int64_t kDefaultSteps = 40000;  // GraspIt!'s search length, as `graspkit plan`

const graspkit_plan& planOf(const graspkit_plan* plan) {
  return *require(plan, "plan");
}

const PlannedGrasp& graspAt(const graspkit_plan& plan, std::size_t index) {
  if (index >= plan.grasps.size())
    throw Failure{
        GRASPKIT_ERROR_OUT_OF_RANGE,
        fmt::format("grasp {} does not exist (the plan has {})", index, plan.grasps.size())};
  return plan.grasps[index];
}

}  // namespace

extern "C" {

graspkit_status graspkit_plan_options_default(graspkit_plan_options* options) {
  return guarded([&] {
    graspkit_plan_options& o = *require(options, "options");
    o = graspkit_plan_options{};
    o.planner = "simann";
    o.energy = "contact";
    o.steps = kDefaultSteps;
    o.seconds = 0.0;
    o.seed = 1;
    o.threads = 0;
    o.top = 20;
  });
}

graspkit_status graspkit_plan_grasps(const graspkit_world* world, int32_t robot, int32_t object,
                                     const graspkit_plan_options* options, graspkit_plan** plan) {
  return guarded([&] {
    const World& w = require(world, "world")->world;
    require(plan, "plan");
    checkedRobot(w, robot);
    checkedBody(w, object);
    graspkit_plan_options o;
    graspkit_plan_options_default(&o);
    if (options) o = *options;
    if (!o.planner) o.planner = "simann";
    if (!o.energy) o.energy = "contact";
    if (o.steps < 0 || std::isnan(o.seconds) || o.seconds < 0 || o.threads < 0 || o.top < 1)
      throw Error(
          fmt::format("plan options: steps {}, seconds {}, threads {}, top {}: steps and "
                      "seconds must be >= 0, threads >= 0 and top >= 1",
                      o.steps, o.seconds, o.threads, o.top));

    auto result = std::make_unique<graspkit_plan>();
    PlanningRequest& request = result->request;
    request.world = std::make_shared<World>(w.clone());
    request.robot = robot;
    request.object = BodyRef::body(object);
    request.energy = o.energy;
    request.seed = o.seed;
    const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    request.threads = o.threads > 0 ? o.threads : cores;
    request.bestListSize = o.top;
    if (std::string(o.planner) == "simann") request.options["mode"] = "restarts";
    Registry::global().makeSearchEnergy(request.energy);  // an unknown name fails first
    auto planner = Registry::global().makePlanner(o.planner, request);
    PlanningBudget budget;
    if (o.steps > 0 || o.seconds <= 0)
      budget.steps = o.steps > 0 ? o.steps : kDefaultSteps;
    else
      budget.seconds = o.seconds;
    PlanningRun run = runPlanner(*planner, budget);
    finishGrasps(request, run.grasps, request.threads);
    result->grasps = std::move(run.grasps);
    *plan = result.release();
  });
}

graspkit_status graspkit_plan_count(const graspkit_plan* plan, size_t* count) {
  return guarded([&] { *require(count, "count") = planOf(plan).grasps.size(); });
}

graspkit_status graspkit_plan_grasp(const graspkit_plan* plan, size_t index,
                                    graspkit_planned_grasp* grasp) {
  return guarded([&] {
    const PlannedGrasp& g = graspAt(planOf(plan), index);
    graspkit_planned_grasp& out = *require(grasp, "grasp");
    out.pregrasp = toPose(g.pose);
    out.closed = toPose(g.evaluated ? g.closed.pose : g.pose);
    out.energy = g.energy;
    out.epsilon = g.epsilon;
    out.volume = g.volume;
    out.contacts = g.contacts;
    out.force_closure = g.forceClosure ? 1 : 0;
  });
}

graspkit_status graspkit_plan_grasp_dofs(const graspkit_plan* plan, size_t index, double* values,
                                         size_t count) {
  return guarded([&] {
    const graspkit_plan& p = planOf(plan);
    const PlannedGrasp& g = graspAt(p, index);
    const std::vector<double>& dofs = g.evaluated ? g.closed.dofs : g.dofs;
    checkCount(count, dofs.size(), "graspkit_plan_grasp_dofs");
    if (count > 0) require(values, "values");
    std::copy(dofs.begin(), dofs.end(), values);
  });
}

graspkit_status graspkit_plan_grasp_world(const graspkit_plan* plan, size_t index,
                                          graspkit_world** world) {
  return guarded([&] {
    const graspkit_plan& p = planOf(plan);
    const PlannedGrasp& g = graspAt(p, index);
    require(world, "world");
    *world = new graspkit_world{graspWorld(p.request, g)};
  });
}

void graspkit_plan_free(graspkit_plan* plan) {
  delete plan;
}

}  // extern "C"
