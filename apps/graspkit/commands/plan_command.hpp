#pragma once
// graspkit plan: its options, its flags and what it does.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "support/load_flags.hpp"

namespace graspkit::cli {

struct PlanOptions {
  std::filesystem::path world;
  LoadFlags load;
  std::string robot;   // name or 0-based index; the world's first hand when empty
  std::string object;  // the first graspable body when empty
  // Defaults: the host layer's (host::PlanSettings), set by addPlanCommand.
  std::string planner;
  std::string energy;
  std::string space;
  std::string posture;
  std::optional<std::string> mode;  // simann only; the host layer's default when unset
  std::string preset;               // the planner's default when empty
  std::vector<std::string> set;     // KEY=VALUE planner options
  std::optional<std::int64_t> steps;
  std::optional<double> seconds;
  std::optional<int> threads;  // every core when unset
  std::uint64_t seed = 0;
  int top = 0;
  bool validate = false;  // label each grasp physically (graspkit validate)
  double validateSeconds = 0.0;
  bool json = false;
  std::filesystem::path out;
};

void addPlanCommand(CLI::App& app, PlanOptions& options);
// Prints the best grasps as a table (or JSON); with --out also writes the JSON and one world
// file per grasp. Progress goes to stderr: a redrawn line with percentage and ETA on a
// terminal, a plain line every few seconds otherwise (unless quiet).
int runPlan(const PlanOptions& options, bool quiet, std::ostream& out);

}  // namespace graspkit::cli
