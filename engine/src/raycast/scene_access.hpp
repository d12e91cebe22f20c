#pragma once
// The Embree scene behind a RayScene, for the engine's renderer: a picture traces hundreds of
// thousands of camera rays that need only a hit's body, triangle and facing, so it packs them
// into Embree packets itself instead of going through RayScene's checked double-precision hits.

#include <embree3/rtcore.h>

#include <vector>

#include "graspkit/model/body_ref.hpp"
#include "graspkit/raycast/ray_scene.hpp"

namespace graspkit::raycast {

struct SceneAccess {
  // The committed top-level scene; a hit's instID[0] indexes instancePoses and bodies().
  static RTCScene scene(const RayScene& scene);
  static std::vector<Transform> instancePoses(const RayScene& scene);
};

}  // namespace graspkit::raycast
