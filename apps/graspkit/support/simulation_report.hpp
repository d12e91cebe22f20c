#pragma once
// What simulate and validate print: how a simulation ended and where everything is.

#include <nlohmann/json.hpp>
#include <ostream>
#include <string>

#include "graspkit/dynamics/dynamics.hpp"
#include "graspkit/dynamics/grasp_validation.hpp"

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

// A grasp's validation label: held, directions held, and per direction (+x, -x, +y, -y, +z, -z)
// whether it held, the slip (mm), the turn (degrees) and the failure, if the simulation failed.
nlohmann::json validationJson(const ValidationResult& result);
// The label on one line: "held  +x ok (0.1 mm)  -x lost (12.0 mm) ...".
std::string validationLine(const ValidationResult& result);

}  // namespace graspkit::cli
