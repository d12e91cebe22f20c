#pragma once
// graspkit batch's unit of work: one object planned in a process of its own.

#include <sys/types.h>

#include <chrono>
#include <cstddef>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

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

// One object's process in flight: started when made, its report read as it comes, its outcome
// taken once the report is whole (or the time is up). Killed and reaped if dropped unfinished.
class ObjectProcess {
 public:
  ObjectProcess(const BatchOptions& options, const std::filesystem::path& object_file,
                const std::filesystem::path& dataset_file);
  ~ObjectProcess();
  ObjectProcess(const ObjectProcess&) = delete;
  ObjectProcess& operator=(const ObjectProcess&) = delete;

  // The pipe to poll for the report.
  int channel() const { return channel_; }
  // Seconds before the object's --object-timeout.
  double secondsLeft() const;
  // Reads what the pipe holds (without waiting) and kills the process once its time is up; true
  // when the outcome is ready.
  bool step();
  // The outcome, once step() said it is ready: reaps the process.
  ObjectOutcome finish();

 private:
  std::filesystem::path dataset_;
  double limit_;
  std::chrono::steady_clock::time_point start_;
  pid_t child_ = -1;
  int channel_ = -1;
  std::string report_;
  bool ended_ = false, timedOut_ = false;
};

// One object of the batch's list: where its body file is and where its dataset goes.
struct ObjectJob {
  std::size_t index = 0;
  std::filesystem::path objectFile, datasetFile;
};

// Runs `objects` with up to `parallel` processes at once, in the list's order; `record` gets
// each outcome in this (the parent) process as its object ends, so the caller alone writes the
// manifest. Each process plans on one thread (planGraspDataset), so N at once use N cores.
void runObjects(const BatchOptions& options, const std::vector<ObjectJob>& objects, int parallel,
                const std::function<void(std::size_t index, const ObjectOutcome&)>& record);

}  // namespace graspkit::cli
