#pragma once
// What render, export and view show: a world file, or a plan's grasps (plan --out), each as a
// frame: the world as it stands and, for a grasp, its figures and contacts.

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "graspkit/collision/contact.hpp"
#include "graspkit/model/world.hpp"
#include "graspkit/render/render.hpp"
#include "support/load_flags.hpp"

namespace graspkit::cli {

struct SceneFrame {
  std::string name;  // the world's file stem, or "grasp N"
  World world;
  std::vector<BodyRef> focus;     // what an automatic camera frames: the hand and the object
  std::vector<Contact> contacts;  // the hand's contacts with the object (object side = body2)
  nlohmann::json summary;         // epsilon, volume, contact count...; empty for a bare world
  bool fromPlan = false;          // a plan's grasp: its world's <camera> framed the open hand
};

struct FrameSource {
  std::filesystem::path input;  // a world XML or a plan JSON
  LoadFlags load;
  bool contacts = false;  // find the contacts of the world's first hand with its first object
  int grasp = 0;          // plans: only grasp N (1-based) when > 0
  int top = 0;            // plans: the first N grasps when > 0 (all when 0)
};

// A world file gives one frame; a plan gives one per grasp, from the worlds plan --out wrote
// beside it (or, for JSON without them, its world with each grasp's closed pose and DOFs).
// Throws graspkit::Error naming the file for bad input or a grasp number out of range.
std::vector<SceneFrame> loadFrames(const FrameSource& source);

// The frame as glTF scene extras: {"summary": {...}, "contacts": [{"point", "normal", "mu"}]}
// with points in metres (glTF's unit) on the object and normals opening the friction cones.
std::string frameExtras(const SceneFrame& frame);

// The frames as binary glTF: one scene each, named as the frame, with frameExtras.
std::string framesGltf(const std::vector<SceneFrame>& frames);

// The camera a picture of `frame` starts from: --camera's choice (see kCameraNames).
ViewCamera chooseCamera(const SceneFrame& frame, const std::string& camera, double aspect);

// True when `file` holds a plan (JSON), false for a world (XML): by its .json extension, else
// by its first character.
bool isPlanFile(const std::filesystem::path& file);

}  // namespace graspkit::cli
