#pragma once
// Simulation and validation as every front end offers them: the settings with one set of
// defaults, and a run that reports a simulation that blew up as an outcome (what stopped it and
// the state before the failed step) rather than as an exception, so that a front end can print,
// return or store it.

#include <array>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "graspkit/dynamics/dynamics.hpp"
#include "graspkit/dynamics/grasp_validation.hpp"
#include "graspkit/math/transform.hpp"

namespace graspkit::host {

struct SimulationSettings {
  double seconds = 1.0;
  double dt = kDefaultTimeStep;
  std::optional<Vector3> gravity;  // mm/s^2; the world's own when unset
  // Drive the first hand's DOFs towards their closing limits (the dynamic autograsp).
  bool autograsp = false;
  int every = 10;  // steps between trajectory frames
};

struct SimulationOutcome {
  bool completed = false;
  SimulateResult result;
  std::string stopReason;    // "completed", or the error that stopped the simulation
  std::string failureState;  // the state before the failed step (JSON), when it failed
};

// Applies the settings to `world` (gravity, autograsp targets), then steps it. `frame` (may be
// empty) is called with the world before the first step and after every `every` steps. A
// DynamicsError ends the run as a failed outcome; bad settings (a dt out of range, every < 1, a
// world with no hand for autograsp) throw graspkit::Error.
SimulationOutcome simulateWorld(World& world, const SimulationSettings& settings,
                                const std::function<void(const World&)>& frame = {});

// The validation directions, in ValidationResult::directions' order.
inline constexpr std::array<std::string_view, 6> kValidationDirections = {"+x", "-x", "+y",
                                                                          "-y", "+z", "-z"};

// Validates the grasp a world holds: its first hand closed on its first graspable body (the
// world a plan's grasp or a dataset's grasp stands for). Throws graspkit::Error when the world
// has no hand or no graspable body.
ValidationResult validateWorld(const World& world, const ValidationRequest& request = {});

}  // namespace graspkit::host
