#pragma once
// graspkit batch's unit of work: one object planned in a process of its own.

#include <filesystem>
#include <functional>
#include <string>

#include <nlohmann/json.hpp>

#include "commands/batch_command.hpp"

namespace graspkit::cli {

struct ObjectOutcome {
  bool done = false;
  std::string error;  // why not, when not done
  int grasps = 0, forceClosure = 0, held = 0;
  double seconds = 0.0;
};

nlohmann::json outcomeJson(const ObjectOutcome& outcome);
ObjectOutcome outcomeFromJson(const nlohmann::json& json);

// Plans `object_file` as the batch options say and writes its dataset to `dataset_file`, in a
// child process: an error, a crash, a kill or running past options.objectTimeout is a failed
// outcome, never an exception. `while_waiting`, when given, is called every few milliseconds
// while the child works (an MPI rank serving the others).
ObjectOutcome runObject(const BatchOptions& options, const std::filesystem::path& object_file,
                        const std::filesystem::path& dataset_file,
                        const std::function<void()>& while_waiting = {});

}  // namespace graspkit::cli
