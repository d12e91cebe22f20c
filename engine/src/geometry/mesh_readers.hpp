#pragma once
// The per-format readers behind loadMesh (mesh_loader.cpp). Each takes a path that exists and
// throws graspkit::Error naming it when the content is unusable; a readable file with no
// triangles gives an empty mesh (loadMesh warns).

#include <filesystem>
#include <string>

#include "graspkit/base/error.hpp"
#include "graspkit/geometry/mesh.hpp"
#include "graspkit/geometry/mesh_loader.hpp"

namespace graspkit::detail {

// Where in a geometry file a problem lies; line 0 when the reader cannot tell.
inline SourceLocation locationIn(const std::string& file, int line = 0) {
  SourceLocation where;
  where.file = file;
  where.line = line;
  return where;
}

// Inventor (.iv) and VRML 2 (.wrl) through Coin3D; inventor_reader.cpp.
TriangleMesh readInventor(const std::filesystem::path& path);

// OFF; off_reader.cpp.
TriangleMesh readOff(const std::filesystem::path& path);

// STL, OBJ and PLY through assimp; assimp_reader.cpp.
TriangleMesh readWithAssimp(const std::filesystem::path& path, MeshFormat format);

}  // namespace graspkit::detail
