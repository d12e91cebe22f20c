#pragma once
// Body files: the GraspIt! Body XML (material, mass properties, geometry file), or a bare
// geometry file (.iv, .wrl, .off, .ply, .stl, .obj) loaded with default properties.

#include <filesystem>
#include <memory>
#include <string>

#include "graspkit/base/error.hpp"
#include "graspkit/io/common/model_cache.hpp"
#include "graspkit/model/body.hpp"

namespace graspkit {

// Throws graspkit::Error naming file, line and element for anything the file gets wrong.
std::shared_ptr<const BodyModel> loadBodyFile(const std::filesystem::path& file,
                                              ModelCache* cache = nullptr);

// Warns at `where` when the body's inertia is the fallback (BodyModel::inertiaFallback): called
// where the value is used, for graspable bodies and robot links.
void warnIfInertiaFallback(const BodyModel& body, const SourceLocation& where);

// What a Body XML written for a bare mesh file says besides the mesh.
struct BodyXmlOptions {
  Material material = Material::Plastic;
  double massGrams = 300.0;  // GraspIt!'s default mass
  double scale = 1.0;        // <geometryScaling>, > 0
};

// The Body XML for `mesh_file`, to be written as `xml_file`: material, mass, the CoG and inertia
// graspkit computes for the scaled mesh (the surface centroid, and the volume integrals per unit
// mass, or the identity for an open mesh, as when the tags are absent), the geometry file and
// its scaling. The geometry is named as a Body XML reads it, relative to the XML's folder (its
// bare file name when the XML sits beside the mesh; `../meshes/mug.iv`), or absolute when the two
// share no folder below the file system's root (base/file_reference.hpp). Numbers are written in
// their shortest exact form, so loading the XML gives these very values. Throws graspkit::Error
// naming the mesh file.
std::string bodyXmlForMesh(const std::filesystem::path& mesh_file,
                           const std::filesystem::path& xml_file, const BodyXmlOptions& options);

// Saves `mesh` as a GraspIt! body: FOLDER/NAME.off (coordinates exact) and FOLDER/NAME.xml, the
// Body XML bodyXmlForMesh writes for it, each atomically. Returns the XML's path.
std::filesystem::path saveBodyFiles(const std::filesystem::path& folder, const std::string& name,
                                    const TriangleMesh& mesh, const BodyXmlOptions& options);

}  // namespace graspkit
