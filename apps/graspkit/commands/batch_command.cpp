// graspkit batch: plan (and optionally validate) grasps on many objects with one hand, one HDF5
// dataset file per object (io/grasp_dataset_file.hpp), with a manifest that makes a re-run
// resume. Each object runs in a child process (batch_object.cpp), so that a crash, a hang or an
// error on one object is recorded against it and the batch goes on; under mpirun the objects are
// shared over the ranks (batch/batch_mpi.cpp); batch/shard.cpp chooses this process's share
// (Slurm), batch/object_list.cpp reads the objects. What stays here: the flags, the manifest and
// the run. `--jobs N` keeps N objects' processes in flight at once (each plans on one thread); the
// manifest is written by this process alone, and holds nothing that depends on timing or order,
// so any --jobs gives the same files. Wall times go to timings.json beside it.

#include <fmt/format.h>
#include <sched.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <sstream>
#include <thread>

#include "batch/batch_mpi.hpp"
#include "batch/batch_object.hpp"
#include "batch/object_list.hpp"
#include "batch/shard.hpp"
#include "commands/batch_command.hpp"
#include "graspkit/base/error.hpp"
#include "graspkit/base/input_file.hpp"
#include "graspkit/base/output_file.hpp"
#include "graspkit/base/utf8.hpp"
#include "graspkit/base/version.hpp"
#include "graspkit/dataset/dataset_planning.hpp"
#include "graspkit/host/plan_task.hpp"
#include "graspkit/io/dataset/grasp_dataset_file.hpp"
#include "support/argument_checks.hpp"
#include "support/process_runs.hpp"
#include "support/progress_reporter.hpp"

namespace graspkit::cli {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr int kManifestVersion = 1;
constexpr int kMaxAttempts = 2;  // a failed object is retried once

// `options`, once the paths the manifest records are found to be UTF-8.
const BatchOptions& utf8Checked(const BatchOptions& options) {
  requireUtf8(options.hand.string(), {}, "--hand");
  requireUtf8(options.objects.string(), {}, "--objects");
  requireUtf8(options.out.string(), {}, "--out");
  return options;
}

// The load flags that change the hand itself (its palm, closing directions, materials, switched-off
// pairs, collision shapes), as given; empty when none is. Roots and package paths only say where
// files are found, which may differ between the machines that resume one run.
json handShapingFlags(const LoadFlags& load) {
  json flags = json::object();
  if (load.genericRobots) flags["generic_robots"] = true;
  if (!load.palm.empty()) flags["palm"] = load.palm;
  if (!load.material.empty()) flags["urdf_material"] = load.material;
  if (!load.linkMaterials.empty()) flags["link_materials"] = load.linkMaterials;
  if (!load.closing.empty()) flags["close"] = load.closing;
  if (!load.srdf.empty()) flags["srdf"] = fs::absolute(load.srdf).lexically_normal().string();
  if (load.mjcfExactMeshes) flags["mjcf_exact_meshes"] = true;
  return flags;
}

// What a dataset depends on: a manifest written with other settings cannot be resumed.
json settingsJson(const BatchOptions& options) {
  json settings = {{"hand", fs::absolute(options.hand).lexically_normal().string()},
                   {"objects", fs::absolute(options.objects).lexically_normal().string()},
                   {"grasps", options.grasps},
                   {"seed", options.seed},
                   {"validate", options.validate}};
  if (options.secondsPerObject)
    settings["seconds_per_object"] = *options.secondsPerObject;
  else
    settings["steps_per_object"] = options.steps;
  if (options.validate) {
    settings["validate_seconds"] = options.validateSeconds;
    settings["validate_all_directions"] = options.validateAllDirections;
    // Only when set, so that manifests written before the flag existed still resume.
    if (options.validateStatics) settings["validate_statics"] = true;
  }
  // Also only when given: a hand loaded otherwise is another hand.
  if (json hand = handShapingFlags(options.load); !hand.empty()) settings["hand_options"] = hand;
  return settings;
}

}  // namespace

void addBatchCommand(CLI::App& app, BatchOptions& options) {
  CLI::App* cmd = app.add_subcommand(
      "batch",
      "Plan grasps on many objects with one hand: one HDF5 dataset file per object and a "
      "manifest; running the same command again resumes");
  cmd->add_option("--hand", options.hand, "The hand's robot file (GraspIt! XML or URDF)")
      ->required()
      ->check(existingFile());
  cmd->add_option("--objects", options.objects,
                  "A folder of body files (objects.txt's order when it has one) or a list file")
      ->required()
      ->check(CLI::ExistingPath);
  cmd->add_option("--out", options.out, "The dataset folder")->required();
  addLoadFlags(*cmd, options.load);
  const DatasetRequest defaults;  // one object's dataset, as the host layer plans it
  cmd->add_option("--grasps", options.grasps, "Grasps kept per object (the best list's size)")
      ->default_val(defaults.grasps)
      ->check(CLI::Range(1, 10000));
  auto* steps = cmd->add_option("--steps", options.steps, "Planner steps per object")
                    ->default_val(host::kDefaultPlanSteps)
                    ->check(CLI::Range(std::int64_t{1}, std::int64_t{1} << 40));
  cmd->add_option("--seconds-per-object", options.secondsPerObject,
                  "Plan each object for this long instead (not reproducible: depends on speed)")
      ->excludes(steps)
      ->check(positiveFinite());
  cmd->add_flag("--validate", options.validate,
                "Label each grasp physically (graspkit validate: 6 directions)");
  cmd->add_option("--validate-seconds", options.validateSeconds,
                  "--validate: simulated seconds per direction")
      ->default_val(defaults.validateSeconds)
      ->check(positiveFinite());
  cmd->add_flag("--validate-all-directions", options.validateAllDirections,
                "--validate: try all six directions of every grasp (by default a grasp's "
                "directions stop at the first it lets go: the same held label, the rest untried)");
  cmd->add_flag("--validate-statics", options.validateStatics,
                "--validate: a direction that statics shows the grasp bears with margins is held "
                "after a 0.025 s probe instead of a run to rest (graspkit validate --statics)");
  cmd->add_option("--seed", options.seed, "The planner's seed, the same for every object")
      ->check(seedNumber())
      ->default_val(defaults.seed);
  cmd->add_option("--shard", options.shard,
                  "K/N: take every N-th object from the K-th (default: a Slurm job array's task "
                  "from SLURM_ARRAY_TASK_ID and SLURM_ARRAY_TASK_COUNT, else all)");
  cmd->add_option("--object-timeout", options.objectTimeout,
                  "Seconds an object may take before it is killed and recorded as failed")
      ->check(positiveFinite())
      ->default_val(1800.0);
  cmd->add_option("--jobs,-j", options.jobs,
                  "Objects planned at once, each in its own process on one thread (default: the "
                  "CPUs this command may use); the files do not depend on it")
      ->check(CLI::Range(1, 4096));
}

namespace {

// Temporaries a killed run left behind (".NAME.h5.PID.tmp" whose process is gone).
void removeStaleTemporaries(const fs::path& folder) {
  std::error_code missing;
  for (const auto& entry : fs::directory_iterator(folder, missing)) {
    const std::string name = entry.path().filename().string();
    if (name.empty() || name[0] != '.' || entry.path().extension() != ".tmp") continue;
    const std::string stem = entry.path().stem().string();  // .NAME.h5.PID
    const pid_t pid = static_cast<pid_t>(std::atol(stem.substr(stem.rfind('.') + 1).c_str()));
    if (!processRuns(pid)) {
      std::error_code ignored;
      fs::remove(entry.path(), ignored);
    }
  }
}

// writeFileAtomically()'s temporary "FILE.tmpPID" that a killed run of this shard left behind
// (killed between naming its written copy and renaming it over FILE): each shard's manifest and
// timings are written by that shard's run alone, so another's is never touched.
void removeStaleTemporariesOf(const fs::path& file) {
  const std::string prefix = file.filename().string() + ".tmp";
  std::error_code missing;
  for (const auto& entry : fs::directory_iterator(file.parent_path(), missing)) {
    const std::string name = entry.path().filename().string();
    if (name.size() <= prefix.size() || name.compare(0, prefix.size(), prefix) != 0) continue;
    const std::string digits = name.substr(prefix.size());
    if (digits.size() > 9 ||
        !std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; }))
      continue;
    std::error_code ignored;
    if (entry.is_regular_file(ignored) && !processRuns(static_cast<pid_t>(std::stol(digits))))
      fs::remove(entry.path(), ignored);
  }
}

// What a run of the batch keeps: the objects, this share of them, and on the rank that writes it,
// the manifest and the counts for the summary.
class BatchRun {
 public:
  BatchRun(const BatchOptions& options, bool quiet)
      : options_(options),
        quiet_(quiet),
        shard_(shardOf(options.shard)),
        files_(objectFiles(utf8Checked(options).objects)),
        names_(objectNames(files_)) {}

  const fs::path& file(std::size_t i) const { return files_[i]; }
  fs::path dataset(std::size_t i) const { return options_.out / "grasps" / (names_[i] + ".h5"); }

  // Reads (or starts) the manifest and returns this share's objects still to run; the others
  // are counted as settled. Only the rank that writes the manifest calls it.
  std::vector<std::size_t> prepare() {
    createOutputFolder(options_.out / "grasps");
    removeStaleTemporaries(options_.out / "grasps");
    manifest_file_ = options_.out / shardFileName("manifest", shard_.index + 1);
    timings_file_ = options_.out / shardFileName("timings", shard_.index + 1);
    removeStaleTemporariesOf(manifest_file_);
    removeStaleTemporariesOf(timings_file_);
    timings_ = {{"objects", json::object()}};
    if (fs::exists(timings_file_)) {  // informative only: a file that does not parse is replaced
      const json previous = json::parse(readInputFile(timings_file_), nullptr, false);
      if (previous.is_object() && previous.contains("objects") && previous["objects"].is_object())
        timings_["objects"] = previous["objects"];
    }
    const json settings = settingsJson(options_);
    manifest_ = {{"manifest_version", kManifestVersion},
                 {"engine_version", engineVersion()},
                 {"settings", settings},
                 {"shard", {{"index", shard_.index + 1}, {"count", shard_.count}}},
                 {"objects", json::object()}};
    if (fs::exists(manifest_file_)) {
      const json previous = json::parse(readInputFile(manifest_file_), nullptr, false);
      if (previous.is_discarded() || !previous.contains("objects"))
        throw Error(SourceLocation{manifest_file_.string()}, "not a batch manifest");
      if (previous.value("settings", json()) != settings)
        throw Error(SourceLocation{manifest_file_.string()},
                    fmt::format("the folder holds a batch run with other settings ({}); use "
                                "another --out, or the same settings to resume",
                                previous.value("settings", json()).dump()));
      checkManifestObjects(previous["objects"]);
      manifest_["objects"] = previous["objects"];
    }
    std::vector<std::size_t> pending;
    for (std::size_t i = 0; i < files_.size(); ++i) {
      if (static_cast<int>(i % static_cast<std::size_t>(shard_.count)) != shard_.index) continue;
      ++share_;
      const json& entry = entryOf(i);
      const std::string status = entry.value("status", "");
      if (status == "done" && datasetLoads(dataset(i))) {
        ++done_, ++settled_;
      } else if (status == "failed" && entry.value("attempts", 0) >= kMaxAttempts) {
        ++failed_, ++settled_;
        failures_.push_back(fmt::format("{}: {}", names_[i], entry.value("error", "")));
      } else {
        pending.push_back(i);
      }
    }
    pending_ = pending.size();
    writeFileAtomically(manifest_file_, manifest_.dump(2) + "\n");
    return pending;
  }

  // Enters one object's outcome in the manifest (written at once) and reports progress.
  void record(std::size_t i, const ObjectOutcome& outcome) {
    json& entry = entryOf(i);
    const int attempts = entry.value("attempts", 0) + 1;
    entry = {{"file", files_[i].string()},
             {"status", outcome.done ? "done" : "failed"},
             {"attempts", attempts}};
    if (outcome.done) {
      ++done_;
      entry["dataset"] = (fs::path("grasps") / (names_[i] + ".h5")).string();
      entry["grasps"] = outcome.grasps;
      entry["force_closure"] = outcome.forceClosure;
      if (options_.validate) entry["held"] = outcome.held;
    } else {
      ++failed_;
      entry["error"] = outcome.error;
      failures_.push_back(fmt::format("{}: {}", names_[i], outcome.error));
    }
    writeFileAtomically(manifest_file_, manifest_.dump(2) + "\n");
    timings_["objects"][names_[i]] = {{"seconds", outcome.seconds}, {"jobs", workers_}};
    writeFileAtomically(timings_file_, timings_.dump(2) + "\n");
    ++ran_;
    spent_ += outcome.seconds;
    if (quiet_) return;
    const double eta = spent_ / ran_ * static_cast<double>(pending_ - ran_) / workers_;
    std::cerr << fmt::format(
        "graspkit: [{}/{}] {}: {} ({:.1f} s), {} left\n", ran_, pending_, names_[i],
        outcome.done
            ? fmt::format("{} grasps, {} force closure", outcome.grasps, outcome.forceClosure)
            : "failed: " + outcome.error,
        outcome.seconds, clockTime(eta));
  }

  void setWorkers(int workers) { workers_ = std::max(1, workers); }

  // This share's objects still to run, as runObjects takes them.
  std::vector<ObjectJob> jobs(const std::vector<std::size_t>& pending) const {
    std::vector<ObjectJob> jobs;
    for (std::size_t i : pending) jobs.push_back({i, files_[i], dataset(i)});
    return jobs;
  }

  // Once every shard has written its manifest, manifest.json gathers them (each shard's run
  // writes it as it ends; the last to end writes the whole set). A later run without --shard
  // then resumes from it.
  void mergeShards(std::ostream& out) const {
    if (shard_.count == 1) return;
    json merged = {{"manifest_version", kManifestVersion}, {"engine_version", engineVersion()},
                   {"settings", settingsJson(options_)},   {"shard", {{"index", 1}, {"count", 1}}},
                   {"merged_from", json::array()},         {"objects", json::object()}};
    json timings = {{"objects", json::object()}};
    for (int k = 1; k <= shard_.count; ++k) {
      const fs::path file = options_.out / shardFileName("manifest", k);
      if (!fs::exists(file)) return;  // a shard has not run yet
      const json part = json::parse(readInputFile(file), nullptr, false);
      if (part.is_discarded() || part.value("settings", json()) != merged["settings"]) return;
      merged["merged_from"].push_back(file.filename().string());
      for (const auto& [name, entry] : part["objects"].items()) merged["objects"][name] = entry;
      const fs::path part_timings = options_.out / shardFileName("timings", k);
      const json times = fs::exists(part_timings)
                             ? json::parse(readInputFile(part_timings), nullptr, false)
                             : json();
      if (times.is_object() && times.contains("objects") && times["objects"].is_object())
        for (const auto& [name, entry] : times["objects"].items()) timings["objects"][name] = entry;
    }
    int done = 0;
    for (const auto& [name, entry] : merged["objects"].items())
      done += entry.value("status", "") == "done" ? 1 : 0;
    writeFileAtomically(options_.out / "manifest.json", merged.dump(2) + "\n");
    writeFileAtomically(options_.out / "timings.json", timings.dump(2) + "\n");
    out << fmt::format("merged {} shard manifests into {}: {} of {} objects done\n", shard_.count,
                       (options_.out / "manifest.json").string(), done, files_.size());
  }

  // The summary; the exit status (1 when some object failed).
  int summary(std::ostream& out) const {
    removeStaleTemporaries(options_.out / "grasps");  // a writer that died during this run
    out << fmt::format(
        "{} objects: {} done, {} failed{}; manifest {}\n", share_, done_, failed_,
        settled_ ? fmt::format(" ({} already settled before this run)", settled_) : "",
        manifest_file_.string());
    for (const std::string& failure : failures_) out << "  failed " << failure << "\n";
    mergeShards(out);
    return failed_ > 0 ? 1 : 0;
  }

 private:
  // A manifest's "objects" as batch writes it: an object of entries, each an object whose
  // status is a string and attempts a whole number. A tampered manifest is bad input.
  void checkManifestObjects(const json& objects) const {
    auto refuse = [&](const std::string& what) {
      throw Error(SourceLocation{manifest_file_.string(), 0, "objects"},
                  "not a batch manifest: " + what);
    };
    if (!objects.is_object()) refuse("\"objects\" is not an object of entries");
    for (const auto& [name, entry] : objects.items()) {
      if (!entry.is_object()) refuse(fmt::format("entry '{}' is not an object", name));
      if (entry.contains("status") && !entry["status"].is_string())
        refuse(fmt::format("entry '{}': status is not a string", name));
      if (entry.contains("attempts") && !entry["attempts"].is_number_integer())
        refuse(fmt::format("entry '{}': attempts is not a whole number", name));
      if (entry.contains("error") && !entry["error"].is_string())
        refuse(fmt::format("entry '{}': error is not a string", name));
    }
  }

  // A dataset marked done counts only when it loads: a truncated or replaced file is planned
  // again rather than kept.
  static bool datasetLoads(const fs::path& file) {
    try {
      loadGraspDataset(file);
      return true;
    } catch (const Error&) {
      return false;
    }
  }

  // "manifest.json", or "manifest-K-of-N.json" for shard K of a split run.
  fs::path shardFileName(const std::string& stem, int k) const {
    if (shard_.count == 1) return stem + ".json";
    return fmt::format("{}-{}-of-{}.json", stem, k, shard_.count);
  }

  json& entryOf(std::size_t i) {
    json& entry = manifest_["objects"][names_[i]];
    if (!entry.is_object()) entry = json::object();
    return entry;
  }

  const BatchOptions& options_;
  bool quiet_;
  Shard shard_;
  std::vector<fs::path> files_;
  std::vector<std::string> names_;
  fs::path manifest_file_, timings_file_;
  json manifest_, timings_;
  std::size_t share_ = 0, pending_ = 0, ran_ = 0;
  int done_ = 0, failed_ = 0, settled_ = 0, workers_ = 1;
  double spent_ = 0.0;
  std::vector<std::string> failures_;
};

// The CPUs this process may run on: the machine's cores, or fewer under taskset or a Slurm task's
// binding.
int usableCores() {
  cpu_set_t set;
  if (::sched_getaffinity(0, sizeof set, &set) == 0) return std::max(1, CPU_COUNT(&set));
  return static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

// The objects in child processes of this one, `jobs` at a time.
int runLocally(BatchRun& run, const BatchOptions& options, std::ostream& out) {
  const int jobs = options.jobs.value_or(usableCores());
  const std::vector<std::size_t> pending = run.prepare();
  run.setWorkers(std::min<int>(jobs, static_cast<int>(std::max<std::size_t>(1, pending.size()))));
  runObjects(options, run.jobs(pending), jobs,
             [&](std::size_t i, const ObjectOutcome& outcome) { run.record(i, outcome); });
  return run.summary(out);
}

// Every rank plans; rank 0 also keeps the manifest. An error on rank 0 before the objects are
// shared out (a manifest with other settings) stops every rank.
int runOverMpi(BatchRun& run, const BatchOptions& options, std::ostream& out) {
  if (options.jobs.value_or(1) != 1)
    throw Error(
        "--jobs: under mpirun each rank plans one object at a time; choose the ranks "
        "with mpirun -np instead");
  const MpiBatch mpi;
  std::vector<std::size_t> pending;
  std::string error;
  if (mpi.rank() == 0) {
    try {
      pending = run.prepare();
      run.setWorkers(mpi.size());
    } catch (const std::exception& e) {
      error = e.what();
    }
  }
  if (!mpi.agree(error.empty())) {
    if (mpi.rank() == 0) throw Error(error);
    return 1;
  }
  mpi.run(
      pending,
      [&](std::size_t i, const std::function<void()>& serve) {
        return runObject(options, run.file(i), run.dataset(i), serve);
      },
      [&](std::size_t i, const ObjectOutcome& outcome) { run.record(i, outcome); });
  return mpi.rank() == 0 ? run.summary(out) : 0;
}

}  // namespace

int runBatch(const BatchOptions& options, bool quiet, std::ostream& out) {
  BatchRun run(options, quiet);
  return launchedByMpi() ? runOverMpi(run, options, out) : runLocally(run, options, out);
}

}  // namespace graspkit::cli
