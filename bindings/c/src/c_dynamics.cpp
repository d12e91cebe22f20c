// Dynamics and grasp validation: the host layer's simulation and validation, as graspkit
// simulate and graspkit validate run them.

#include <cmath>

#include <fmt/format.h>

#include "c_api_support.hpp"
#include "graspkit/dynamics/dynamics.hpp"
#include "graspkit/host/simulation_task.hpp"

using namespace graspkit;
using namespace graspkit::c_api;

namespace {

graspkit_step_report toReport(const StepReport& report) {
  return {report.time, report.contacts, report.activeContacts, report.jointLimits};
}

}  // namespace

extern "C" {

graspkit_status graspkit_world_step(graspkit_world* world, double dt,
                                    graspkit_step_report* report) {
  return guarded([&] {
    World& w = require(world, "world")->world;
    const StepReport done = step(w, dt == 0.0 ? kDefaultTimeStep : dt);
    if (report) *report = toReport(done);
  });
}

graspkit_status graspkit_simulation_options_default(graspkit_simulation_options* options) {
  return guarded([&] {
    const host::SimulationSettings defaults;
    graspkit_simulation_options& o = *require(options, "options");
    o = graspkit_simulation_options{};
    o.seconds = defaults.seconds;
    o.dt = defaults.dt;
    o.autograsp = defaults.autograsp ? 1 : 0;
    o.every = defaults.every;
  });
}

graspkit_status graspkit_world_simulate(graspkit_world* world,
                                        const graspkit_simulation_options* options,
                                        graspkit_simulation_result* result) {
  return guarded([&] {
    World& w = require(world, "world")->world;
    host::SimulationSettings settings;
    const graspkit_world* handle = world;
    std::function<void(const World&)> frame;
    if (options) {
      settings.seconds = options->seconds;
      settings.dt = options->dt;
      settings.autograsp = options->autograsp != 0;
      settings.every = options->every;
      if (options->use_gravity)
        settings.gravity = Vector3(options->gravity[0], options->gravity[1], options->gravity[2]);
      if (options->frame) {
        auto* call = options->frame;
        void* user = options->user;
        frame = [call, user, handle](const World&) { call(handle, user); };
      }
    }
    const host::SimulationOutcome outcome = host::simulateWorld(w, settings, frame);
    if (result) {
      result->completed = outcome.completed ? 1 : 0;
      result->steps = outcome.result.steps;
      result->time = w.time();
      result->last = toReport(outcome.result.last);
    }
    if (!outcome.completed) setLastError(GRASPKIT_ERROR_INPUT, outcome.stopReason);
  });
}

graspkit_status graspkit_validate(const graspkit_world* world, double seconds,
                                  graspkit_validation* validation) {
  return guarded([&] {
    const World& w = require(world, "world")->world;
    graspkit_validation& out = *require(validation, "validation");
    ValidationRequest request;
    if (seconds != 0.0) request.seconds = seconds;
    const ValidationResult result = host::validateWorld(w, request);
    out.held = result.held ? 1 : 0;
    out.directions_held = result.directionsHeld;
    out.settle_seconds = result.settleSeconds;
    for (std::size_t k = 0; k < 6; ++k) {
      const DirectionResult& d = result.directions[k];
      graspkit_direction_result& o = out.directions[k];
      for (int i = 0; i < 3; ++i) o.direction[i] = d.direction[i];
      o.held = d.held ? 1 : 0;
      o.slip = d.slip;
      o.turn = d.turn;
      o.seconds = d.seconds;
    }
  });
}

}  // extern "C"
