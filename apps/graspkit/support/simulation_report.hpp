#pragma once
// What simulate and validate print: how a simulation ended and where everything is.

#include <nlohmann/json.hpp>
#include <ostream>
#include <string>

#include "graspkit/dynamics/dynamics.hpp"
#include "graspkit/dynamics/grasp_validation.hpp"
#include "graspkit/host/simulation_task.hpp"

namespace graspkit::cli {

using host::SimulationOutcome;

nlohmann::json simulationJson(const World& world, const SimulationOutcome& outcome);
void printSimulation(const World& world, const SimulationOutcome& outcome, std::ostream& out);

// A grasp's validation label: held, directions held, and per direction (+x, -x, +y, -y, +z, -z)
// whether it held, the slip (mm), the turn (degrees) and the failure, if the simulation failed.
nlohmann::json validationJson(const ValidationResult& result);
// The label on one line: "held  +x ok (0.1 mm)  -x lost (12.0 mm) ...".
std::string validationLine(const ValidationResult& result);

}  // namespace graspkit::cli
