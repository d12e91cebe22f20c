#include "graspkit/geometry/mesh_loader.hpp"

#include <algorithm>
#include <cctype>
#include <string>
#include <system_error>

#include "geometry/mesh_readers.hpp"
#include "graspkit/base/error.hpp"
#include "graspkit/base/input_file.hpp"
#include "graspkit/base/log.hpp"

namespace graspkit {
namespace {

std::string lowerCaseExtension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  if (!ext.empty() && ext.front() == '.') ext.erase(0, 1);
  std::ranges::transform(ext, ext.begin(),
                         [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

// A directory or a dangling path fails here with one clear message instead of a
// format-specific one from deep inside Coin or assimp. The read gate's check asks the read guard
// before it looks at the file, so a refused path tells nothing, not even whether it exists.
void requireRegularFile(const std::filesystem::path& path) {
  checkInputFile(path);
}

}  // namespace

bool isMeshFile(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".iv" || ext == ".wrl" || ext == ".off" || ext == ".ply" || ext == ".stl" ||
         ext == ".stlb" || ext == ".obj" || ext == ".dae";
}

MeshFormat meshFormatFromExtension(const std::filesystem::path& path) {
  const std::string ext = lowerCaseExtension(path);
  if (ext == "off") return MeshFormat::Off;
  if (ext == "ply") return MeshFormat::Ply;
  if (ext == "stl" || ext == "stlb") return MeshFormat::Stl;
  if (ext == "obj") return MeshFormat::Obj;
  if (ext == "dae") return MeshFormat::Collada;
  // .iv and .wrl, and anything unknown: GraspIt! hands every geometry file it does not
  // recognise to Coin, which also detects VRML 2 from the header line.
  return MeshFormat::Inventor;
}

namespace {

TriangleMesh readMesh(const std::filesystem::path& path, MeshFormat format) {
  switch (format) {
    case MeshFormat::Off:
      return detail::readOff(path);
    case MeshFormat::Ply:
    case MeshFormat::Stl:
    case MeshFormat::Obj:
    case MeshFormat::Collada:
      return detail::readWithAssimp(path, format);
    case MeshFormat::Auto:
    case MeshFormat::Inventor:
      break;
  }
  return detail::readInventor(path);
}

}  // namespace

TriangleMesh loadMesh(const std::filesystem::path& path, MeshFormat format) {
  requireRegularFile(path);
  if (format == MeshFormat::Auto) format = meshFormatFromExtension(path);
  TriangleMesh mesh = readMesh(path, format);
  // GraspIt! loads such a body on purpose (DynamicBody::computeDefaultMassProp says "No
  // triangles found"): it never collides, its CoG is the origin and its radius 0.
  if (mesh.triangles.empty())
    warn(WarningKind::Geometry, SourceLocation{path.string()},
         "the geometry holds no triangles: the body never collides or touches, its CoG is the "
         "origin and its radius 0");
  return mesh;
}

}  // namespace graspkit
