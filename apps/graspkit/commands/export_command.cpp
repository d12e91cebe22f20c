// graspkit export: a world, or a plan's or dataset's grasps, as binary glTF.
#include <fmt/format.h>

#include "commands/export_command.hpp"
#include "graspkit/base/output_file.hpp"
#include "support/argument_checks.hpp"
#include "support/scene_frames.hpp"

namespace graspkit::cli {

void addExportCommand(CLI::App& app, ExportOptions& options) {
  CLI::App* cmd = app.add_subcommand(
      "export",
      "Write a world, or a plan's or dataset's grasps (one scene each), as binary glTF (.glb)");
  cmd->add_option("input", options.input,
                  "World XML, a plan's JSON (plan --out) or a grasp dataset (batch's .h5)")
      ->required()
      ->check(existingFile());
  cmd->add_option("--gltf", options.gltf, "The .glb file to write")->required();
  cmd->add_option("--grasp", options.grasp, "Plans: only grasp N (1-based)")
      ->check(CLI::Range(1, 1000000));
  cmd->add_option("--top", options.top, "Plans: the first N grasps (all when not given)")
      ->check(CLI::Range(1, 1000000));
  addLoadFlags(*cmd, options.load);
}

int runExport(const ExportOptions& options, std::ostream& out) {
  const std::vector<SceneFrame> frames =
      loadFrames({options.input, options.load.options(), true, options.grasp, options.top});
  writeFileAtomically(options.gltf, framesGltf(frames));
  out << fmt::format("wrote {} ({} scene{})\n", options.gltf.string(), frames.size(),
                     frames.size() == 1 ? "" : "s");
  return 0;
}

}  // namespace graspkit::cli
