#pragma once
// graspkit convert: its options, its flags and what it does.

#include <filesystem>
#include <ostream>
#include <string>

#include <CLI/CLI.hpp>

#include "support/load_flags.hpp"

namespace graspkit::cli {

struct ConvertOptions {
  std::filesystem::path input;
  std::filesystem::path out;  // beside the input, .xml, when empty; a folder with --to
  std::string to;             // robots: the format to write (urdf, mjcf)
  LoadFlags load;             // robots: how to read the input
  bool force = false;
  std::string material = "plastic";
  double mass = 300.0;
  double scale = 1.0;
};

void addConvertCommand(CLI::App& app, ConvertOptions& options);
// Writes the conversion atomically; a target that exists and differs needs --force.
int runConvert(const ConvertOptions& options, bool quiet, std::ostream& out);

}  // namespace graspkit::cli
