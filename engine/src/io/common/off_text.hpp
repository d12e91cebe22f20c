#pragma once
// Internal: a mesh as OFF text, every coordinate in its shortest exact form, so reading the file
// back gives the very same doubles (the GraspIt! exporter's and generated objects' mesh files).

#include <string>

#include "graspkit/geometry/mesh.hpp"

namespace graspkit::io {

std::string offText(const TriangleMesh& mesh);

}  // namespace graspkit::io
