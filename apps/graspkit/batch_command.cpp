// graspkit batch: plan (and optionally validate) grasps on many objects with one hand, one HDF5
// dataset file per object (io/grasp_dataset_file.hpp), with a manifest that makes a re-run
// resume. Each object runs in a child process, so that a crash, a hang or an error on one object
// is recorded against it and the batch goes on.

#include <fmt/format.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <iostream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "commands.hpp"
#include "graspkit/error.hpp"
#include "graspkit/grasp_validation.hpp"
#include "graspkit/io/body_file.hpp"
#include "graspkit/io/grasp_dataset_file.hpp"
#include "graspkit/io/input_file.hpp"
#include "graspkit/io/output_file.hpp"
#include "graspkit/io/world_file.hpp"
#include "graspkit/planning/planner.hpp"
#include "graspkit/planning/search_space.hpp"
#include "graspkit/registry.hpp"
#include "graspkit/version.hpp"
#include "graspkit/world.hpp"
#include "progress_reporter.hpp"

namespace graspkit::cli {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using Clock = std::chrono::steady_clock;

constexpr int kManifestVersion = 1;
constexpr int kMaxAttempts = 2;  // a failed object is retried once

struct Shard {
  int index = 0;  // 0-based
  int count = 1;
};

// --shard K/N (1-based K), else a Slurm job array's task, else the whole set.
Shard shardOf(const std::string& text) {
  Shard shard;
  if (!text.empty()) {
    int k = 0, n = 0;
    char tail = 0;
    if (std::sscanf(text.c_str(), "%d/%d%c", &k, &n, &tail) != 2 || n < 1 || k < 1 || k > n)
      throw Error(fmt::format("--shard: '{}' is not K/N with 1 <= K <= N", text));
    return {k - 1, n};
  }
  const char* id = std::getenv("SLURM_ARRAY_TASK_ID");
  const char* count = std::getenv("SLURM_ARRAY_TASK_COUNT");
  const char* min = std::getenv("SLURM_ARRAY_TASK_MIN");
  if (id && count) {
    const int first = min ? std::atoi(min) : 0;
    shard = {std::atoi(id) - first, std::atoi(count)};
    if (shard.count < 1 || shard.index < 0 || shard.index >= shard.count)
      throw Error(
          fmt::format("SLURM_ARRAY_TASK_ID={} of SLURM_ARRAY_TASK_COUNT={} (first {}) "
                      "is not a task of the array",
                      id, count, first));
  }
  return shard;
}

// The object files: every .xml body file of a folder (objects.txt's order when it has one), or
// the lines of a list file (# starts a comment; paths relative to the list's folder).
std::vector<fs::path> objectFiles(const fs::path& source) {
  fs::path list = source;
  if (fs::is_directory(source)) {
    list = source / "objects.txt";
    if (!fs::exists(list)) {
      std::vector<fs::path> files;
      for (const auto& entry : fs::directory_iterator(source))
        if (entry.path().extension() == ".xml") files.push_back(entry.path());
      std::sort(files.begin(), files.end());
      if (files.empty())
        throw Error(SourceLocation{source.string()}, "--objects: the folder holds no .xml file");
      return files;
    }
  }
  std::vector<fs::path> files;
  std::istringstream lines(readInputFile(list));
  std::string line;
  int number = 0;
  while (std::getline(lines, line)) {
    ++number;
    line = line.substr(0, line.find('#'));
    line.erase(0, line.find_first_not_of(" \t\r"));
    line.erase(line.find_last_not_of(" \t\r") + 1);
    if (line.empty()) continue;
    const fs::path file = fs::path(line).is_absolute() ? fs::path(line) : list.parent_path() / line;
    files.push_back(file.lexically_normal());
  }
  if (files.empty()) throw Error(SourceLocation{list.string()}, "--objects: the list is empty");
  return files;
}

// Object names are the files' stems, made unique.
std::vector<std::string> objectNames(const std::vector<fs::path>& files) {
  std::vector<std::string> names;
  std::set<std::string> used;
  for (const fs::path& file : files) {
    std::string name = file.stem().string();
    for (int k = 2; !used.insert(name).second; ++k)
      name = fmt::format("{}_{}", file.stem().string(), k);
    names.push_back(name);
  }
  return names;
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
  if (options.validate) settings["validate_seconds"] = options.validateSeconds;
  return settings;
}

// One object's dataset: the hand over the object at the origin, a plan, its grasps closed and
// measured, optionally validated. Runs in the child.
GraspDataset planObject(const BatchOptions& options, const fs::path& object_file) {
  const LoadOptions load = options.load.options();
  auto world = std::make_shared<World>(loadAnyFile(options.hand, load));
  if (world->robotCount() != 1 || !world->bodies().empty())
    throw Error(SourceLocation{options.hand.string()}, "--hand: not a robot file");
  Body object;
  object.model = loadBodyFile(object_file);
  object.kind = BodyKind::Graspable;
  object.name = object.model->name.empty() ? object_file.stem().string() : object.model->name;
  object.filename = object_file;
  const int object_index = world->addBody(object);
  Transform above = Transform::Identity();
  above.translation() = Vector3(0, 0, 300);
  world->setRobotPose(0, above);

  PlanningRequest request;
  request.world = world;
  request.robot = 0;
  request.object = BodyRef::body(object_index);
  request.position = parsePositionSpace("axis-angle");
  request.posture = parsePostureSpace("eigen");
  request.energy = "contact";
  request.seed = options.seed;
  request.threads = 1;  // objects run side by side; one thread each keeps plans reproducible
  request.bestListSize = options.grasps;
  request.options = {{"mode", "restarts"}};
  auto planner = Registry::global().makePlanner("simann", request);
  PlanningBudget budget;
  if (options.secondsPerObject)
    budget.seconds = *options.secondsPerObject;
  else
    budget.steps = options.steps;
  PlanningRun run = runPlanner(*planner, budget);
  finishGrasps(request, run.grasps, 1);

  std::vector<int> held(run.grasps.size(), -1);
  if (options.validate) {
    ValidationRequest validation;
    validation.seconds = options.validateSeconds;
    std::vector<World> worlds;
    for (const PlannedGrasp& g : run.grasps) worlds.push_back(graspWorld(request, g));
    const auto labels = validateGrasps(worlds, 0, object_index, validation, 1);
    for (std::size_t i = 0; i < labels.size(); ++i) held[i] = labels[i].held ? 1 : 0;
  }

  GraspDataset dataset;
  dataset.objectFile = object_file.string();
  dataset.objectName = object.name;
  dataset.objectMass = object.model->mass;
  dataset.handFile = options.hand.string();
  dataset.handName = world->robot(0).name();
  dataset.engineVersion = engineVersion();
  dataset.seed = options.seed;
  const Transform to_object = world->bodies()[object_index].pose.inverse();
  const BodyRef object_ref = BodyRef::body(object_index);
  for (std::size_t i = 0; i < run.grasps.size(); ++i) {
    const PlannedGrasp& g = run.grasps[i];
    DatasetGrasp d;
    d.pregrasp = to_object * g.pose;
    d.grasp = to_object * g.closed.pose;
    d.openDofs = g.dofs;
    d.closedDofs = g.closed.dofs;
    d.epsilon = g.epsilon;
    d.volume = g.volume;
    d.forceClosure = g.forceClosure;
    d.held = held[i];
    for (const Contact& c : g.contactList) {
      // The normal points into body1: out of the object when the object is body2.
      const bool object_second = c.body2 == object_ref;
      d.contactPoints.push_back(to_object * (object_second ? c.position2 : c.position1));
      d.contactNormals.push_back(to_object.linear() * (object_second ? c.normal : -c.normal));
    }
    dataset.grasps.push_back(std::move(d));
  }
  return dataset;
}

struct Outcome {
  bool done = false;
  std::string error;
  int grasps = 0, forceClosure = 0, held = 0;
  double seconds = 0.0;
};

// Runs one object in a child process: its dataset file is written by the child, its summary
// comes back through a pipe as one JSON line. A crash, a kill or a timeout is a failure.
Outcome runObject(const BatchOptions& options, const fs::path& object_file, const fs::path& out) {
  const auto start = Clock::now();
  int channel[2];
  if (::pipe(channel) != 0) throw Error("batch: cannot create a pipe to an object's process");
  std::cout.flush();
  std::cerr.flush();
  const pid_t child = ::fork();
  if (child < 0) throw Error("batch: cannot start a process for an object");
  if (child == 0) {
    ::close(channel[0]);
    json summary;
    int status = 0;
    try {
      const GraspDataset dataset = planObject(options, object_file);
      saveGraspDataset(dataset, out);
      int fc = 0, held = 0;
      for (const DatasetGrasp& g : dataset.grasps) {
        fc += g.forceClosure ? 1 : 0;
        held += g.held == 1 ? 1 : 0;
      }
      summary = {{"grasps", dataset.grasps.size()}, {"force_closure", fc}, {"held", held}};
    } catch (const std::exception& e) {
      summary = {{"error", e.what()}};
      status = 1;
    }
    const std::string text = summary.dump() + "\n";
    [[maybe_unused]] const auto written = ::write(channel[1], text.data(), text.size());
    ::close(channel[1]);
    std::fflush(nullptr);
    ::_exit(status);
  }
  ::close(channel[0 + 1]);
  std::string text;
  bool timed_out = false;
  const double limit = options.objectTimeout;
  for (;;) {
    const double left = limit - std::chrono::duration<double>(Clock::now() - start).count();
    if (left <= 0) {
      timed_out = true;
      ::kill(child, SIGKILL);
      break;
    }
    pollfd p{channel[0], POLLIN, 0};
    const int ready = ::poll(&p, 1, static_cast<int>(std::min(left, 1.0) * 1000) + 1);
    if (ready <= 0) continue;
    char buffer[4096];
    const ssize_t n = ::read(channel[0], buffer, sizeof buffer);
    if (n <= 0) break;
    text.append(buffer, static_cast<std::size_t>(n));
  }
  ::close(channel[0]);
  int status = 0;
  ::waitpid(child, &status, 0);
  Outcome outcome;
  outcome.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  if (timed_out) {
    outcome.error = fmt::format("timed out after {:g} s (--object-timeout)", limit);
  } else if (WIFSIGNALED(status)) {
    outcome.error = fmt::format("the object's process died of signal {} ({})", WTERMSIG(status),
                                strsignal(WTERMSIG(status)));
  } else {
    const json summary = json::parse(text, nullptr, false);
    if (summary.is_discarded() || !summary.is_object()) {
      outcome.error = fmt::format("the object's process ended ({}) without a report",
                                  WIFEXITED(status) ? WEXITSTATUS(status) : -1);
    } else if (summary.contains("error")) {
      outcome.error = summary["error"].get<std::string>();
    } else {
      outcome.done = WIFEXITED(status) && WEXITSTATUS(status) == 0 && fs::exists(out);
      outcome.grasps = summary.value("grasps", 0);
      outcome.forceClosure = summary.value("force_closure", 0);
      outcome.held = summary.value("held", 0);
      if (!outcome.done) outcome.error = "the object's process wrote no dataset file";
    }
  }
  return outcome;
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
  cmd->add_option("--grasps", options.grasps, "Grasps kept per object (the best list's size)")
      ->default_val(20)
      ->check(CLI::Range(1, 10000));
  auto* steps = cmd->add_option("--steps", options.steps, "Planner steps per object")
                    ->default_val(40000)
                    ->check(CLI::Range(std::int64_t{1}, std::int64_t{1} << 40));
  cmd->add_option("--seconds-per-object", options.secondsPerObject,
                  "Plan each object for this long instead (not reproducible: depends on speed)")
      ->excludes(steps);
  cmd->add_flag("--validate", options.validate,
                "Label each grasp physically (graspkit validate: 6 directions)");
  cmd->add_option("--validate-seconds", options.validateSeconds,
                  "--validate: simulated seconds per direction")
      ->default_val(2.0);
  cmd->add_option("--seed", options.seed, "The planner's seed, the same for every object")
      ->default_val(1);
  cmd->add_option("--shard", options.shard,
                  "K/N: take every N-th object from the K-th (default: a Slurm job array's task "
                  "from SLURM_ARRAY_TASK_ID and SLURM_ARRAY_TASK_COUNT, else all)");
  cmd->add_option("--object-timeout", options.objectTimeout,
                  "Seconds an object may take before it is killed and recorded as failed")
      ->default_val(1800.0);
}

namespace {

// Temporaries a killed run left behind (".NAME.h5.PID.tmp" whose process is gone).
void removeStaleTemporaries(const fs::path& folder) {
  for (const auto& entry : fs::directory_iterator(folder)) {
    const std::string name = entry.path().filename().string();
    if (name.empty() || name[0] != '.' || entry.path().extension() != ".tmp") continue;
    const std::string stem = entry.path().stem().string();  // .NAME.h5.PID
    const pid_t pid = static_cast<pid_t>(std::atol(stem.substr(stem.rfind('.') + 1).c_str()));
    if (pid > 0 && ::kill(pid, 0) != 0 && errno == ESRCH) {
      std::error_code ignored;
      fs::remove(entry.path(), ignored);
    }
  }
}

}  // namespace

int runBatch(const BatchOptions& options, bool quiet, std::ostream& out) {
  const Shard shard = shardOf(options.shard);
  const std::vector<fs::path> files = objectFiles(options.objects);
  const std::vector<std::string> names = objectNames(files);
  fs::create_directories(options.out / "grasps");
  removeStaleTemporaries(options.out / "grasps");
  const fs::path manifest_file =
      shard.count == 1
          ? options.out / "manifest.json"
          : options.out / fmt::format("manifest-{}-of-{}.json", shard.index + 1, shard.count);
  const json settings = settingsJson(options);
  json manifest = {{"manifest_version", kManifestVersion},
                   {"engine_version", engineVersion()},
                   {"settings", settings},
                   {"shard", {{"index", shard.index + 1}, {"count", shard.count}}},
                   {"objects", json::object()}};
  if (fs::exists(manifest_file)) {
    const json previous = json::parse(readInputFile(manifest_file), nullptr, false);
    if (previous.is_discarded() || !previous.contains("objects"))
      throw Error(SourceLocation{manifest_file.string()}, "not a batch manifest");
    if (previous.value("settings", json()) != settings)
      throw Error(SourceLocation{manifest_file.string()},
                  fmt::format("the folder holds a batch run with other settings ({}); use "
                              "another --out, or the same settings to resume",
                              previous.value("settings", json()).dump()));
    manifest["objects"] = previous["objects"];
  }

  std::vector<std::size_t> share;
  for (std::size_t i = 0; i < files.size(); ++i)
    if (static_cast<int>(i % static_cast<std::size_t>(shard.count)) == shard.index)
      share.push_back(i);
  int done = 0, failed = 0, skipped = 0, ran = 0;
  double spent = 0.0;
  std::vector<std::string> failures;
  for (std::size_t k = 0; k < share.size(); ++k) {
    const std::size_t i = share[k];
    const std::string& name = names[i];
    const fs::path dataset = options.out / "grasps" / (name + ".h5");
    json& entry = manifest["objects"][name];
    if (!entry.is_object()) entry = json::object();
    const std::string status = entry.value("status", "");
    const int attempts = entry.value("attempts", 0);
    if ((status == "done" && fs::exists(dataset)) ||
        (status == "failed" && attempts >= kMaxAttempts)) {
      ++skipped;
      if (status == "done")
        ++done;
      else {
        ++failed;
        failures.push_back(fmt::format("{}: {}", name, entry.value("error", "")));
      }
      continue;
    }
    const Outcome outcome = runObject(options, files[i], dataset);
    ++ran;
    spent += outcome.seconds;
    entry = {{"file", files[i].string()},
             {"status", outcome.done ? "done" : "failed"},
             {"attempts", attempts + 1},
             {"seconds", outcome.seconds}};
    if (outcome.done) {
      ++done;
      entry["dataset"] = fs::path("grasps") / (name + ".h5");
      entry["grasps"] = outcome.grasps;
      entry["force_closure"] = outcome.forceClosure;
      if (options.validate) entry["held"] = outcome.held;
    } else {
      ++failed;
      entry["error"] = outcome.error;
      failures.push_back(fmt::format("{}: {}", name, outcome.error));
    }
    writeFileAtomically(manifest_file, manifest.dump(2) + "\n");
    if (!quiet) {
      const double eta = spent / ran * static_cast<double>(share.size() - k - 1);
      std::cerr << fmt::format(
          "graspkit: [{}/{}] {}: {} ({:.1f} s), {} left\n", k + 1, share.size(), name,
          outcome.done
              ? fmt::format("{} grasps, {} force closure", outcome.grasps, outcome.forceClosure)
              : "failed: " + outcome.error,
          outcome.seconds, clockTime(eta));
    }
  }
  writeFileAtomically(manifest_file, manifest.dump(2) + "\n");
  out << fmt::format("{} objects: {} done, {} failed{}; manifest {}\n", share.size(), done, failed,
                     skipped ? fmt::format(" ({} already settled before this run)", skipped) : "",
                     manifest_file.string());
  for (const std::string& failure : failures) out << "  failed " << failure << "\n";
  return failed > 0 ? 1 : 0;
}

}  // namespace graspkit::cli
