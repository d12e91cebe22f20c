#pragma once
// graspkit simulate: its options, its flags and what it does.

#include <filesystem>
#include <ostream>
#include <string>

#include <CLI/CLI.hpp>

#include "support/load_flags.hpp"

namespace graspkit::cli {

struct SimulateOptions {
  std::filesystem::path world;
  LoadFlags load;
  double seconds = 0.0;  // defaults: the host layer's (host::SimulationSettings)
  double dt = 0.0;
  std::string gravity;  // "X,Y,Z" or "off"; the world's default when empty
  bool autograsp = false;
  std::filesystem::path trajectory;
  int every = 0;
  std::filesystem::path out;
  bool json = false;
};

void addSimulateCommand(CLI::App& app, SimulateOptions& options);
// Steps the world; exit 1 when the simulation stopped on a bad state (the report says why).
int runSimulate(const SimulateOptions& options, std::ostream& out);
// "X,Y,Z" (mm/s^2) or "off"; throws graspkit::Error naming --gravity otherwise.
Vector3 parseGravity(const std::string& text);

}  // namespace graspkit::cli
