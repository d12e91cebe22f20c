#pragma once
// Body files: the GraspIt! Body XML (material, mass properties, geometry file), or a bare
// geometry file (.iv, .wrl, .off, .ply, .stl, .obj) loaded with default properties.

#include <filesystem>
#include <memory>

#include "graspkit/body.hpp"
#include "graspkit/io/model_cache.hpp"

namespace graspkit {

// Throws graspkit::Error naming file, line and element for anything the file gets wrong.
std::shared_ptr<const BodyModel> loadBodyFile(const std::filesystem::path& file,
                                              ModelCache* cache = nullptr);

}  // namespace graspkit
