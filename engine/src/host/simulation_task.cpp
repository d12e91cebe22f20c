#include "graspkit/host/simulation_task.hpp"

#include <fmt/format.h>

#include "graspkit/base/error.hpp"
#include "graspkit/host/invalid_setting.hpp"
#include "graspkit/host/subject.hpp"
#include "graspkit/model/world.hpp"

namespace graspkit::host {

SimulationOutcome simulateWorld(World& world, const SimulationSettings& settings,
                                const std::function<void(const World&)>& frame) {
  if (settings.every < 1)
    throw InvalidSetting(fmt::format("every {} is not valid: 1 step or more", settings.every));
  if (settings.gravity) {
    if (!settings.gravity->allFinite()) throw InvalidSetting("gravity must be finite");
    world.setGravity(*settings.gravity);
  }
  if (settings.autograsp) setClosingTargets(world, defaultHand(world));
  if (frame) frame(world);
  SimulationOutcome outcome;
  SimulateRequest request{.seconds = settings.seconds, .dt = settings.dt};
  request.onStep = [&](const World& w, const StepReport& report) {
    ++outcome.result.steps;
    outcome.result.last = report;
    if (frame && outcome.result.steps % settings.every == 0) frame(w);
    return true;
  };
  try {
    outcome.result = simulate(world, request);
    outcome.completed = true;
    outcome.stopReason = "completed";
  } catch (const DynamicsError& error) {
    outcome.result.time = world.time();
    outcome.stopReason = error.what();
    outcome.failureState = error.state();
  }
  return outcome;
}

ValidationResult validateWorld(const World& world, const ValidationRequest& request) {
  const int hand = defaultHand(world);
  return validateGrasp(world, hand, defaultObject(world).index, request);
}

}  // namespace graspkit::host
