// One object of graspkit batch: the hand over the object, a plan, its grasps closed, measured and
// optionally validated, the dataset written; all in a forked child, whose one-line JSON report
// comes back through a pipe. runObjects keeps --jobs of them in flight.

#include "batch/batch_object.hpp"

#include <fmt/format.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <iostream>
#include <memory>

#include "graspkit/base/error.hpp"
#include "graspkit/collision/collision.hpp"
#include "graspkit/dataset/dataset_planning.hpp"
#include "graspkit/dynamics/dynamics.hpp"
#include "graspkit/io/dataset/grasp_dataset_file.hpp"
#include "graspkit/io/graspit/world_file.hpp"

namespace graspkit::cli {

namespace fs = std::filesystem;
using nlohmann::json;
using Clock = std::chrono::steady_clock;

json outcomeJson(const ObjectOutcome& o) {
  return {{"done", o.done},     {"error", o.error},
          {"grasps", o.grasps}, {"force_closure", o.forceClosure},
          {"held", o.held},     {"seconds", o.seconds}};
}

ObjectOutcome outcomeFromJson(const json& j) {
  ObjectOutcome o;
  o.done = j.value("done", false);
  o.error = j.value("error", "");
  o.grasps = j.value("grasps", 0);
  o.forceClosure = j.value("force_closure", 0);
  o.held = j.value("held", 0);
  o.seconds = j.value("seconds", 0.0);
  return o;
}

namespace {

// The hand, loaded once per batch process with its collision hierarchies built, for every
// object's forked process to share: a hand's meshes (a Robotiq 2F-85's pads are 19,000 triangles
// each) took a fifth of each object's time to build again. Null when the hand does not load:
// each object's process then loads it and reports why, as it would alone.
std::shared_ptr<const World> loadedHand(const BatchOptions& options) {
  static const std::shared_ptr<const World> hand = [&]() -> std::shared_ptr<const World> {
    try {
      auto world = std::make_shared<World>(loadAnyFile(options.hand, options.load.options()));
      collisionReport(*world, {});  // places every link: its hierarchy and hull are built
      return world;
    } catch (const std::exception&) {
      return nullptr;
    }
  }();
  return hand;
}

DatasetRequest datasetRequest(const BatchOptions& options, const fs::path& object_file) {
  DatasetRequest request;
  request.hand = options.hand;
  request.loadedHand = loadedHand(options);
  request.object = object_file;
  request.load = options.load.options();
  request.grasps = options.grasps;
  if (options.secondsPerObject)
    request.seconds = *options.secondsPerObject;
  else
    request.steps = options.steps;
  request.validate = options.validate;
  request.validateSeconds = options.validateSeconds;
  request.validateAllDirections = options.validateAllDirections;
  request.validateStatics = options.validateStatics;
  request.seed = options.seed;
  return request;
}

// Once an object's dataset is in place, any temporary of it is a killed writer's leftover: one
// object has one writer at a time, and a writer dies with the process that started it.
void removeEarlierTemporaries(const fs::path& dataset) {
  const std::string prefix = "." + dataset.filename().string() + ".";
  std::error_code missing;
  for (const auto& entry : fs::directory_iterator(dataset.parent_path(), missing)) {
    const std::string name = entry.path().filename().string();
    if (name.starts_with(prefix) && entry.path().extension() == ".tmp") {
      std::error_code ignored;
      fs::remove(entry.path(), ignored);
    }
  }
}

}  // namespace

ObjectProcess::ObjectProcess(const BatchOptions& options, const fs::path& object_file,
                             const fs::path& out)
    : dataset_(out), limit_(options.objectTimeout), start_(Clock::now()) {
  loadedHand(options);  // before the fork, so that the child shares it
  useOneBlasThread();   // before the fork, or each child restarts OpenBLAS's threads
  int channel[2];
  if (::pipe(channel) != 0) throw Error("batch: cannot create a pipe to an object's process");
  std::cout.flush();
  std::cerr.flush();
  const pid_t parent = ::getpid();
  const pid_t child = ::fork();
  if (child < 0) {
    ::close(channel[0]);
    ::close(channel[1]);
    throw Error("batch: cannot start a process for an object");
  }
  if (child == 0) {
    // Dies with its parent: a killed rank must not leave a child that goes on writing into the
    // output folder while the run is started again.
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (::getppid() != parent) ::_exit(1);
    ::close(channel[0]);
    json summary;
    int status = 0;
    try {
      const GraspDataset dataset = planGraspDataset(datasetRequest(options, object_file));
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
  ::close(channel[1]);
  child_ = child;
  channel_ = channel[0];
}

ObjectProcess::~ObjectProcess() {
  if (channel_ >= 0) ::close(channel_);
  if (child_ > 0) {
    ::kill(child_, SIGKILL);
    ::waitpid(child_, nullptr, 0);
  }
}

double ObjectProcess::secondsLeft() const {
  return limit_ - std::chrono::duration<double>(Clock::now() - start_).count();
}

bool ObjectProcess::step() {
  if (ended_) return true;
  if (secondsLeft() <= 0) {
    timedOut_ = ended_ = true;
    ::kill(child_, SIGKILL);
    return true;
  }
  for (;;) {
    pollfd p{channel_, POLLIN, 0};
    if (::poll(&p, 1, 0) <= 0) return false;
    char buffer[4096];
    const ssize_t n = ::read(channel_, buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      ended_ = true;
      return true;
    }
    report_.append(buffer, static_cast<std::size_t>(n));
  }
}

ObjectOutcome ObjectProcess::finish() {
  ::close(channel_);
  channel_ = -1;
  int status = 0;
  ::waitpid(child_, &status, 0);
  child_ = -1;
  ObjectOutcome outcome;
  outcome.seconds = std::chrono::duration<double>(Clock::now() - start_).count();
  if (timedOut_) {
    outcome.error = fmt::format("timed out after {:g} s (--object-timeout)", limit_);
  } else if (WIFSIGNALED(status)) {
    outcome.error = fmt::format("the object's process died of signal {} ({})", WTERMSIG(status),
                                strsignal(WTERMSIG(status)));
  } else {
    const json summary = json::parse(report_, nullptr, false);
    if (summary.is_discarded() || !summary.is_object()) {
      outcome.error = fmt::format("the object's process ended ({}) without a report",
                                  WIFEXITED(status) ? WEXITSTATUS(status) : -1);
    } else if (summary.contains("error")) {
      outcome.error = summary["error"].get<std::string>();
    } else {
      outcome.done = WIFEXITED(status) && WEXITSTATUS(status) == 0 && fs::exists(dataset_);
      outcome.grasps = summary.value("grasps", 0);
      outcome.forceClosure = summary.value("force_closure", 0);
      outcome.held = summary.value("held", 0);
      if (!outcome.done) outcome.error = "the object's process wrote no dataset file";
    }
  }
  if (outcome.done) removeEarlierTemporaries(dataset_);
  return outcome;
}

ObjectOutcome runObject(const BatchOptions& options, const fs::path& object_file,
                        const fs::path& out, const std::function<void()>& while_waiting) {
  ObjectProcess process(options, object_file, out);
  while (!process.step()) {
    if (while_waiting) while_waiting();
    pollfd p{process.channel(), POLLIN, 0};
    const double wait = std::min(process.secondsLeft(), while_waiting ? 0.005 : 1.0);
    ::poll(&p, 1, static_cast<int>(std::max(0.0, wait) * 1000) + 1);
  }
  return process.finish();
}

void runObjects(const BatchOptions& options, const std::vector<ObjectJob>& objects, int parallel,
                const std::function<void(std::size_t, const ObjectOutcome&)>& record) {
  const auto slots = static_cast<std::size_t>(std::max(1, parallel));
  std::vector<std::pair<std::size_t, std::unique_ptr<ObjectProcess>>> running;
  std::size_t next = 0;
  while (next < objects.size() || !running.empty()) {
    while (running.size() < slots && next < objects.size()) {
      const ObjectJob& job = objects[next++];
      running.emplace_back(
          job.index, std::make_unique<ObjectProcess>(options, job.objectFile, job.datasetFile));
    }
    std::vector<pollfd> channels;
    double wait = 1.0;
    for (const auto& [index, process] : running) {
      channels.push_back({process->channel(), POLLIN, 0});
      wait = std::min(wait, process->secondsLeft());
    }
    ::poll(channels.data(), channels.size(), static_cast<int>(std::max(0.0, wait) * 1000) + 1);
    // Outcomes in the order the objects started, whichever ended first within one wait.
    for (auto it = running.begin(); it != running.end();) {
      if (!it->second->step()) {
        ++it;
        continue;
      }
      const std::size_t index = it->first;
      const ObjectOutcome outcome = it->second->finish();
      it = running.erase(it);
      record(index, outcome);
    }
  }
}

}  // namespace graspkit::cli
