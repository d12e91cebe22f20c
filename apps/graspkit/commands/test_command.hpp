#pragma once
// graspkit test: its options, its flags and what it does.

#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "support/script_flags.hpp"

namespace graspkit::cli {

struct TestOptions {
  std::vector<std::filesystem::path> paths;  // test files and folders
  std::filesystem::path junit;               // --junit FILE; none when empty
  bool json = false;
  ScriptFlags flags;
};

void addTestCommand(CLI::App& app, TestOptions& options);
// Prints a line per test and "N passed, N failed[, N skipped]" (or one JSON object). Exit
// status 0 when no test failed, 1 when one did or no test was found.
int runTest(const TestOptions& options, bool quiet, bool verbose, std::ostream& out);

}  // namespace graspkit::cli
