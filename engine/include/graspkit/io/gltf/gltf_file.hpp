#pragma once
// glTF 2.0 export (binary .glb, through tinygltf): the bodies of one or more worlds as meshes
// with their poses and colours, so that any glTF viewer, Blender or a web page shows them.
//
// Units and frames: glTF is in metres, so vertices and translations are the engine's mm / 1000;
// axes are the world's own (no change of up axis). Each body (obstacle, graspable body, robot
// base, link, mount piece) is one node named as the engine names it, holding a mesh shared by
// every node and scene that uses the same geometry. Each scene is one world: a plan exports one
// scene per grasp. Colours are the file's (Inventor materials) or the material's, as in render.

#include <filesystem>
#include <span>
#include <string>

namespace graspkit {

class World;

struct GltfScene {
  std::string name;
  const World* world = nullptr;
  // A JSON object (text) stored as the scene's "extras", e.g. a grasp's quality and contacts;
  // empty for none. three.js shows it as the scene's userData.
  std::string extras;
};

// The .glb bytes of `scenes`. Throws graspkit::Error for a null world or extras that are not a
// JSON object.
std::string gltfBinary(std::span<const GltfScene> scenes);

// Writes gltfBinary(scenes) to `file` atomically.
void saveGltf(std::span<const GltfScene> scenes, const std::filesystem::path& file);

}  // namespace graspkit
