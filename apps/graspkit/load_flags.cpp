// The options every command that loads files shares, and where models are found by default.

#include <cstdlib>
#include <filesystem>
#include <system_error>

#include "commands.hpp"

namespace fs = std::filesystem;

namespace graspkit::cli {
namespace {

// <prefix>/share/graspkit/models beside <prefix>/bin/graspkit: `cmake --install` puts the
// project's models there, so an installed program finds them with no setting, wherever the
// prefix was moved. Empty in a build tree (there is no share/ beside the program).
fs::path installedModels() {
  std::error_code ec;
  const fs::path program = fs::read_symlink("/proc/self/exe", ec);
  if (ec) return {};
  const fs::path models =
      (program.parent_path() / ".." / "share" / "graspkit" / "models").lexically_normal();
  return fs::is_directory(models, ec) ? models : fs::path{};
}

bool rootInEnvironment() {
  for (const char* name : {"GRASPKIT_ROOT", "GRASPIT"}) {
    if (const char* value = std::getenv(name); value != nullptr && *value != '\0') return true;
  }
  return false;
}

}  // namespace

void addLoadFlags(CLI::App& command, std::vector<fs::path>& roots, bool& generic_robots) {
  command.add_option("--root", roots, "Folder that world <filename> paths are relative to")
      ->allow_extra_args(false);
  command.add_flag("--generic-robots", generic_robots,
                   "Load a robot whose type no plugin provides as a generic Hand (with a warning)");
  // Applied once the command line is read, and only when it names no root.
  command.parse_complete_callback([&roots] {
    if (!roots.empty() || rootInEnvironment()) return;
    if (fs::path models = installedModels(); !models.empty()) roots.push_back(std::move(models));
  });
}

}  // namespace graspkit::cli
