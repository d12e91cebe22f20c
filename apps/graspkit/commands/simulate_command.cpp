// graspkit simulate: step a world's dynamics and report where everything ended up, and why the
// simulation stopped.

#include <fmt/format.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "commands/simulate_command.hpp"
#include "graspkit/base/error.hpp"
#include "graspkit/base/output_file.hpp"
#include "graspkit/dynamics/dynamics.hpp"
#include "graspkit/host/simulation_task.hpp"
#include "graspkit/io/graspit/world_file.hpp"
#include "graspkit/model/world.hpp"
#include "support/argument_checks.hpp"
#include "support/simulation_report.hpp"

namespace graspkit::cli {
namespace {

using nlohmann::json;

}  // namespace

Vector3 parseGravity(const std::string& text) {
  if (text == "off") return Vector3::Zero();
  const std::vector<double> v = parseNumberList(text, "--gravity");
  if (v.size() != 3) {
    throw Error(
        fmt::format("--gravity: expected X,Y,Z in mm/s^2 or 'off', got {} numbers", v.size()));
  }
  return Vector3(v[0], v[1], v[2]);
}

void addSimulateCommand(CLI::App& app, SimulateOptions& options) {
  CLI::App* cmd = app.add_subcommand("simulate", "Step a world's dynamics (gravity on by default)");
  cmd->add_option("world", options.world, "World XML")->required()->check(existingFile());
  addLoadFlags(*cmd, options.load);
  const host::SimulationSettings defaults;  // every default is the host layer's
  cmd->add_option("--seconds", options.seconds, "Simulated time, s")->default_val(defaults.seconds);
  cmd->add_option("--dt", options.dt, "Time step, s")->default_val(defaults.dt);
  cmd->add_option("--gravity", options.gravity,
                  "Gravity X,Y,Z in mm/s^2, or 'off' as in GraspIt! (default 0,0,-9810)");
  cmd->add_flag("--autograsp", options.autograsp,
                "Drive the first hand's DOFs towards their closed limits (dynamic autograsp)");
  cmd->add_option("--trajectory", options.trajectory,
                  "Write the state every --every steps, one JSON object per line");
  cmd->add_option("--every", options.every, "Steps between trajectory lines")
      ->default_val(defaults.every);
  cmd->add_option("--out", options.out, "Save the final world as a world XML");
  cmd->add_flag("--json", options.json, "Print one JSON object");
}

int runSimulate(const SimulateOptions& options, std::ostream& out) {
  World world = loadWorldFile(options.world, options.load.options());
  host::SimulationSettings settings{.seconds = options.seconds,
                                    .dt = options.dt,
                                    .autograsp = options.autograsp,
                                    .every = options.every};
  if (!options.gravity.empty()) settings.gravity = parseGravity(options.gravity);

  std::ofstream trajectory;
  if (!options.trajectory.empty()) {
    trajectory.open(options.trajectory);
    if (!trajectory) throw Error(fmt::format("cannot write {}", options.trajectory.string()));
  }
  const SimulationOutcome outcome = host::simulateWorld(world, settings, [&](const World& w) {
    if (trajectory.is_open()) trajectory << dynamicStateJson(w) << "\n";
  });
  if (trajectory.is_open()) {
    trajectory.flush();
    if (!trajectory) throw Error(fmt::format("cannot write {}", options.trajectory.string()));
  }
  if (!options.out.empty() && outcome.completed) saveWorldFile(world, options.out);
  const json report = simulationJson(world, outcome);
  if (options.json) {
    out << report.dump(2) << "\n";
  } else {
    printSimulation(world, outcome, out);
  }
  return outcome.completed ? 0 : 1;
}

}  // namespace graspkit::cli
