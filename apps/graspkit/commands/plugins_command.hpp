#pragma once
// graspkit plugins: its options, its flags and what it does.

#include <filesystem>
#include <ostream>
#include <string>

#include <CLI/CLI.hpp>

namespace graspkit::cli {

struct PluginsOptions {
  bool json = false;
};

void addPluginsCommand(CLI::App& app, PluginsOptions& options);
// Lists every plugin on the search path and what it provides. Exit status 1 when a plugin on the
// path failed to load (each failure is listed with its reason).
int runPlugins(const PluginsOptions& options, std::ostream& out);

}  // namespace graspkit::cli
