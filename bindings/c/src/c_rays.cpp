// Ray and nearest-point queries in batches, over the engine's Embree scene.

#include <algorithm>
#include <cmath>
#include <optional>

#include <fmt/format.h>

#include "c_api_support.hpp"

using namespace graspkit;
using namespace graspkit::c_api;

namespace {

void fillHit(const BodyRef& body, int triangle, const Vector3& point, const Vector3& normal,
             double distance, graspkit_ray_hit& out) {
  out.hit = 1;
  out.triangle = triangle;
  out.body = toRef(body);
  for (int i = 0; i < 3; ++i) {
    out.point[i] = point[i];
    out.normal[i] = normal[i];
  }
  out.distance = distance;
}

void storeHit(void* context, std::size_t index, const RayHit* hit) {
  graspkit_ray_hit& out = static_cast<graspkit_ray_hit*>(context)[index];
  if (hit)
    fillHit(hit->body, hit->triangle, hit->point, hit->normal, hit->distance, out);
  else
    out = graspkit_ray_hit{};
}

// The engine's own checks (RayScene::intersect), made here first over the whole batch.
void checkRay(const graspkit_ray& r, std::size_t i) {
  constexpr double kFar = 1e20;  // mm, the engine's limit on coordinates
  const double o = std::max({std::abs(r.origin[0]), std::abs(r.origin[1]), std::abs(r.origin[2])});
  const bool finite = std::isfinite(o) && std::isfinite(r.direction[0]) &&
                      std::isfinite(r.direction[1]) && std::isfinite(r.direction[2]) &&
                      std::isfinite(r.tmin) && !std::isnan(r.tmax);
  const bool zero = r.direction[0] == 0 && r.direction[1] == 0 && r.direction[2] == 0;
  if (!finite || zero || r.tmin < 0 || o > kFar || r.tmin > kFar)
    throw Error(fmt::format("ray {}: {}", i,
                            !finite      ? "a value is not a finite number"
                            : zero       ? "the direction is zero"
                            : o > kFar   ? "the origin is more than 1e20 mm from the world origin"
                            : r.tmin < 0 ? "tmin is negative"
                                         : "tmin is more than 1e20 mm"));
}

const RayScene& sceneOf(const graspkit_ray_scene* scene) {
  return require(scene, "scene")->scene;
}

}  // namespace

extern "C" {

graspkit_status graspkit_ray_scene_new(const graspkit_world* world, int include_links,
                                       graspkit_ray_scene** scene) {
  return guarded([&] {
    const World& w = require(world, "world")->world;
    require(scene, "scene");
    RaySceneOptions options;
    if (!include_links) options.include = [](const BodyRef& b) { return !b.isLink(); };
    *scene = new graspkit_ray_scene{RayScene(w, options)};
  });
}

graspkit_status graspkit_ray_scene_update(graspkit_ray_scene* scene, const graspkit_world* world) {
  return guarded([&] { require(scene, "scene")->scene.update(require(world, "world")->world); });
}

graspkit_status graspkit_ray_scene_intersect(const graspkit_ray_scene* scene,
                                             const graspkit_ray* rays, graspkit_ray_hit* hits,
                                             size_t count) {
  return guarded([&] {
    const RayScene& s = sceneOf(scene);
    if (count == 0) return;
    require(rays, "rays");
    require(hits, "hits");
    // In chunks, so a batch of millions needs no second copy of itself: each chunk is checked
    // by the engine, after the whole batch was checked here (a bad ray fails the call before any
    // is traced), and each answer goes straight into the caller's array.
    for (std::size_t i = 0; i < count; ++i) checkRay(rays[i], i);
    constexpr std::size_t kChunk = 256;  // in the L1/L2 cache
    Ray in[kChunk];
    for (std::size_t start = 0; start < count; start += kChunk) {
      const std::size_t n = std::min(kChunk, count - start);
      for (std::size_t i = 0; i < n; ++i) {
        const graspkit_ray& r = rays[start + i];
        in[i].origin = Vector3(r.origin[0], r.origin[1], r.origin[2]);
        in[i].direction = Vector3(r.direction[0], r.direction[1], r.direction[2]);
        in[i].tmin = r.tmin;
        in[i].tmax = r.tmax;
      }
      s.intersect(std::span<const Ray>(in, n), &storeHit, hits + start);
    }
  });
}

graspkit_status graspkit_ray_scene_nearest(const graspkit_ray_scene* scene, const double* points,
                                           size_t count, double max_distance,
                                           graspkit_ray_hit* nearest) {
  return guarded([&] {
    const RayScene& s = sceneOf(scene);
    if (count == 0) return;
    require(points, "points");
    require(nearest, "nearest");
    if (std::isnan(max_distance) || max_distance < 0)
      throw Error(fmt::format("max_distance {} is not a distance", max_distance));
    for (std::size_t i = 0; i < count; ++i)
      if (!Vector3(points[3 * i], points[3 * i + 1], points[3 * i + 2]).allFinite())
        throw Error(fmt::format("point {}: a coordinate is not a finite number", i));
    for (std::size_t i = 0; i < count; ++i) {
      const Vector3 p(points[3 * i], points[3 * i + 1], points[3 * i + 2]);
      const auto found = s.nearestSurfacePoint(p, max_distance);
      if (!found) {
        nearest[i] = graspkit_ray_hit{};
        continue;
      }
      fillHit(found->body, found->triangle, found->point, found->normal, found->distance,
              nearest[i]);
    }
  });
}

void graspkit_ray_scene_free(graspkit_ray_scene* scene) {
  delete scene;
}

}  // extern "C"
