#pragma once
// Raw Embree, the baseline of the ray benchmarks (raycast_bench, render_bench): a flat scene of
// world-space triangles and rays traced one at a time or in packets, with no graspkit code.

#include <embree3/rtcore.h>

#include <array>
#include <cstdint>
#include <limits>
#include <vector>

#include "graspkit/raycast/ray_scene.hpp"

namespace graspkit::bench {

inline RTCScene triangleScene(RTCDevice device, const std::vector<Vector3>& vertices,
                              const std::vector<std::array<std::uint32_t, 3>>& triangles) {
  RTCScene scene = rtcNewScene(device);
  rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_HIGH);
  rtcSetSceneFlags(scene, RTC_SCENE_FLAG_ROBUST);
  RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(
      geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), vertices.size()));
  for (std::size_t i = 0; i < vertices.size(); ++i)
    for (int k = 0; k < 3; ++k) v[3 * i + k] = static_cast<float>(vertices[i][k]);
  auto* t = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0,
                                                           RTC_FORMAT_UINT3, 3 * sizeof(unsigned),
                                                           triangles.size()));
  for (std::size_t i = 0; i < triangles.size(); ++i)
    for (int k = 0; k < 3; ++k) t[3 * i + k] = triangles[i][k];
  rtcCommitGeometry(geometry);
  rtcAttachGeometry(scene, geometry);
  rtcReleaseGeometry(geometry);
  rtcCommitScene(scene);
  return scene;
}

inline void fill(RTCRayHit& rh, const Ray& ray) {
  rh.ray.org_x = static_cast<float>(ray.origin.x());
  rh.ray.org_y = static_cast<float>(ray.origin.y());
  rh.ray.org_z = static_cast<float>(ray.origin.z());
  rh.ray.dir_x = static_cast<float>(ray.direction.x());
  rh.ray.dir_y = static_cast<float>(ray.direction.y());
  rh.ray.dir_z = static_cast<float>(ray.direction.z());
  rh.ray.tnear = 0.0f;
  rh.ray.tfar = std::numeric_limits<float>::infinity();
  rh.ray.time = 0.0f;
  rh.ray.mask = ~0u;
  rh.ray.id = 0;
  rh.ray.flags = 0;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
}

// rtcIntersect1 over every ray; returns the number of hits.
inline std::size_t rawIntersect1(RTCScene scene, const std::vector<Ray>& rays) {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  std::size_t hits = 0;
  for (const Ray& ray : rays) {
    RTCRayHit rh;
    fill(rh, ray);
    rtcIntersect1(scene, &context, &rh);
    hits += rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
  }
  return hits;
}

template <int N, class Packet, class Function>
inline std::size_t rawIntersectN(RTCScene scene, const std::vector<Ray>& rays, Function intersect) {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  alignas(64) Packet packet;
  alignas(64) int valid[N];
  std::size_t hits = 0;
  for (std::size_t start = 0; start < rays.size(); start += N) {
    for (int k = 0; k < N; ++k) {
      const bool in = start + k < rays.size();
      valid[k] = in ? -1 : 0;
      RTCRayHit rh;
      fill(rh, in ? rays[start + k] : rays[0]);
      packet.ray.org_x[k] = rh.ray.org_x;
      packet.ray.org_y[k] = rh.ray.org_y;
      packet.ray.org_z[k] = rh.ray.org_z;
      packet.ray.dir_x[k] = rh.ray.dir_x;
      packet.ray.dir_y[k] = rh.ray.dir_y;
      packet.ray.dir_z[k] = rh.ray.dir_z;
      packet.ray.tnear[k] = rh.ray.tnear;
      packet.ray.tfar[k] = rh.ray.tfar;
      packet.ray.time[k] = 0.0f;
      packet.ray.mask[k] = ~0u;
      packet.ray.id[k] = 0;
      packet.ray.flags[k] = 0;
      packet.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
      packet.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
    }
    intersect(valid, scene, &context, &packet);
    for (int k = 0; k < N; ++k) hits += valid[k] && packet.hit.geomID[k] != RTC_INVALID_GEOMETRY_ID;
  }
  return hits;
}

}  // namespace graspkit::bench
