// Grasp planning: a planner from the registry, run on a budget, each grasp closed and measured.

#include <cmath>
#include <thread>

#include <fmt/format.h>

#include "c_api_support.hpp"
#include "graspkit/base/enum_names.hpp"
#include "graspkit/host/plan_task.hpp"

using namespace graspkit;
using namespace graspkit::c_api;

namespace {

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
    // The host layer's defaults; the strings live as long as the program.
    static const host::PlanSettings defaults;
    graspkit_plan_options& o = *require(options, "options");
    o = graspkit_plan_options{};
    o.planner = defaults.planner.c_str();
    o.energy = defaults.energy.c_str();
    o.steps = host::kDefaultPlanSteps;
    o.seconds = 0.0;
    o.seed = defaults.seed;
    o.threads = defaults.threads;
    o.top = defaults.top;
    o.mode = nullptr;  // simann's default mode
    o.space = nameOf(defaults.space).data();
    o.posture = nameOf(defaults.posture).data();
  });
}

graspkit_status graspkit_plan_grasps(const graspkit_world* world, int32_t robot, int32_t object,
                                     const graspkit_plan_options* options, graspkit_plan** plan) {
  return guarded([&] {
    const World& w = require(world, "world")->world;
    require(plan, "plan");
    checkedRobot(w, robot);
    checkedBody(w, object);
    host::PlanSettings settings;
    if (options) {
      const graspkit_plan_options& o = *options;
      if (o.steps < 0 || std::isnan(o.seconds) || o.seconds < 0)
        throw Error(fmt::format("plan options: steps {}, seconds {}: both must be >= 0", o.steps,
                                o.seconds));
      if (o.planner) settings.planner = o.planner;
      if (o.energy) settings.energy = o.energy;
      if (o.steps > 0)
        settings.steps = o.steps;
      else if (o.seconds > 0)
        settings.seconds = o.seconds;
      settings.seed = o.seed;
      settings.threads = o.threads;
      settings.top = o.top;
      if (o.mode) settings.mode = o.mode;
      if (o.space) settings.space = parseNamed<PositionSpace>(o.space, "position space");
      if (o.posture) settings.posture = parseNamed<PostureSpace>(o.posture, "posture space");
    }
    host::PlanResult run = host::planGrasps(std::make_shared<const World>(w.clone()), robot,
                                            BodyRef::body(object), settings);
    auto result = std::make_unique<graspkit_plan>();
    result->request = *run.request;
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
    *world = newWorld(host::WorldSession{graspWorld(p.request, g)});
  });
}

void graspkit_plan_free(graspkit_plan* plan) {
  delete plan;
}

}  // extern "C"
