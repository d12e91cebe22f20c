#pragma once
// Ray and nearest-surface queries over a world's bodies (Embree 3). A RayScene holds one
// instance per body of the shared per-mesh Embree geometry, placed at the body's pose, so
// building one for a world (or for each clone of it) costs only the instances: meshes are
// built once per process. update() re-reads the poses after the world moved.
//
// Precision: Embree works in float (vertices, instance transforms, rays), so hits are good to
// about 1e-5 relative to the scene's size: which triangle is hit near an edge, and the hit's
// distance, point and normal, carry float rounding. Nearest surface points are found the same
// way, but the reported point and distance are computed in double on the triangle found.
//
// Threads: queries are const and thread-safe on a scene that is not being updated; update()
// is not (give each thread its own RayScene, as each thread has its own World clone).

#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "graspkit/math/transform.hpp"
#include "graspkit/model/body_ref.hpp"

namespace graspkit {

class World;
namespace raycast {
struct SceneAccess;  // the engine's own pictures trace the Embree scene directly
}

struct Ray {
  Vector3 origin = Vector3::Zero();      // world, mm
  Vector3 direction = Vector3::UnitX();  // world; any non-zero length, queries normalise it
  double tmin = 0.0;                     // mm along the normalised direction, >= 0
  double tmax = std::numeric_limits<double>::infinity();  // mm; tmax < tmin finds nothing
};

struct RayHit {
  BodyRef body;
  int triangle = 0;                   // index into the body's mesh triangles
  Vector3 point = Vector3::Zero();    // world, mm
  Vector3 normal = Vector3::UnitZ();  // world, unit: the triangle's counter-clockwise normal
                                      // (outward for a closed mesh), whichever side was hit
  double distance = 0.0;              // mm from the ray's origin
};

struct SurfacePoint {
  BodyRef body;
  int triangle = 0;                   // index into the body's mesh triangles
  Vector3 point = Vector3::Zero();    // world, mm: the nearest point of the body's surface
  Vector3 normal = Vector3::UnitZ();  // world, unit: the triangle's counter-clockwise normal
  double distance = 0.0;              // mm from the query point
};

struct RaySceneOptions {
  // Which of worldBodies(world) the scene holds; empty holds them all. Robot links are
  // usually left out when casting at the object a hand is about to grasp.
  std::function<bool(const BodyRef&)> include;
};

class RayScene {
 public:
  explicit RayScene(const World& world, const RaySceneOptions& options = {});
  ~RayScene();
  // A moved-from RayScene may only be destroyed or assigned to.
  RayScene(RayScene&&) noexcept;
  RayScene& operator=(RayScene&&) noexcept;
  RayScene(const RayScene&) = delete;
  RayScene& operator=(const RayScene&) = delete;

  // Re-reads the poses of the scene's bodies from `world` (the world it was built from or a
  // clone) and recommits the instances; no mesh is rebuilt. Throws graspkit::Error when a body
  // of the scene no longer exists in `world`. Not thread-safe.
  void update(const World& world);

  // The bodies the scene holds, in worldBodies order.
  const std::vector<BodyRef>& bodies() const;

  // The first surface the ray meets within [tmin, tmax], from either side. Throws
  // graspkit::Error for a non-finite origin, direction, tmin, a zero direction or tmin < 0.
  std::optional<RayHit> intersect(const Ray& ray) const;
  // The same for many rays at once (Embree packets of 8); hits[i] answers rays[i]. Throws
  // graspkit::Error, before tracing any ray, when the sizes differ or a ray is bad as above.
  void intersect(std::span<const Ray> rays, std::span<std::optional<RayHit>> hits) const;
  // The same, handing the answer to rays[i] to sink(context, i, hit) (hit null for a miss)
  // instead of storing it: for callers that keep hits in a layout of their own (the C ABI). The
  // sink is called in order of i, from the calling thread; `hit` lives for the call only. Each
  // ray is checked as it is traced: a bad one throws after the rays before it were answered
  // (check the batch first where that matters, as the C ABI does).
  using HitSink = void (*)(void* context, std::size_t index, const RayHit* hit);
  void intersect(std::span<const Ray> rays, HitSink sink, void* context) const;

  // The nearest surface point of the scene's bodies (of `only`, when not empty) within
  // `maxDistance` mm of `point`; nullopt when none is that close. A small maxDistance makes the
  // query far cheaper. Throws graspkit::Error for a non-finite point, a NaN or negative
  // maxDistance, or a body of `only` that is not in the scene.
  std::optional<SurfacePoint> nearestSurfacePoint(
      const Vector3& point, double maxDistance = std::numeric_limits<double>::infinity(),
      std::span<const BodyRef> only = {}) const;
  // The nearest point of one body's surface (e.g. a planner's distance to the object).
  std::optional<SurfacePoint> nearestSurfacePoint(
      const BodyRef& body, const Vector3& point,
      double maxDistance = std::numeric_limits<double>::infinity()) const;

 private:
  friend struct raycast::SceneAccess;
  template <class Sink>
  void intersectChecked(std::span<const Ray> rays, Sink&& sink) const;

  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace graspkit
