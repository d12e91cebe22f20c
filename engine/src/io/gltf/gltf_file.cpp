#include "graspkit/io/gltf/gltf_file.hpp"

#include <cmath>
#include <cstring>
#include <map>
#include <sstream>

#include <tiny_gltf.h>
#include <nlohmann/json.hpp>

#include "graspkit/base/error.hpp"
#include "graspkit/base/output_file.hpp"
#include "graspkit/math/units.hpp"
#include "graspkit/model/body_ref.hpp"
#include "graspkit/model/material.hpp"
#include "graspkit/model/world.hpp"

namespace graspkit {

namespace {

tinygltf::Value toValue(const nlohmann::json& j) {
  if (j.is_object()) {
    tinygltf::Value::Object object;
    for (const auto& [key, value] : j.items()) object[key] = toValue(value);
    return tinygltf::Value(std::move(object));
  }
  if (j.is_array()) {
    tinygltf::Value::Array array;
    for (const auto& value : j) array.push_back(toValue(value));
    return tinygltf::Value(std::move(array));
  }
  if (j.is_boolean()) return tinygltf::Value(j.get<bool>());
  if (j.is_number_integer() && std::abs(j.get<double>()) < 2e9)
    return tinygltf::Value(j.get<int>());
  if (j.is_number()) return tinygltf::Value(j.get<double>());
  if (j.is_string()) return tinygltf::Value(j.get<std::string>());
  return {};
}

// glTF's base colour is linear; Inventor's colours are the display's (sRGB-like).
double toLinear(float c) {
  return std::pow(static_cast<double>(c), 2.2);
}

// Builds the model: one buffer, one mesh per geometry (one primitive per colour), one material
// per colour, one node per body per scene.
class GltfBuilder {
 public:
  GltfBuilder() {
    model_.asset.version = "2.0";
    model_.asset.generator = "graspkit";
    model_.buffers.emplace_back();
  }

  void addScene(const GltfScene& scene) {
    if (scene.world == nullptr) throw Error("glTF export: scene '" + scene.name + "' has no world");
    tinygltf::Scene out;
    out.name = scene.name;
    if (!scene.extras.empty()) {
      const nlohmann::json extras = nlohmann::json::parse(scene.extras, nullptr, false);
      if (!extras.is_object())
        throw Error("glTF export: the extras of scene '" + scene.name + "' are not a JSON object");
      out.extras = toValue(extras);
    }
    for (const BodyRef& body : worldBodies(*scene.world)) {
      const BodyModel& model = bodyModel(*scene.world, body);
      if (!model.mesh || model.mesh->empty()) continue;
      tinygltf::Node node;
      node.name = bodyName(*scene.world, body);
      node.mesh = meshFor(*model.mesh, materialColour(model.material));
      const Transform pose = bodyPose(*scene.world, body);
      const Vector3 t = pose.translation() * (1.0 / units::kMetre);
      const Quaternion q(pose.linear());
      node.translation = {t.x(), t.y(), t.z()};
      node.rotation = {q.x(), q.y(), q.z(), q.w()};
      out.nodes.push_back(static_cast<int>(model_.nodes.size()));
      model_.nodes.push_back(std::move(node));
    }
    model_.scenes.push_back(std::move(out));
  }

  std::string binary() {
    model_.defaultScene = model_.scenes.empty() ? -1 : 0;
    model_.buffers[0].data = std::move(bytes_);
    std::ostringstream out;
    tinygltf::TinyGLTF writer;
    if (!writer.WriteGltfSceneToStream(&model_, out, false, true))
      throw Error("glTF export: tinygltf could not write the model");
    return out.str();
  }

 private:
  int meshFor(const TriangleMesh& mesh, Colour fallback) {
    const auto key =
        std::make_pair(&mesh, std::array<float, 3>{fallback.r, fallback.g, fallback.b});
    if (const auto it = meshes_.find(key); it != meshes_.end()) return it->second;
    const int positions = addPositions(mesh);
    // Triangles grouped by colour, in order of first appearance.
    std::vector<std::pair<Colour, std::vector<std::uint32_t>>> groups;
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
      const Colour colour = i < mesh.triangleColours.size() ? mesh.triangleColours[i] : fallback;
      auto group = std::find_if(groups.begin(), groups.end(),
                                [&](const auto& g) { return g.first == colour; });
      if (group == groups.end()) group = groups.insert(groups.end(), {colour, {}});
      group->second.insert(group->second.end(), mesh.triangles[i].begin(), mesh.triangles[i].end());
    }
    tinygltf::Mesh out;
    for (const auto& [colour, indices] : groups) {
      tinygltf::Primitive primitive;
      primitive.attributes["POSITION"] = positions;
      primitive.indices = addIndices(indices);
      primitive.material = materialFor(colour);
      primitive.mode = TINYGLTF_MODE_TRIANGLES;
      out.primitives.push_back(std::move(primitive));
    }
    model_.meshes.push_back(std::move(out));
    const int index = static_cast<int>(model_.meshes.size()) - 1;
    meshes_[key] = index;
    return index;
  }

  int materialFor(const Colour& colour) {
    const std::array<float, 3> key{colour.r, colour.g, colour.b};
    if (const auto it = materials_.find(key); it != materials_.end()) return it->second;
    tinygltf::Material material;
    material.pbrMetallicRoughness.baseColorFactor = {toLinear(colour.r), toLinear(colour.g),
                                                     toLinear(colour.b), 1.0};
    material.pbrMetallicRoughness.metallicFactor = 0.0;
    material.pbrMetallicRoughness.roughnessFactor = 0.7;
    material.doubleSided = true;  // some GraspIt! models are open surfaces
    model_.materials.push_back(std::move(material));
    materials_[key] = static_cast<int>(model_.materials.size()) - 1;
    return materials_[key];
  }

  // Appends raw bytes to the buffer, 4-byte aligned, as a view; returns the view's index.
  int addView(const void* data, std::size_t size, int target) {
    while (bytes_.size() % 4 != 0) bytes_.push_back(0);
    tinygltf::BufferView view;
    view.buffer = 0;
    view.byteOffset = bytes_.size();
    view.byteLength = size;
    view.target = target;
    const auto* begin = static_cast<const unsigned char*>(data);
    bytes_.insert(bytes_.end(), begin, begin + size);
    model_.bufferViews.push_back(view);
    return static_cast<int>(model_.bufferViews.size()) - 1;
  }

  int addPositions(const TriangleMesh& mesh) {
    std::vector<float> xyz;
    xyz.reserve(mesh.vertices.size() * 3);
    std::vector<double> low(3, std::numeric_limits<double>::infinity());
    std::vector<double> high(3, -std::numeric_limits<double>::infinity());
    for (const Vector3& v : mesh.vertices) {
      for (int k = 0; k < 3; ++k) {
        const float c = static_cast<float>(v[k] * (1.0 / units::kMetre));
        xyz.push_back(c);
        low[static_cast<std::size_t>(k)] = std::min(low[static_cast<std::size_t>(k)], double(c));
        high[static_cast<std::size_t>(k)] = std::max(high[static_cast<std::size_t>(k)], double(c));
      }
    }
    tinygltf::Accessor accessor;
    accessor.bufferView =
        addView(xyz.data(), xyz.size() * sizeof(float), TINYGLTF_TARGET_ARRAY_BUFFER);
    accessor.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
    accessor.type = TINYGLTF_TYPE_VEC3;
    accessor.count = mesh.vertices.size();
    accessor.minValues = low;
    accessor.maxValues = high;
    model_.accessors.push_back(std::move(accessor));
    return static_cast<int>(model_.accessors.size()) - 1;
  }

  int addIndices(const std::vector<std::uint32_t>& indices) {
    tinygltf::Accessor accessor;
    accessor.bufferView = addView(indices.data(), indices.size() * sizeof(std::uint32_t),
                                  TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
    accessor.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
    accessor.type = TINYGLTF_TYPE_SCALAR;
    accessor.count = indices.size();
    model_.accessors.push_back(std::move(accessor));
    return static_cast<int>(model_.accessors.size()) - 1;
  }

  tinygltf::Model model_;
  std::vector<unsigned char> bytes_;
  std::map<std::pair<const TriangleMesh*, std::array<float, 3>>, int> meshes_;
  std::map<std::array<float, 3>, int> materials_;
};

}  // namespace

std::string gltfBinary(std::span<const GltfScene> scenes) {
  GltfBuilder builder;
  for (const GltfScene& scene : scenes) builder.addScene(scene);
  return builder.binary();
}

void saveGltf(std::span<const GltfScene> scenes, const std::filesystem::path& file) {
  writeFileAtomically(file, gltfBinary(scenes));
}

}  // namespace graspkit
