#pragma once
// graspkit run: its options, its flags and what it does.

#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "support/script_flags.hpp"

namespace graspkit::cli {

struct RunOptions {
  std::filesystem::path script;
  std::vector<std::string> args;
  bool json = false;  // print the script's return value as JSON
  ScriptFlags flags;
};

void addRunCommand(CLI::App& app, RunOptions& options);
// Exit status: 0, the script's os.exit status, 1 after a Lua error (traceback on stderr), 124
// after --timeout.
int runRun(const RunOptions& options, bool quiet);

}  // namespace graspkit::cli
