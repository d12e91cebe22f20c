#pragma once
// What simulate and validate print: how a simulation ended and where everything is.

#include <nlohmann/json.hpp>
#include <ostream>
#include <string>

#include "graspkit/dynamics.hpp"

namespace graspkit::cli {

struct SimulationOutcome {
  bool completed = false;
  SimulateResult result;
  std::string stopReason;    // "completed", or the error that stopped the simulation
  std::string failureState;  // the state before the failed step (JSON), when it failed
};

// Runs simulate(); a DynamicsError becomes a failed outcome instead of an exception.
SimulationOutcome runSimulation(World& world, const SimulateRequest& request);

nlohmann::json simulationJson(const World& world, const SimulationOutcome& outcome);
void printSimulation(const World& world, const SimulationOutcome& outcome, std::ostream& out);

}  // namespace graspkit::cli
