// graspkit validate: label grasps physically. The hand squeezes and the object's weight is turned
// along each axis direction in turn (grasp_validation.hpp); a world gives one grasp, a plan one
// per grasp.

#include <fmt/format.h>

#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "graspkit/error.hpp"
#include "graspkit/grasp_validation.hpp"
#include "graspkit/render.hpp"
#include "scene_frames.hpp"

namespace graspkit::cli {
namespace {

using nlohmann::json;

constexpr const char* kDirectionNames[6] = {"+x", "-x", "+y", "-y", "+z", "-z"};

}  // namespace

json validationJson(const ValidationResult& result) {
  json directions = json::array();
  for (int k = 0; k < 6; ++k) {
    const DirectionResult& d = result.directions[k];
    json entry = {{"direction", kDirectionNames[k]},
                  {"held", d.held},
                  {"slip_mm", d.slip},
                  {"turn_deg", d.turn * 180.0 / M_PI}};
    if (!d.failure.empty()) entry["failure"] = d.failure;
    directions.push_back(entry);
  }
  return {{"held", result.held},
          {"directions_held", result.directionsHeld},
          {"directions", directions}};
}

ValidationResult validateFrameGrasp(const World& world, const ValidationRequest& request) {
  const GraspSubject subject = graspSubject(world);
  if (!subject.hand) throw Error("validate: the world has no hand (no robot) to hold a grasp");
  if (!subject.object || subject.object->kind != BodyRef::Kind::Body) {
    throw Error("validate: the world has no graspable body to hold");
  }
  return validateGrasp(world, *subject.hand, subject.object->index, request);
}

void addValidateCommand(CLI::App& app, ValidateOptions& options) {
  CLI::App* cmd = app.add_subcommand(
      "validate",
      "Label grasps physically: does the hand hold the object's weight in 6 directions?");
  cmd->add_option("input", options.input, "World XML (the hand closed on the object) or plan JSON")
      ->required()
      ->check(existingFile());
  addLoadFlags(*cmd, options.roots, options.genericRobots);
  cmd->add_option("--grasp", options.grasp, "Plans: only grasp N (1-based)");
  cmd->add_option("--top", options.top, "Plans: the first N grasps");
  cmd->add_option("--seconds", options.seconds, "Simulated seconds per direction")
      ->default_val(2.0);
  cmd->add_flag("--json", options.json, "Print one JSON object");
}

int runValidate(const ValidateOptions& options, std::ostream& out) {
  ValidationRequest request;
  request.seconds = options.seconds;
  const std::vector<SceneFrame> frames = loadFrames({.input = options.input,
                                                     .roots = options.roots,
                                                     .genericRobots = options.genericRobots,
                                                     .grasp = options.grasp,
                                                     .top = options.top});
  json grasps = json::array();
  int held = 0;
  for (const SceneFrame& frame : frames) {
    const ValidationResult result = validateFrameGrasp(frame.world, request);
    held += result.held ? 1 : 0;
    json entry = validationJson(result);
    entry["name"] = frame.name;
    grasps.push_back(entry);
    if (options.json) continue;
    std::string line = fmt::format("{}: {}", frame.name, result.held ? "held" : "not held");
    for (int k = 0; k < 6; ++k) {
      const DirectionResult& d = result.directions[k];
      line +=
          fmt::format("  {} {} ({:.1f} mm)", kDirectionNames[k], d.held ? "ok" : "lost", d.slip);
    }
    out << line << "\n";
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
