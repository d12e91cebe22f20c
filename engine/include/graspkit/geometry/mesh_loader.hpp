#pragma once
// Reading geometry files into triangle meshes:
//   Inventor (.iv) and VRML 2 (.wrl) through Coin3D (shape nodes tessellated, transforms applied),
//   OFF through the reader in geometry/off_reader.cpp,
//   STL, OBJ, PLY and COLLADA (.dae, as URDF hands use) through assimp.

#include <filesystem>
#include <string_view>

#include "graspkit/geometry/mesh.hpp"

namespace graspkit {

enum class MeshFormat { Auto, Inventor, Off, Ply, Stl, Obj, Collada };

// Guesses the format from the file extension (case-insensitive); Inventor when unknown.
MeshFormat meshFormatFromExtension(const std::filesystem::path& path);

// True for the extensions loadMesh reads (iv, wrl, off, ply, stl, stlb, obj, dae; any case).
bool isMeshFile(const std::filesystem::path& path);

// Loads a geometry file. Throws graspkit::Error naming the file (and line where the parser
// knows it) for missing, unreadable or malformed files. A file with no triangles (an empty
// Separator, a VRML file of comments) gives an empty mesh with a warning, as GraspIt! loads it.
TriangleMesh loadMesh(const std::filesystem::path& path, MeshFormat format = MeshFormat::Auto);

// Parses OFF text already in memory; `file` names it in errors. Exposed for the fuzz target.
TriangleMesh parseOff(std::string_view text, const std::string& file);

// Coin3D must be initialised once per process before Inventor files are read; loadMesh does
// it on first use. Thread-safe.
void initInventorReader();

}  // namespace graspkit
