#pragma once
// graspkit objects: its options, its flags and what it does.

#include <cstdint>
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace graspkit::cli {

struct ObjectsOptions {
  std::size_t generate = 0;  // how many objects
  std::uint64_t seed = 1;
  std::filesystem::path out;
  double minSize = 40.0;  // mm
  double maxSize = 120.0;
  double density = 0.5;  // g/cm^3
  std::string material = "plastic";
  std::vector<std::string> kinds;  // empty: every kind
  bool force = false;
};

void addObjectsCommand(CLI::App& app, ObjectsOptions& options);
// Writes every object's OFF mesh and Body XML into the folder, and objects.txt listing the XMLs.
// A file that exists and differs needs --force; without it nothing is written.
int runObjects(const ObjectsOptions& options, bool quiet, std::ostream& out);

}  // namespace graspkit::cli
