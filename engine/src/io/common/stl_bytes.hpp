#pragma once
// Internal: a mesh as binary STL in metres (the robot exporters' mesh files).

#include <string>

#include "graspkit/geometry/mesh.hpp"

namespace graspkit::io {

std::string stlBytes(const TriangleMesh& mesh);

}  // namespace graspkit::io
