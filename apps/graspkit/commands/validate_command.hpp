#pragma once
// graspkit validate: its options, its flags and what it does.

#include <filesystem>
#include <optional>
#include <ostream>
#include <string>

#include <CLI/CLI.hpp>

#include "support/load_flags.hpp"

namespace graspkit::cli {

struct ValidateOptions {
  std::filesystem::path input;
  LoadFlags load;
  int grasp = 0;
  int top = 0;
  double seconds = 2.0;
  bool statics = false;  // directions statics shows held are not simulated
  std::optional<int> threads;  // every core when unset
  bool json = false;
};

void addValidateCommand(CLI::App& app, ValidateOptions& options);
int runValidate(const ValidateOptions& options, std::ostream& out);

}  // namespace graspkit::cli
