// graspkit validate: label grasps physically. The hand squeezes and the object's weight is turned
// along each axis direction in turn (grasp_validation.hpp); a world gives one grasp, a plan or a
// dataset one per grasp.

#include <algorithm>
#include <thread>
#include <utility>

#include <fmt/format.h>

#include <nlohmann/json.hpp>

#include "commands/validate_command.hpp"
#include "graspkit/base/error.hpp"
#include "graspkit/dynamics/grasp_validation.hpp"
#include "graspkit/render/render.hpp"
#include "support/argument_checks.hpp"
#include "support/scene_frames.hpp"
#include "support/simulation_report.hpp"

namespace graspkit::cli {
using nlohmann::json;

// The hand and the object a frame's grasp is of.
std::pair<int, int> validationSubject(const World& world) {
  const GraspSubject subject = graspSubject(world);
  if (!subject.hand) throw Error("validate: the world has no hand (no robot) to hold a grasp");
  if (!subject.object || subject.object->kind != BodyRef::Kind::Body) {
    throw Error("validate: the world has no graspable body to hold");
  }
  return {*subject.hand, subject.object->index};
}

// Validates each frame, frames that share their hand and object (a plan's) `threads` at a time.
std::vector<ValidationResult> validateFrames(const std::vector<SceneFrame>& frames,
                                             const ValidationRequest& request, int threads) {
  std::vector<ValidationResult> results;
  std::size_t first = 0;
  while (first < frames.size()) {
    const auto subject = validationSubject(frames[first].world);
    std::vector<World> worlds;
    std::size_t end = first;
    for (; end < frames.size() && validationSubject(frames[end].world) == subject; ++end)
      worlds.push_back(frames[end].world.clone());
    for (ValidationResult& r :
         validateGrasps(worlds, subject.first, subject.second, request, threads))
      results.push_back(std::move(r));
    first = end;
  }
  return results;
}

void addValidateCommand(CLI::App& app, ValidateOptions& options) {
  CLI::App* cmd = app.add_subcommand(
      "validate",
      "Label grasps physically: does the hand hold the object's weight in 6 directions?");
  cmd->add_option(
         "input", options.input,
         "World XML (the hand closed on the object), plan JSON or a grasp dataset (batch's .h5)")
      ->required()
      ->check(existingFile());
  addLoadFlags(*cmd, options.load);
  // 0 would mean "not given" below: the ranges start at 1, as export's and render's do.
  cmd->add_option("--grasp", options.grasp, "Plans: only grasp N (1-based)")
      ->check(CLI::Range(1, 1000000));
  cmd->add_option("--top", options.top, "Plans: the first N grasps")->check(CLI::Range(1, 1000000));
  cmd->add_option("--seconds", options.seconds, "Simulated seconds per direction")
      ->default_val(ValidationRequest{}.seconds)
      ->check(positiveFinite());
  cmd->add_option("--threads", options.threads, "Grasps validated at once (default: every core)")
      ->check(CLI::Range(1, 4096));
  cmd->add_flag("--statics", options.statics,
                "A direction that statics shows the grasp bears with margins (twice the weight) is "
                "held after a 0.025 s probe instead of a run to rest: faster, the same labels on "
                "planned grasps (docs/dynamics.md)");
  cmd->add_flag("--json", options.json, "Print one JSON object");
}

int runValidate(const ValidateOptions& options, std::ostream& out) {
  ValidationRequest request;
  request.seconds = options.seconds;
  request.statics = options.statics;
  const std::vector<SceneFrame> frames = loadFrames({.input = options.input,
                                                     .load = options.load.options(),
                                                     .grasp = options.grasp,
                                                     .top = options.top});
  const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  const int threads = options.threads.value_or(cores);
  if (threads < 1) throw Error(fmt::format("--threads {} is not valid", threads));
  const std::vector<ValidationResult> results = validateFrames(frames, request, threads);
  json grasps = json::array();
  int held = 0;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const SceneFrame& frame = frames[i];
    const ValidationResult& result = results[i];
    held += result.held ? 1 : 0;
    json entry = validationJson(result);
    entry["name"] = frame.name;
    grasps.push_back(entry);
    if (options.json) continue;
    out << frame.name << ": " << validationLine(result) << "\n";
    for (const DirectionResult& d : result.directions) {
      if (!d.failure.empty()) out << "  simulation stopped: " << d.failure << "\n";
    }
  }
  if (options.json) {
    out << json({{"grasps", grasps}, {"held", held}, {"count", frames.size()}}).dump(2) << "\n";
  } else {
    out << fmt::format("{} of {} grasps held\n", held, frames.size());
  }
  return 0;
}

}  // namespace graspkit::cli
