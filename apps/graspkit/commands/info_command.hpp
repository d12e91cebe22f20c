#pragma once
// graspkit info: its options, its flags and what it does.

#include <filesystem>
#include <ostream>
#include <string>

#include <CLI/CLI.hpp>

#include "support/load_flags.hpp"

namespace graspkit::cli {

struct InfoOptions {
  std::filesystem::path file;
  LoadFlags load;
  std::string dofs;   // comma-separated DOF values
  std::string robot;  // name or 0-based index; the first robot when empty
  bool json = false;
};

void addInfoCommand(CLI::App& app, InfoOptions& options);
int runInfo(const InfoOptions& options, std::ostream& out);

}  // namespace graspkit::cli
