#pragma once
// What render, export, view, validate and serve show: a world file, a plan's grasps (plan --out)
// or a grasp dataset's (batch), each as a frame: the world as it stands and, for a grasp, its
// figures and contacts.

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "graspkit/collision/contact.hpp"
#include "graspkit/io/common/load_options.hpp"
#include "graspkit/model/world.hpp"
#include "graspkit/render/render.hpp"

namespace graspkit::cli {

struct SceneFrame {
  std::string name;  // the world's file stem, or "grasp N"
  World world;
  std::vector<BodyRef> focus;     // what an automatic camera frames: the hand and the object
  std::vector<Contact> contacts;  // the hand's contacts with the object (object side = body2)
  nlohmann::json summary;         // epsilon, volume, contact count...; empty for a bare world
  bool fromPlan =
      false;  // a grasp of a plan (its world's <camera> framed the open hand) or dataset
};

struct FrameSource {
  std::filesystem::path input;  // a world XML, a plan JSON or a dataset (HDF5)
  LoadOptions load;
  bool contacts = false;  // find the contacts of the world's first hand with its first object
  int grasp = 0;          // plans and datasets: only grasp N (1-based) when > 0
  int top = 0;            // plans and datasets: the first N grasps when > 0 (all when 0)
};

// A world file gives one frame; a plan gives one per grasp, from the worlds plan --out wrote
// beside it (or, for JSON without them, its world with each grasp's closed pose and DOFs); a
// dataset one per grasp, the hand closed over the object at the origin as batch left it (the
// hand loaded with `load`, which must be batch's: each grasp is measured again and must give
// the file's epsilon). Throws graspkit::Error naming the file for bad input, a grasp number out
// of range, or a dataset grasp that measures otherwise.
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

// True when `file` starts with HDF5's signature: a grasp dataset (graspkit batch).
bool isDatasetFile(const std::filesystem::path& file);

}  // namespace graspkit::cli
