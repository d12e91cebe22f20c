#include "graspkit/io/graspit/body_file.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include <fmt/format.h>

#include "graspkit/base/file_reference.hpp"
#include "graspkit/base/log.hpp"
#include "graspkit/base/output_file.hpp"
#include "graspkit/geometry/mass_properties.hpp"
#include "graspkit/geometry/mesh_loader.hpp"
#include "io/common/export_text.hpp"
#include "io/common/off_text.hpp"
#include "io/common/xml.hpp"

namespace graspkit {
namespace {

// Model coordinates, mm: a thousand kilometres is beyond any robot or object, and well inside the
// float range of the ray and collision libraries.
constexpr double kMaxModelCoordinate = 1e9;

namespace fs = std::filesystem;
using tinyxml2::XMLElement;

MeshFormat formatFromType(const fs::path& file, const XMLElement& element,
                          const fs::path& geometry) {
  const char* type = element.Attribute("type");
  if (!type) return meshFormatFromExtension(geometry);
  const std::string_view t(type);
  if (t == "Inventor") return MeshFormat::Inventor;
  if (t == "off") return MeshFormat::Off;
  if (t == "ply") return MeshFormat::Ply;
  if (t == "stl") return MeshFormat::Stl;
  if (t == "obj") return MeshFormat::Obj;
  if (t == "dae") return MeshFormat::Collada;
  throw Error(xml::at(file, element),
              fmt::format("unknown geometry type '{}' (Inventor, off, ply, stl, obj or dae)", t));
}

double positive(const fs::path& file, const XMLElement& element) {
  const double value = xml::number(file, element);
  if (value <= 0) {
    throw Error(xml::at(file, element), fmt::format("must be greater than 0, found {}", value));
  }
  return value;
}

Vector3 geometryScaling(const fs::path& file, const XMLElement& root) {
  Vector3 scale = Vector3::Ones();
  if (const auto* uniform = xml::child(root, "geometryScaling")) {
    scale.setConstant(positive(file, *uniform));
  }
  const std::array<const char*, 3> axes = {"geometryScalingX", "geometryScalingY",
                                           "geometryScalingZ"};
  for (int i = 0; i < 3; ++i) {
    if (const auto* axis = xml::child(root, axes[i])) scale[i] = positive(file, *axis);
  }
  return scale;
}

void readMaterial(const fs::path& file, const XMLElement& root, BodyModel& body) {
  if (const auto* element = xml::child(root, "material")) {
    const std::string name = xml::text(*element);
    auto material = valueNamed<Material>(name);
    if (!material) {
      throw Error(xml::at(file, *element),
                  fmt::format("unknown material '{}' (frictionless, glass, metal, plastic, wood, "
                              "rubber or stone)",
                              name));
    }
    body.material = *material;
  }
  if (const auto* element = xml::child(root, "youngs")) body.youngs = positive(file, *element);
  const auto* normal = xml::child(root, "normalCompliance");
  const auto* shear = xml::child(root, "shearCompliance");
  if ((normal == nullptr) != (shear == nullptr)) {
    throw Error(xml::at(file, normal ? *normal : *shear),
                "normalCompliance and shearCompliance go together: give both or neither");
  }
  if (normal) {
    body.normalCompliance = positive(file, *normal);
    body.shearCompliance = positive(file, *shear);
  }
  if (const auto* element = xml::child(root, "useFlockOfBirds")) {
    // GraspIt!'s own files write the sensor number as a real ("1.0").
    const double number = xml::number(file, *element);
    if (!(number >= 0 && number <= 1e6) || number != std::floor(number)) {
      throw Error(xml::at(file, *element),
                  fmt::format("useFlockOfBirds takes a sensor number (a whole number from 0), "
                              "not '{}'",
                              xml::text(*element)));
    }
    body.useFlockOfBirds = true;
    body.flockOfBirdsNumber = static_cast<int>(number);
  }
}

void readMassProperties(const fs::path& file, const XMLElement& root, BodyModel& body) {
  if (const auto* element = xml::child(root, "mass")) {
    body.mass = positive(file, *element);
    body.massFromFile = true;
  }
  if (const auto* element = xml::child(root, "cog")) {
    body.cog = xml::vector3(file, *element);
    if (body.cog.cwiseAbs().maxCoeff() > kMaxModelCoordinate)
      throw Error(xml::at(file, *element),
                  fmt::format("a CoG beyond {:g} mm is not a body's", kMaxModelCoordinate));
    body.cogFromFile = true;
  }
  if (const auto* element = xml::child(root, "inertia_matrix")) {
    const auto v = xml::numbers(file, *element, 9);
    body.inertia = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(v.data());
    body.inertiaFromFile = true;
  }
}

// Fills in what the file left out, as GraspIt! does: the CoG defaults to the area-weighted
// surface centroid, the inertia to the volume integrals about the volume centroid.
void completeMassProperties(BodyModel& body) {
  const TriangleMesh& mesh = *body.mesh;
  if (!body.cogFromFile || !body.inertiaFromFile) {
    const MassProperties props = computeMassProperties(mesh);
    if (!body.cogFromFile) body.cog = surfaceCentroid(mesh);
    if (!body.inertiaFromFile) {
      if (props.valid) {
        body.inertia = props.inertia;
      } else {
        // GraspIt!'s fallback meant a unit diagonal (it sets elements 0, 3, 6, a slip we do
        // not copy): the body keeps a usable, symmetric inertia.
        body.inertia = Matrix3::Identity();
        body.inertiaFallback = true;
      }
    }
  }
  body.maxRadius = maxRadius(mesh, body.cog);
}

void readGeometry(const fs::path& file, const XMLElement& root, BodyModel& body) {
  const auto* element = xml::child(root, "geometryFile");
  if (!element) throw Error(xml::at(file, root), "missing <geometryFile>");
  const std::string name = xml::text(*element);
  if (name.empty()) throw Error(xml::at(file, *element), "empty geometry file name");
  body.geometryFile = file.parent_path() / name;
  body.geometryType = element->Attribute("type") ? element->Attribute("type") : "Inventor";
  const MeshFormat format = formatFromType(file, *element, body.geometryFile);
  TriangleMesh mesh;
  try {
    mesh = loadMesh(body.geometryFile, format);
  } catch (const Error& e) {
    throw Error(xml::at(file, *element), fmt::format("cannot load geometry: {}", e.what()));
  }
  body.geometryScaling = geometryScaling(file, root);
  if (const auto* offset = xml::child(root, "geometryOffset")) {
    const auto* t = xml::child(*offset, "transform");
    if (!t) throw Error(xml::at(file, *offset), "expected a <transform> inside");
    body.geometryOffset = xml::transform(file, *t);
  }
  // The offset sits outside the scale node, so it is in millimetres.
  Eigen::Affine3d placement = Eigen::Affine3d(body.geometryOffset.matrix());
  placement = placement * Eigen::Scaling(body.geometryScaling);
  transformMesh(mesh, placement);
  // Each factor may be finite and their product not (a scale of 1e300): refuse what would turn
  // into infinities, or into floats past range in the ray and collision queries, downstream.
  for (const Vector3& v : mesh.vertices) {
    if (!v.allFinite() || v.cwiseAbs().maxCoeff() > kMaxModelCoordinate) {
      const XMLElement* blame = xml::child(root, "geometryOffset");
      for (const char* scaling :
           {"geometryScaling", "geometryScalingX", "geometryScalingY", "geometryScalingZ"})
        if (!blame) blame = xml::child(root, scaling);
      throw Error(xml::at(file, blame ? *blame : *element),
                  fmt::format("the scaled and offset geometry reaches ({}, {}, {}) mm, beyond "
                              "the {:g} mm a model coordinate may hold",
                              v.x(), v.y(), v.z(), kMaxModelCoordinate));
    }
  }
  body.mesh = std::make_shared<const TriangleMesh>(std::move(mesh));
}

std::shared_ptr<const BodyModel> readBodyXml(const fs::path& file) {
  xml::Document doc(file);
  const XMLElement& root = doc.root();
  xml::warnUnknownChildren(
      file, root,
      {"material", "youngs", "normalCompliance", "shearCompliance", "useFlockOfBirds",
       "geometryFile", "geometryScaling", "geometryScalingX", "geometryScalingY",
       "geometryScalingZ", "geometryOffset", "mass", "cog", "inertia_matrix"});
  auto body = std::make_shared<BodyModel>();
  body->name = file.stem().string();
  body->file = file;
  readMaterial(file, root, *body);
  readMassProperties(file, root, *body);
  readGeometry(file, root, *body);
  completeMassProperties(*body);
  return body;
}

std::shared_ptr<const BodyModel> readBareGeometry(const fs::path& file) {
  auto body = std::make_shared<BodyModel>();
  body->name = file.stem().string();
  body->file = file;
  body->geometryFile = file;
  body->mesh = std::make_shared<const TriangleMesh>(loadMesh(file));
  completeMassProperties(*body);
  return body;
}

}  // namespace

void warnIfInertiaFallback(const BodyModel& body, const SourceLocation& where) {
  if (!body.inertiaFallback || body.inertiaFromFile) return;
  warn(WarningKind::Mass, where,
       fmt::format("the inertia of '{}' cannot be computed from its mesh (GraspIt! fails "
                   "too): the identity per unit mass is used; give <inertia_matrix> in {}",
                   body.name, body.file.filename().string()));
}

std::string bodyXmlForMesh(const fs::path& mesh_file, const fs::path& xml_file,
                           const BodyXmlOptions& options) {
  if (!(options.scale > 0.0) || !std::isfinite(options.scale))
    throw Error(SourceLocation{mesh_file.string()},
                fmt::format("the scale must be a positive number, found {}", options.scale));
  if (!(options.massGrams > 0.0) || !std::isfinite(options.massGrams))
    throw Error(
        SourceLocation{mesh_file.string()},
        fmt::format("the mass must be a positive number of grams, found {}", options.massGrams));
  BodyModel body;
  body.name = mesh_file.stem().string();
  TriangleMesh mesh = loadMesh(mesh_file);
  for (Vector3& v : mesh.vertices) v *= options.scale;
  body.mesh = std::make_shared<const TriangleMesh>(std::move(mesh));
  completeMassProperties(body);
  const Vector3& c = body.cog;
  const Matrix3& i = body.inertia;
  std::string xml = "<?xml version=\"1.0\" ?>\n<root>\n";
  xml += fmt::format("  <material>{}</material>\n", nameOf(options.material));
  xml += fmt::format("  <mass>{}</mass>\n", options.massGrams);
  xml += fmt::format("  <cog>{} {} {}</cog>\n", c.x(), c.y(), c.z());
  xml += fmt::format("  <inertia_matrix>{} {} {} {} {} {} {} {} {}</inertia_matrix>\n", i(0, 0),
                     i(0, 1), i(0, 2), i(1, 0), i(1, 1), i(1, 2), i(2, 0), i(2, 1), i(2, 2));
  const char* type = "Inventor";
  switch (meshFormatFromExtension(mesh_file)) {
    case MeshFormat::Off:
      type = "off";
      break;
    case MeshFormat::Ply:
      type = "ply";
      break;
    case MeshFormat::Stl:
      type = "stl";
      break;
    case MeshFormat::Obj:
      type = "obj";
      break;
    case MeshFormat::Collada:
      type = "dae";
      break;
    default:
      break;
  }
  xml += fmt::format("  <geometryFile type=\"{}\">{}</geometryFile>\n", type,
                     io::xmlEscaped(fileReference(mesh_file, xml_file.parent_path())));
  if (options.scale != 1.0)
    xml += fmt::format("  <geometryScaling>{}</geometryScaling>\n", options.scale);
  return xml + "</root>\n";
}

std::shared_ptr<const BodyModel> loadBodyFile(const fs::path& file, ModelCache* cache) {
  auto load = [&]() { return isMeshFile(file) ? readBareGeometry(file) : readBodyXml(file); };
  return cache ? cache->body(file, load) : load();
}

fs::path saveBodyFiles(const fs::path& folder, const std::string& name, const TriangleMesh& mesh,
                       const BodyXmlOptions& options) {
  createOutputFolder(folder);
  const fs::path off = folder / (name + ".off");
  const fs::path xml = folder / (name + ".xml");
  writeFileAtomically(off, io::offText(mesh));
  writeFileAtomically(xml, bodyXmlForMesh(off, xml, options));
  return xml;
}

}  // namespace graspkit
