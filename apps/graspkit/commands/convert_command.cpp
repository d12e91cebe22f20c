// graspkit convert: GraspIt!'s legacy side files (.egr eigengrasps, .vgr virtual contacts) into
// their XML forms, and a bare mesh into a Body XML beside it with computed mass properties.

#include <fmt/format.h>

#include "commands/convert_command.hpp"
#include "graspkit/base/error.hpp"
#include "graspkit/base/input_file.hpp"
#include "graspkit/base/output_file.hpp"
#include "graspkit/geometry/mesh_loader.hpp"
#include "graspkit/io/graspit/body_file.hpp"
#include "graspkit/io/graspit/robot_export.hpp"
#include "graspkit/io/graspit/robot_file.hpp"
#include "graspkit/io/legacy/legacy_files.hpp"
#include "graspkit/io/mjcf/mjcf_export.hpp"
#include "graspkit/io/mjcf/mjcf_file.hpp"
#include "graspkit/io/urdf/urdf_export.hpp"
#include "graspkit/io/urdf/urdf_file.hpp"
#include "graspkit/model/material.hpp"
#include "support/argument_checks.hpp"

namespace graspkit::cli {
namespace {

namespace fs = std::filesystem;

std::string lowerExtension(const fs::path& file) {
  std::string ext = file.extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

std::string converted(const ConvertOptions& options, const fs::path& target) {
  const std::string ext = lowerExtension(options.input);
  if (ext == ".egr") return eigengraspXmlFromEgr(options.input);
  if (ext == ".vgr") return virtualContactXmlFromVgr(options.input);
  if (isMeshFile(options.input)) {
    BodyXmlOptions body;
    const auto material = valueNamed<Material>(options.material);
    if (!material)
      throw Error(
          fmt::format("--material: '{}' is not one of GraspIt!'s materials", options.material));
    body.material = *material;
    body.massGrams = options.mass;
    body.scale = options.scale;
    return bodyXmlForMesh(options.input, target, body);
  }
  throw Error(SourceLocation{options.input.string()},
              "convert reads .egr, .vgr and mesh files (.iv, .wrl, .off, .ply, .stl, .obj); the "
              "pre-2.1 .cfg and .wld grammars have no public description and are not read");
}

}  // namespace

void addConvertCommand(CLI::App& app, ConvertOptions& options) {
  CLI::App* cmd = app.add_subcommand(
      "convert",
      "Turn a legacy .egr or .vgr file into its XML form, a mesh into a Body XML beside it, or a "
      "robot (GraspIt! XML, URDF or MJCF) into URDF, MJCF or GraspIt! XML (--to)");
  cmd->add_option("input", options.input, ".egr, .vgr, mesh or robot file")
      ->required()
      ->check(existingFile());
  cmd->add_option("-o,--out", options.out,
                  "Where to write (default: beside the input, .xml); with --to, a folder");
  cmd->add_option("--to", options.to,
                  "Robots: write this format into the --out folder (urdf: the .urdf, mjcf: "
                  "MuJoCo's XML, meshes as STL beside them; graspit: GraspIt! XML with body "
                  "files and OFF meshes in iv/)")
      ->check(CLI::IsMember({"urdf", "mjcf", "graspit"}));
  addLoadFlags(*cmd, options.load);
  cmd->add_flag("--force", options.force, "Replace an existing file that differs");
  cmd->add_option("--material", options.material, "Mesh: the body's material")
      ->default_val("plastic");
  cmd->add_option("--mass", options.mass, "Mesh: the body's mass, g")->default_val(300.0);
  cmd->add_option("--scale", options.scale, "Mesh: <geometryScaling>")->default_val(1.0);
}

int runConvert(const ConvertOptions& options, bool quiet, std::ostream& out) {
  if (!options.to.empty()) {
    if (options.out.empty())
      throw Error("--to " + options.to + " needs --out FOLDER to write into");
    const auto robot = loadRobotFile(options.input, options.load.options());
    const fs::path written = options.to == "mjcf"      ? saveMjcf(*robot, options.out)
                             : options.to == "graspit" ? saveRobotFile(*robot, options.out)
                                                       : saveUrdf(*robot, options.out);
    if (!quiet) out << fmt::format("wrote {}\n", written.string());
    return 0;
  }
  const fs::path target =
      options.out.empty() ? fs::path(options.input).replace_extension(".xml") : options.out;
  std::error_code ec;
  if (fs::equivalent(target, options.input, ec))
    throw Error(SourceLocation{target.string()}, "the output would replace the input");
  const std::string text = converted(options, target);
  if (fs::exists(target, ec) && !options.force && readInputFile(target) != text) {
    throw Error(SourceLocation{target.string()},
                "the file exists and differs from the conversion; --force replaces it");
  }
  writeFileAtomically(target, text);
  if (!quiet) out << fmt::format("wrote {}\n", target.string());
  return 0;
}

}  // namespace graspkit::cli
