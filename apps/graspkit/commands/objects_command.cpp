// graspkit objects --generate N: procedural objects (engine: graspkit/model/object_generator.hpp)
// written as GraspIt! bodies, an OFF mesh and a Body XML each, with objects.txt listing them.

#include <fmt/format.h>

#include <unistd.h>

#include <charconv>
#include <random>
#include <string_view>

#include "commands/objects_command.hpp"
#include "graspkit/base/error.hpp"
#include "graspkit/base/input_file.hpp"
#include "graspkit/base/output_file.hpp"
#include "graspkit/host/object_task.hpp"
#include "graspkit/model/material.hpp"
#include "graspkit/model/object_generator.hpp"
#include "support/argument_checks.hpp"
#include "support/process_runs.hpp"

namespace graspkit::cli {
namespace {

namespace fs = std::filesystem;

ObjectGeneratorOptions generatorOptions(const ObjectsOptions& options) {
  ObjectGeneratorOptions generator;
  generator.seed = options.seed;
  generator.minSize = options.minSize;
  generator.maxSize = options.maxSize;
  generator.density = options.density * 1e-3;  // g/cm^3 -> g/mm^3
  const auto material = valueNamed<Material>(options.material);
  if (!material)
    throw Error(
        fmt::format("--material: '{}' is not one of GraspIt!'s materials", options.material));
  generator.material = *material;
  if (!options.kinds.empty()) {
    generator.kinds.clear();
    for (const std::string& name : options.kinds)
      generator.kinds.push_back(parseNamed<ObjectKind>(name, "--kinds"));
  }
  return generator;
}

constexpr std::string_view kStagingPrefix = ".objects-staging-";

// A folder beside the targets, removed however the command ends; one that a killed run left
// (".objects-staging-PID-RANDOM" whose process is gone) is removed by the next run.
struct StagingFolder {
  fs::path path;
  explicit StagingFolder(const fs::path& out) {
    removeStale(out);
    std::random_device device;
    path = out / fmt::format("{}{}-{:08x}", kStagingPrefix, ::getpid(), device());
    createOutputFolder(path);
  }
  static void removeStale(const fs::path& out) {
    std::error_code missing;
    for (const auto& entry : fs::directory_iterator(out, missing)) {
      const std::string name = entry.path().filename().string();
      if (!name.starts_with(kStagingPrefix)) continue;
      const std::string rest = name.substr(kStagingPrefix.size());
      pid_t pid = 0;
      const auto [end, error] = std::from_chars(rest.data(), rest.data() + rest.size(), pid);
      if (error != std::errc() || end == rest.data() + rest.size() || *end != '-') continue;
      std::error_code ignored;
      if (!processRuns(pid) && entry.is_directory(ignored) && !entry.is_symlink(ignored))
        fs::remove_all(entry.path(), ignored);
    }
  }
  ~StagingFolder() {
    std::error_code ignored;
    fs::remove_all(path, ignored);
  }
};

}  // namespace

void addObjectsCommand(CLI::App& app, ObjectsOptions& options) {
  CLI::App* cmd = app.add_subcommand(
      "objects",
      "Generate procedural objects to grasp (boxes, cylinders, spheres, superquadrics, convex "
      "hulls) as GraspIt! bodies: NAME.off and NAME.xml each, and objects.txt listing them");
  cmd->add_option("--generate", options.generate, "How many objects")
      ->required()
      ->check(CLI::Range(std::size_t{1}, std::size_t{1000000}));
  const ObjectGeneratorOptions defaults;  // the generator's own
  cmd->add_option("--seed", options.seed, "The set's seed: object i of a seed never changes")
      ->check(seedNumber())
      ->default_val(defaults.seed);
  cmd->add_option("--out", options.out, "The folder to write into")->required();
  cmd->add_option("--min-size", options.minSize, "Smallest largest-extent, mm")
      ->default_val(defaults.minSize);
  cmd->add_option("--max-size", options.maxSize, "Largest largest-extent, mm")
      ->default_val(defaults.maxSize);
  cmd->add_option("--density", options.density, "g/cm^3; the mass is the volume times it")
      ->default_val(defaults.density * 1e3);
  cmd->add_option("--material", options.material, "Every object's material")
      ->default_val(std::string(nameOf(defaults.material)));
  cmd->add_option("--kinds", options.kinds, "The kinds to draw from, in turn (default: all)")
      ->delimiter(',');
  cmd->add_flag("--force", options.force, "Replace existing files that differ");
}

int runObjects(const ObjectsOptions& options, bool quiet, std::ostream& out) {
  const ObjectGeneratorOptions generator = generatorOptions(options);
  createOutputFolder(options.out);
  // Everything is written to a staging folder first and compared with what is there, so a
  // refusal leaves the folder as it was.
  const StagingFolder staging(options.out);
  std::vector<std::string> written;
  std::string listing = fmt::format(
      "# graspkit objects --generate {} --seed {} --min-size {} --max-size {} --density {} "
      "--material {}\n",
      options.generate, options.seed, options.minSize, options.maxSize, options.density,
      options.material);
  for (std::size_t i = 0; i < options.generate; ++i) {
    const host::SavedObject object = host::saveGeneratedObject(staging.path, generator, i);
    written.push_back(object.name + ".off");
    written.push_back(object.name + ".xml");
    listing += fmt::format("{}.xml  # {}, {:.1f} g\n", object.name, object.shape, object.mass);
  }
  writeFileAtomically(staging.path / "objects.txt", listing);
  written.push_back("objects.txt");
  for (const std::string& name : written) {
    const fs::path target = options.out / name;
    if (!options.force && fs::exists(target) &&
        readInputFile(target) != readInputFile(staging.path / name))
      throw Error(SourceLocation{target.string()},
                  "the file exists and differs from the generated one; --force replaces it "
                  "(nothing was written)");
  }
  for (const std::string& name : written) fs::rename(staging.path / name, options.out / name);
  if (!quiet)
    out << fmt::format("wrote {} objects to {} (objects.txt lists them)\n", options.generate,
                       options.out.string());
  return 0;
}

}  // namespace graspkit::cli
