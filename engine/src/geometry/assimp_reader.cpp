// STL (ASCII and binary), OBJ, PLY and COLLADA through assimp. assimp triangulates polygons, welds
// identical vertices within each mesh and bakes the node transforms into the vertices; we
// concatenate its meshes into one and keep only the triangles (points and lines bound nothing).

#include <cmath>
#include <cstdint>
#include <fstream>
#include <string>

#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/IOStream.hpp>  // complete, so that Close() runs its destructor
#include <assimp/IOSystem.hpp>
#include <assimp/Importer.hpp>

#include "geometry/mesh_readers.hpp"
#include "geometry/ply_header.hpp"
#include "graspkit/base/error.hpp"
#include "graspkit/base/input_file.hpp"

namespace graspkit::detail {
namespace {

// Normals, colours and texture coordinates are dropped first: STL repeats every corner with
// its facet's normal, and assimp only joins vertices that agree in every component.
constexpr unsigned kPostProcess = aiProcess_RemoveComponent | aiProcess_Triangulate |
                                  aiProcess_JoinIdenticalVertices | aiProcess_PreTransformVertices |
                                  aiProcess_ValidateDataStructure;
constexpr int kRemovedComponents =
    aiComponent_NORMALS | aiComponent_TANGENTS_AND_BITANGENTS | aiComponent_COLORS |
    aiComponent_TEXCOORDS | aiComponent_BONEWEIGHTS | aiComponent_ANIMATIONS |
    aiComponent_TEXTURES | aiComponent_LIGHTS | aiComponent_CAMERAS | aiComponent_MATERIALS;

// assimp picks its importer by extension; the hint makes the caller's format win, so binary STL
// saved as .stlb (whose bytes carry no signature to sniff) loads too.
const char* formatHint(MeshFormat format) {
  switch (format) {
    case MeshFormat::Stl:
      return "stl";
    case MeshFormat::Obj:
      return "obj";
    case MeshFormat::Ply:
      return "ply";
    case MeshFormat::Collada:
      return "dae";
    default:
      return "";
  }
}

void appendMesh(const aiMesh& source, const SourceLocation& where, TriangleMesh& mesh) {
  const auto offset = static_cast<std::uint32_t>(mesh.vertices.size());
  mesh.vertices.reserve(mesh.vertices.size() + source.mNumVertices);
  for (unsigned i = 0; i < source.mNumVertices; ++i) {
    const aiVector3D& p = source.mVertices[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
      throw Error(where, "vertex " + std::to_string(i) + " has a non-finite coordinate");
    }
    mesh.vertices.emplace_back(p.x, p.y, p.z);
  }
  for (unsigned f = 0; f < source.mNumFaces; ++f) {
    const aiFace& face = source.mFaces[f];
    if (face.mNumIndices != 3) continue;
    std::array<std::uint32_t, 3> triangle;
    for (int k = 0; k < 3; ++k) {
      // ValidateDataStructure already rejects these; checked again because a bad index here
      // would be a read out of bounds later, not just a wrong answer.
      if (face.mIndices[k] >= source.mNumVertices) {
        throw Error(where, "face " + std::to_string(f) + " has an out-of-range vertex index");
      }
      triangle[k] = offset + face.mIndices[k];
    }
    mesh.triangles.push_back(triangle);
  }
}

// The file system assimp sees: none. The file itself is read into memory first, through the
// engine's input gate; whatever else an importer asks for (an OBJ's material library, which
// could name a FIFO or a file outside a sandbox) is simply not there.
class NoFiles final : public Assimp::IOSystem {
 public:
  bool Exists(const char* /*file*/) const override { return false; }
  char getOsSeparator() const override { return '/'; }
  Assimp::IOStream* Open(const char* /*file*/, const char* /*mode*/) override { return nullptr; }
  void Close(Assimp::IOStream* stream) override { delete stream; }
};

}  // namespace

TriangleMesh readWithAssimp(const std::filesystem::path& path, MeshFormat format) {
  const SourceLocation where = locationIn(path.string());
  // Read from memory: the geometry is all we keep, so an OBJ's material library is not needed.
  const std::string bytes = readInputFile(path);
  if (bytes.empty()) throw Error(where, "the file is empty");
  if (format == MeshFormat::Ply) checkPlyHeader(bytes, where);
  Assimp::Importer importer;
  importer.SetIOHandler(new NoFiles);  // the importer owns it
  importer.SetPropertyInteger(AI_CONFIG_PP_RVC_FLAGS, kRemovedComponents);
  const aiScene* scene =
      importer.ReadFileFromMemory(bytes.data(), bytes.size(), kPostProcess, formatHint(format));
  if (scene == nullptr)
    throw Error(where, std::string("cannot read: ") + importer.GetErrorString());
  if ((scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE) != 0) {
    throw Error(where, "the file holds an incomplete scene");
  }
  TriangleMesh mesh;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) appendMesh(*scene->mMeshes[m], where, mesh);
  return mesh;
}

}  // namespace graspkit::detail
