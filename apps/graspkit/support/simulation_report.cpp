#include "support/simulation_report.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "graspkit/model/world.hpp"

namespace graspkit::cli {

using nlohmann::json;

using host::kValidationDirections;

json validationJson(const ValidationResult& result) {
  json directions = json::array();
  for (int k = 0; k < 6; ++k) {
    const DirectionResult& d = result.directions[k];
    json entry = {{"direction", kValidationDirections[k]},
                  {"held", d.held},
                  {"slip_mm", d.slip},
                  {"turn_deg", d.turn * 180.0 / M_PI},
                  {"seconds", d.seconds},
                  {"by_statics", d.byStatics}};
    if (!d.failure.empty()) entry["failure"] = d.failure;
    directions.push_back(entry);
  }
  return {{"held", result.held},
          {"directions_held", result.directionsHeld},
          {"settle_seconds", result.settleSeconds},
          {"directions", directions}};
}

std::string validationLine(const ValidationResult& result) {
  std::string line = result.held ? "held" : "not held";
  for (int k = 0; k < 6; ++k) {
    const DirectionResult& d = result.directions[k];
    if (d.byStatics) {
      line += fmt::format("  {} ok (statics)", kValidationDirections[k]);
      continue;
    }
    line += fmt::format("  {} {} ({:.1f} mm, {:.0f} deg)", kValidationDirections[k],
                        d.held ? "ok" : "lost", d.slip, d.turn * 180.0 / M_PI);
  }
  return line;
}

json simulationJson(const World& world, const SimulationOutcome& outcome) {
  json report = json::parse(dynamicStateJson(world));
  report["completed"] = outcome.completed;
  report["stop_reason"] = outcome.stopReason;
  report["steps"] = outcome.result.steps;
  report["contacts"] = outcome.result.last.contacts;
  report["active_contacts"] = outcome.result.last.activeContacts;
  if (!outcome.completed) report["failure_state"] = json::parse(outcome.failureState);
  return report;
}

void printSimulation(const World& world, const SimulationOutcome& outcome, std::ostream& out) {
  out << fmt::format("t = {:.4f} s after {} steps: {}\n", world.time(), outcome.result.steps,
                     outcome.stopReason);
  for (const Body& body : world.bodies()) {
    if (!body.isDynamic()) continue;
    const Vector3 p = body.pose.translation();
    out << fmt::format("  {}: position {:.3f} {:.3f} {:.3f} mm, speed {:.3f} mm/s\n", body.name,
                       p.x(), p.y(), p.z(), body.state.v.head<3>().norm());
  }
  for (int r = 0; r < world.robotCount(); ++r) {
    const auto values = world.robot(r).dofValues();
    out << fmt::format("  {}: DOFs {:.4f}\n", world.robot(r).name(),
                       fmt::join(values.begin(), values.end(), " "));
  }
  out << fmt::format("  {} contacts, {} pushing\n", outcome.result.last.contacts,
                     outcome.result.last.activeContacts);
}

}  // namespace graspkit::cli
