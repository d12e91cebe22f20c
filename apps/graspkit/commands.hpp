#pragma once
// The subcommands of the graspkit program.

#include <filesystem>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace graspkit::cli {

struct InfoOptions {
  std::filesystem::path file;
  std::vector<std::filesystem::path> roots;
  std::string dofs;  // comma-separated DOF values
  int robot = 0;
  bool json = false;
};

void addInfoCommand(CLI::App& app, InfoOptions& options);
int runInfo(const InfoOptions& options, std::ostream& out);

}  // namespace graspkit::cli
