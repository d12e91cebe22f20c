#pragma once
// graspkit serve: its options, its flags and what it does.

#include <filesystem>
#include <ostream>
#include <vector>

#include <CLI/CLI.hpp>

#include "support/load_flags.hpp"

namespace graspkit::cli {

struct ServeOptions {
  std::filesystem::path input;
  int port = 8765;
  std::vector<std::filesystem::path> allowRead;
  std::vector<std::filesystem::path> allowWrite;
  LoadFlags load;
};

void addServeCommand(CLI::App& app, ServeOptions& options);
// Opens the world (or a plan's grasps) in a local web application until Ctrl-C.
int runServe(const ServeOptions& options, std::ostream& out);

}  // namespace graspkit::cli
