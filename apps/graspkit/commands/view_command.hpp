#pragma once
// graspkit view: its options, its flags and what it does.

#include <filesystem>
#include <ostream>
#include <string>

#include <CLI/CLI.hpp>

#include "support/load_flags.hpp"

namespace graspkit::cli {

struct ViewOptions {
  std::filesystem::path input;
  std::filesystem::path html;
  LoadFlags load;
  int top = 0;
  std::filesystem::path trajectory;  // simulate --trajectory's lines, played back on the world
};

void addViewCommand(CLI::App& app, ViewOptions& options);
// Writes one self-contained HTML page (three.js inside): orbit the scene, step through grasps.
int runView(const ViewOptions& options, std::ostream& out);

}  // namespace graspkit::cli
