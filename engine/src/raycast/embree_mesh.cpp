#include "raycast/embree_mesh.hpp"

#include <cmath>
#include <limits>
#include <mutex>
#include <unordered_map>

#include "geometry/closest_point.hpp"
#include "graspkit/base/error.hpp"

namespace graspkit::raycast {

RTCDevice device() {
  // Created on first use and kept for the life of the process: scenes outlive any one world.
  static RTCDevice instance = [] {
    RTCDevice d = rtcNewDevice(nullptr);
    if (!d) throw Error("Embree: could not create a device");
    return d;
  }();
  return instance;
}

EmbreeMesh::EmbreeMesh(std::shared_ptr<const TriangleMesh> mesh) : mesh_(std::move(mesh)) {
  scene_ = rtcNewScene(device());
  rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);
  rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);
  RTCGeometry geometry = rtcNewGeometry(device(), RTC_GEOMETRY_TYPE_TRIANGLE);
  const auto& vertices = mesh_->vertices;
  auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(
      geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), vertices.size()));
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    bounds_.extend(vertices[i]);
    for (int k = 0; k < 3; ++k) v[3 * i + k] = toEmbreeFloat(vertices[i][k]);
  }
  const auto& triangles = mesh_->triangles;
  auto* t = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0,
                                                           RTC_FORMAT_UINT3, 3 * sizeof(unsigned),
                                                           triangles.size()));
  triangle_boxes_.reserve(triangles.size());
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    for (int k = 0; k < 3; ++k) t[3 * i + k] = triangles[i][k];
    Eigen::AlignedBox3d box(vertices[triangles[i][0]]);
    triangle_boxes_.push_back(
        box.extend(vertices[triangles[i][1]]).extend(vertices[triangles[i][2]]));
  }
  for (const Eigen::AlignedBox3d& box : triangle_boxes_)
    mean_triangle_size_ += box.diagonal().norm() / static_cast<double>(triangle_boxes_.size());
  rtcCommitGeometry(geometry);
  rtcAttachGeometry(scene_, geometry);
  rtcReleaseGeometry(geometry);
  rtcCommitScene(scene_);
}

EmbreeMesh::~EmbreeMesh() {
  rtcReleaseScene(scene_);
}

namespace {

struct NearQuery {
  void* user;
  void (*callback)(void*, unsigned);
};

bool visitPrimitive(RTCPointQueryFunctionArguments* args) {
  auto* query = static_cast<NearQuery*>(args->userPtr);
  query->callback(query->user, args->primID);
  return false;  // the search radius stays as it is
}

}  // namespace

void EmbreeMesh::forEachNear(const Vector3& center, double radius, Callback callback,
                             void* user) const {
  if (mesh_->triangles.empty()) return;
  const double pad = floatPad(center);
  RTCPointQuery query;
  query.x = toEmbreeFloat(center.x());
  query.y = toEmbreeFloat(center.y());
  query.z = toEmbreeFloat(center.z());
  query.time = 0.0f;
  query.radius = toEmbreeFloat(radius + pad);
  RTCPointQueryContext context;
  rtcInitPointQueryContext(&context);
  NearQuery near{user, callback};
  rtcPointQuery(scene_, &query, &context, &visitPrimitive, &near);
}

namespace {

struct NearestSearch {
  const TriangleMesh* mesh;
  Vector3 center;
  double pad;
  double best;  // the distance to beat, mm
  std::optional<EmbreeMesh::Nearest> found;
};

bool visitNearest(RTCPointQueryFunctionArguments* args) {
  auto* search = static_cast<NearestSearch*>(args->userPtr);
  const auto& t = search->mesh->triangles[args->primID];
  const auto& v = search->mesh->vertices;
  const Vector3 p = geometry::closestPointOnTriangle(search->center, v[t[0]], v[t[1]], v[t[2]]);
  const double d = (p - search->center).norm();
  if (!(d < search->best)) return false;
  search->best = d;
  search->found = EmbreeMesh::Nearest{args->primID, p, d};
  args->query->radius = toEmbreeFloat(d + search->pad);
  return true;
}

}  // namespace

std::optional<EmbreeMesh::Nearest> EmbreeMesh::nearest(const Vector3& center,
                                                       double maxDistance) const {
  if (mesh_->triangles.empty()) return std::nullopt;
  NearestSearch search{mesh_.get(), center, floatPad(center),
                       std::nextafter(maxDistance, std::numeric_limits<double>::infinity()),
                       std::nullopt};
  RTCPointQuery query;
  query.x = toEmbreeFloat(center.x());
  query.y = toEmbreeFloat(center.y());
  query.z = toEmbreeFloat(center.z());
  query.time = 0.0f;
  // Infinite radii are fine: Embree shrinks nothing until the callback does.
  query.radius = toEmbreeFloat(maxDistance + search.pad);
  RTCPointQueryContext context;
  rtcInitPointQueryContext(&context);
  rtcPointQuery(scene_, &query, &context, &visitNearest, &search);
  return search.found;
}

std::shared_ptr<const EmbreeMesh> embreeMesh(const std::shared_ptr<const TriangleMesh>& mesh) {
  struct Entry {
    std::weak_ptr<const TriangleMesh> mesh;
    std::shared_ptr<const EmbreeMesh> embree;
  };
  static std::mutex mutex;
  static std::unordered_map<const TriangleMesh*, Entry> cache;
  if (!mesh) throw Error("Embree: no mesh");
  std::lock_guard lock(mutex);
  auto it = cache.find(mesh.get());
  if (it != cache.end() && !it->second.mesh.expired()) return it->second.embree;
  if (it == cache.end()) {
    // Drop entries of meshes that have died, so the cache never grows without bound.
    std::erase_if(cache, [](const auto& item) { return item.second.mesh.expired(); });
  }
  auto built = std::make_shared<const EmbreeMesh>(mesh);
  cache[mesh.get()] = Entry{mesh, built};
  return built;
}

}  // namespace graspkit::raycast
