#pragma once
// graspkit export: its options, its flags and what it does.

#include <filesystem>
#include <ostream>
#include <string>

#include <CLI/CLI.hpp>

#include "support/load_flags.hpp"

namespace graspkit::cli {

struct ExportOptions {
  std::filesystem::path input;
  std::filesystem::path gltf;
  LoadFlags load;
  int grasp = 0;
  int top = 0;
};

void addExportCommand(CLI::App& app, ExportOptions& options);
// Writes a binary glTF (.glb): one scene for a world, one per grasp for a plan.
int runExport(const ExportOptions& options, std::ostream& out);

}  // namespace graspkit::cli
