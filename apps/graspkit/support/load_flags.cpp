// The options every command that loads files shares, and where models are found by default.

#include "support/load_flags.hpp"

#include <fmt/format.h>

#include <cstdlib>
#include <filesystem>
#include <system_error>

#include "graspkit/base/error.hpp"
#include "graspkit/model/material.hpp"

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

LoadOptions LoadFlags::options() const {
  LoadOptions options;
  options.roots = roots;
  options.genericRobotFallback = genericRobots;
  options.packagePaths = packagePaths;
  options.urdfPalm = palm;
  options.srdf = srdf;
  options.mjcfMeshHulls = !mjcfExactMeshes;
  auto materialNamed = [](const std::string& option, const std::string& name) {
    const auto m = valueNamed<Material>(name);
    if (!m) throw Error(fmt::format("{}: '{}' is not one of GraspIt!'s materials", option, name));
    return *m;
  };
  if (!material.empty()) options.urdfMaterial = materialNamed("--urdf-material", material);
  for (const std::string& pair : linkMaterials) {
    const auto equals = pair.find('=');
    if (equals == std::string::npos || equals == 0)
      throw Error(fmt::format("--link-material: '{}' is not LINK=MATERIAL", pair));
    options.urdfLinkMaterials[pair.substr(0, equals)] =
        materialNamed("--link-material", pair.substr(equals + 1));
  }
  for (const std::string& pair : closing) {
    const auto equals = pair.find('=');
    const std::string dof = pair.substr(0, equals),
                      sign = equals == std::string::npos ? "" : pair.substr(equals + 1);
    int index = -1;
    try {
      std::size_t used = 0;
      index = std::stoi(dof, &used);
      if (used != dof.size()) index = -1;
    } catch (const std::exception&) {
      index = -1;
    }
    if (index < 0 || (sign != "+" && sign != "-"))
      throw Error(fmt::format("--close: '{}' is not DOF=+ or DOF=- (DOF a 0-based index)", pair));
    options.closingDirections[index] = sign == "+" ? 1 : -1;
  }
  return options;
}

void addLoadFlags(CLI::App& command, LoadFlags& flags) {
  command.add_option("--root", flags.roots, "Folder that world <filename> paths are relative to")
      ->allow_extra_args(false);
  command.add_flag("--generic-robots", flags.genericRobots,
                   "Load a robot whose type no plugin provides as a generic Hand (with a warning)");
  command
      .add_option("--package-path", flags.packagePaths,
                  "URDF: a folder holding the packages package:// paths name (repeatable)")
      ->allow_extra_args(false);
  command.add_option("--palm", flags.palm,
                     "URDF: the link to take as the palm (default: the root)");
  command.add_option("--urdf-material", flags.material,
                     "URDF: every link's material, one of GraspIt!'s (default: rubber)");
  command.add_option("--srdf", flags.srdf,
                     "URDF: an SRDF whose <disable_collisions> pairs are never checked (default: "
                     "the .srdf beside the URDF)");
  command.add_flag("--mjcf-exact-meshes", flags.mjcfExactMeshes,
                   "MJCF: mesh geoms collide as their every triangle (default: as their convex "
                   "hulls, as in MuJoCo)");
  command
      .add_option("--close", flags.closing,
                  "DOF=+|-: the way DOF (0-based) closes the hand, towards its upper (+) or lower "
                  "(-) limit; overrides the file and the inferred direction (repeatable)")
      ->allow_extra_args(false);
  command
      .add_option("--link-material", flags.linkMaterials,
                  "URDF: LINK=MATERIAL, one link's material (repeatable)")
      ->allow_extra_args(false);
  // Applied once the command line is read, and only when it names no root.
  auto& roots = flags.roots;
  command.parse_complete_callback([&roots] {
    if (!roots.empty() || rootInEnvironment()) return;
    if (fs::path models = installedModels(); !models.empty()) roots.push_back(std::move(models));
  });
}

}  // namespace graspkit::cli
