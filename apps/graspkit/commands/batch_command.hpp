#pragma once
// graspkit batch: its options, its flags and what it does.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <ostream>
#include <string>

#include <CLI/CLI.hpp>

#include "support/load_flags.hpp"

namespace graspkit::cli {

struct BatchOptions {
  std::filesystem::path hand;
  std::filesystem::path objects;  // a folder of body files or a list file
  std::filesystem::path out;
  LoadFlags load;
  int grasps = 20;
  std::int64_t steps = 0;  // default: host::kDefaultPlanSteps, set by addBatchCommand
  std::optional<double> secondsPerObject;
  bool validate = false;
  double validateSeconds = 2.0;
  bool validateAllDirections = false;  // false: a grasp's directions stop at the first let go
  bool validateStatics = false;        // true: directions statics shows held are not simulated
  std::uint64_t seed = 1;
  std::string shard;  // K/N
  double objectTimeout = 1800.0;
  std::optional<int> jobs;  // objects at once in this process (default: the cores)
};

void addBatchCommand(CLI::App& app, BatchOptions& options);
// Exit status 1 when some object of the share failed (after its retry), 0 otherwise.
int runBatch(const BatchOptions& options, bool quiet, std::ostream& out);

}  // namespace graspkit::cli
