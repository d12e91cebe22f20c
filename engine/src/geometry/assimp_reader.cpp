// STL (ASCII and binary), OBJ and PLY through assimp. assimp triangulates polygons, welds
// identical vertices within each mesh and bakes the node transforms into the vertices; we
// concatenate its meshes into one and keep only the triangles (points and lines bound nothing).

#include <cmath>
#include <cstdint>
#include <string>

#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/Importer.hpp>

#include "geometry/mesh_readers.hpp"
#include "graspkit/error.hpp"

namespace graspkit::detail {
namespace {

constexpr unsigned kPostProcess = aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                                  aiProcess_PreTransformVertices | aiProcess_ValidateDataStructure;

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

}  // namespace

TriangleMesh readWithAssimp(const std::filesystem::path& path, MeshFormat /*format*/) {
  // assimp picks its importer from the extension and falls back to sniffing the content, which
  // covers the formats loadMesh routes here (including binary STL saved as .stlb).
  const SourceLocation where = locationIn(path.string());
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(path.string(), kPostProcess);
  if (scene == nullptr)
    throw Error(where, std::string("cannot read: ") + importer.GetErrorString());
  if ((scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE) != 0) {
    throw Error(where, "the file holds an incomplete scene");
  }
  TriangleMesh mesh;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) appendMesh(*scene->mMeshes[m], where, mesh);
  if (mesh.triangles.empty()) throw Error(where, "the file holds no triangles");
  return mesh;
}

}  // namespace graspkit::detail
