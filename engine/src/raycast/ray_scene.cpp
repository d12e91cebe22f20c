#include "graspkit/raycast/ray_scene.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "geometry/closest_point.hpp"
#include "graspkit/base/error.hpp"
#include "graspkit/model/world.hpp"
#include "raycast/embree_mesh.hpp"
#include "raycast/scene_access.hpp"

namespace graspkit {

using raycast::EmbreeMesh;
using raycast::toEmbreeFloat;

namespace raycast {

// One body of the scene: an Embree instance of its mesh's shared scene. The double poses are
// kept beside Embree's float copy so results are computed in double. Outside the anonymous
// namespace because RayScene::Impl, which has external linkage, holds them.
struct Instance {
  BodyRef body;
  std::shared_ptr<const EmbreeMesh> mesh;
  RTCGeometry geometry = nullptr;  // owned by the top-level scene
  Transform pose = Transform::Identity();
  Transform inverse = Transform::Identity();
};

}  // namespace raycast

using raycast::Instance;

namespace {

// Embree's RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR: the three rotation columns, then the translation.
void setInstancePose(RTCGeometry geometry, const Transform& pose) {
  float m[12];
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 3; ++r) m[3 * c + r] = toEmbreeFloat(pose.matrix()(r, c));
  rtcSetGeometryTransform(geometry, 0, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, m);
  rtcCommitGeometry(geometry);
}

bool finite(const Vector3& v) {
  return v.allFinite();
}

// Embree works in float: a coordinate past float range becomes infinite inside it and aborts the
// process. Scenes are in mm; this bound is far beyond any of them and well inside float range.
constexpr double kMaxRayCoordinate = 1e20;

// A checked ray with its direction made unit.
struct UnitRay {
  Vector3 origin;
  Vector3 direction;
  double tmin, tmax;
};

UnitRay checkedRay(const Ray& ray, std::size_t index, bool batch) {
  const auto fail = [&](const std::string& what) {
    throw Error("RayScene::intersect: " + (batch ? "ray " + std::to_string(index) + ": " : "") +
                what);
  };
  if (!finite(ray.origin)) fail("origin is not finite");
  if (ray.origin.cwiseAbs().maxCoeff() > kMaxRayCoordinate)
    fail("origin is more than 1e20 mm from the world origin");
  if (!finite(ray.direction)) fail("direction is not finite");
  const double length = ray.direction.norm();
  if (!(length > 0) || !std::isfinite(length)) fail("direction has no usable length");
  if (!std::isfinite(ray.tmin) || ray.tmin < 0) fail("tmin must be finite and >= 0");
  if (ray.tmin > kMaxRayCoordinate) fail("tmin is more than 1e20 mm");
  if (std::isnan(ray.tmax)) fail("tmax is NaN");
  return {ray.origin, ray.direction / length, ray.tmin, ray.tmax};
}

// Embree's float segment; a tmax below tmin leaves an empty segment that hits nothing.
template <class RayT>
void fillRay(RayT& r, const UnitRay& ray) {
  r.org_x = toEmbreeFloat(ray.origin.x());
  r.org_y = toEmbreeFloat(ray.origin.y());
  r.org_z = toEmbreeFloat(ray.origin.z());
  r.dir_x = toEmbreeFloat(ray.direction.x());
  r.dir_y = toEmbreeFloat(ray.direction.y());
  r.dir_z = toEmbreeFloat(ray.direction.z());
  r.tnear = toEmbreeFloat(ray.tmin);
  r.tfar = toEmbreeFloat(ray.tmax);  // past float range: no end
  r.time = 0.0f;
  r.mask = ~0u;
  r.id = 0;
  r.flags = 0;
}

}  // namespace

struct RayScene::Impl {
  RTCScene scene = nullptr;
  std::vector<Instance> instances;  // index = Embree instance geometry id
  std::vector<BodyRef> bodies;
  double extent = 0.0;  // largest |coordinate| of any instance's world bounds, for float pads

  ~Impl() {
    if (scene) rtcReleaseScene(scene);
  }

  void place(Instance& instance, const World& world) {
    instance.pose = bodyPose(world, instance.body);
    instance.inverse = instance.pose.inverse(Eigen::Isometry);
    setInstancePose(instance.geometry, instance.pose);
  }

  void measure() {
    extent = 0.0;
    for (const Instance& instance : instances) {
      const auto& box = instance.mesh->bounds();
      const double radius = 0.5 * box.sizes().norm();
      const Vector3 centre = instance.pose * box.center();
      extent = std::max(extent, centre.cwiseAbs().maxCoeff() + radius);
    }
  }

  // Float rounding of the instance transforms, vertices and the query point, in mm.
  double pad(const Vector3& point) const {
    return 2e-6 * (point.cwiseAbs().maxCoeff() + extent) + 1e-6;
  }

  const Instance& instanceOf(const BodyRef& body) const {
    for (const Instance& instance : instances)
      if (instance.body == body) return instance;
    throw Error("RayScene: body is not in the scene");
  }

  // The hit Embree found: triangle `primitive` of instance `id`, at float distance `t`, with
  // the unnormalised object-space normal `ng`, which points as (v1-v0) x (v2-v0): the
  // counter-clockwise normal (the rotated-cube test pins this down). Float throughout, as
  // documented; reading the mesh's double vertices here to refine cost 15% of the ray's time.
  RayHit hit(const UnitRay& ray, unsigned id, unsigned primitive, float t, float ngx, float ngy,
             float ngz) const {
    const Instance& instance = instances[id];
    RayHit result;
    result.body = instance.body;
    result.triangle = static_cast<int>(primitive);
    result.distance = t;
    result.point = ray.origin + result.distance * ray.direction;
    const Vector3 n = instance.pose.linear() * Vector3(ngx, ngy, ngz);
    const double length = n.norm();
    result.normal = length > 0 ? Vector3(n / length) : Vector3(-ray.direction);
    return result;
  }
};

RayScene::RayScene(const World& world, const RaySceneOptions& options)
    : impl_(std::make_unique<Impl>()) {
  Impl& s = *impl_;
  RTCDevice device = raycast::device();
  s.scene = rtcNewScene(device);
  // A handful of instances: rebuilding the top level on every update() costs microseconds.
  rtcSetSceneFlags(s.scene, RTC_SCENE_FLAG_DYNAMIC | RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(s.scene, RTC_BUILD_QUALITY_LOW);
  for (const BodyRef& body : worldBodies(world)) {
    if (options.include && !options.include(body)) continue;
    const auto& mesh = bodyModel(world, body).mesh;
    if (!mesh || mesh->empty()) continue;
    Instance instance;
    instance.body = body;
    instance.mesh = raycast::embreeMesh(mesh);
    instance.geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_INSTANCE);
    rtcSetGeometryInstancedScene(instance.geometry, instance.mesh->scene());
    rtcSetGeometryTimeStepCount(instance.geometry, 1);
    const auto id = static_cast<unsigned>(s.instances.size());
    rtcAttachGeometryByID(s.scene, instance.geometry, id);
    rtcReleaseGeometry(instance.geometry);  // the scene keeps it alive
    s.place(instance, world);
    s.bodies.push_back(body);
    s.instances.push_back(std::move(instance));
  }
  s.measure();
  rtcCommitScene(s.scene);
}

RayScene::~RayScene() = default;
RayScene::RayScene(RayScene&&) noexcept = default;
RayScene& RayScene::operator=(RayScene&&) noexcept = default;

void RayScene::update(const World& world) {
  Impl& s = *impl_;
  // Check everything first: a failed update leaves the scene as it was.
  for (const Instance& instance : s.instances)
    if (!isValid(world, instance.body))
      throw Error("RayScene::update: the world has no body " + std::to_string(instance.body.index) +
                  " of the scene");
  for (Instance& instance : s.instances) {
    // A clone shares its meshes; a body given another mesh gets that mesh's shared scene.
    const auto& mesh = bodyModel(world, instance.body).mesh;
    if (mesh && !mesh->empty() && &instance.mesh->mesh() != mesh.get()) {
      instance.mesh = raycast::embreeMesh(mesh);
      rtcSetGeometryInstancedScene(instance.geometry, instance.mesh->scene());
    }
    s.place(instance, world);
  }
  s.measure();
  rtcCommitScene(s.scene);
}

const std::vector<BodyRef>& RayScene::bodies() const {
  return impl_->bodies;
}

std::optional<RayHit> RayScene::intersect(const Ray& input) const {
  const UnitRay ray = checkedRay(input, 0, false);
  if (ray.tmax < ray.tmin) return std::nullopt;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rayhit;
  fillRay(rayhit.ray, ray);
  rayhit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rayhit.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(impl_->scene, &context, &rayhit);
  if (rayhit.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
  return impl_->hit(ray, rayhit.hit.instID[0], rayhit.hit.primID, rayhit.ray.tfar, rayhit.hit.Ng_x,
                    rayhit.hit.Ng_y, rayhit.hit.Ng_z);
}

void RayScene::intersect(std::span<const Ray> rays, std::span<std::optional<RayHit>> hits) const {
  if (rays.size() != hits.size())
    throw Error("RayScene::intersect: " + std::to_string(rays.size()) + " rays but " +
                std::to_string(hits.size()) + " hit slots");
  // Check every ray first, so a bad one leaves `hits` untouched.
  for (std::size_t i = 0; i < rays.size(); ++i) checkedRay(rays[i], i, true);
  intersectChecked(rays, [&](std::size_t i, const RayHit* hit) {
    if (hit)
      hits[i] = *hit;
    else
      hits[i].reset();
  });
}

void RayScene::intersect(std::span<const Ray> rays, HitSink sink, void* context) const {
  intersectChecked(rays, [&](std::size_t i, const RayHit* hit) { sink(context, i, hit); });
}

// Each ray is checked again as it is traced (checkedRay also normalises it).
template <class Sink>
void RayScene::intersectChecked(std::span<const Ray> rays, Sink&& sink) const {
  // Packets of 8: on incoherent rays (bench/raycast_bench.cpp) they beat single rays by 15%,
  // packets of 16 by 6% and rtcIntersect1M streams by 9% (AVX-512 machine, Embree 3.13).
  constexpr int N = 8;
  alignas(64) RTCRayHit8 packet;
  alignas(64) int valid[N];
  UnitRay unit[N];
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  for (std::size_t start = 0; start < rays.size(); start += N) {
    const int count = static_cast<int>(std::min<std::size_t>(N, rays.size() - start));
    for (int k = 0; k < N; ++k) {
      valid[k] = 0;
      packet.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
      packet.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
      if (k >= count) continue;
      unit[k] = checkedRay(rays[start + k], start + k, true);
      if (unit[k].tmax < unit[k].tmin) continue;
      valid[k] = -1;
      RTCRay ray;
      fillRay(ray, unit[k]);
      packet.ray.org_x[k] = ray.org_x;
      packet.ray.org_y[k] = ray.org_y;
      packet.ray.org_z[k] = ray.org_z;
      packet.ray.dir_x[k] = ray.dir_x;
      packet.ray.dir_y[k] = ray.dir_y;
      packet.ray.dir_z[k] = ray.dir_z;
      packet.ray.tnear[k] = ray.tnear;
      packet.ray.tfar[k] = ray.tfar;
      packet.ray.time[k] = 0.0f;
      packet.ray.mask[k] = ~0u;
      packet.ray.id[k] = 0;
      packet.ray.flags[k] = 0;
    }
    rtcIntersect8(valid, impl_->scene, &context, &packet);
    for (int k = 0; k < count; ++k) {
      if (!valid[k] || packet.hit.geomID[k] == RTC_INVALID_GEOMETRY_ID) {
        sink(start + k, nullptr);
        continue;
      }
      const RayHit hit =
          impl_->hit(unit[k], packet.hit.instID[0][k], packet.hit.primID[k], packet.ray.tfar[k],
                     packet.hit.Ng_x[k], packet.hit.Ng_y[k], packet.hit.Ng_z[k]);
      sink(start + k, &hit);
    }
  }
}

namespace {

// A point query over the instanced scene. Embree walks the top-level BVH and each instance's
// mesh BVH in float; each candidate triangle is measured here in double in its body's frame
// (a rigid pose keeps distances), and the search radius shrinks to the best distance so far.
struct WorldSearch {
  const std::vector<Instance>* instances;
  Vector3 point;  // world
  double pad;
  double best;
  unsigned lastInstance = RTC_INVALID_GEOMETRY_ID;
  Vector3 local = Vector3::Zero();  // `point` in lastInstance's frame
  unsigned instance = RTC_INVALID_GEOMETRY_ID;
  EmbreeMesh::Nearest found;
};

bool visitWorld(RTCPointQueryFunctionArguments* args) {
  auto* search = static_cast<WorldSearch*>(args->userPtr);
  const RTCPointQueryContext* context = args->context;
  if (context->instStackSize == 0) return false;  // the top level holds only instances
  const unsigned id = context->instID[context->instStackSize - 1];
  const Instance& instance = (*search->instances)[id];
  if (id != search->lastInstance) {
    search->lastInstance = id;
    search->local = instance.inverse * search->point;
  }
  const TriangleMesh& mesh = instance.mesh->mesh();
  const auto& t = mesh.triangles[args->primID];
  const Vector3 p = geometry::closestPointOnTriangle(search->local, mesh.vertices[t[0]],
                                                     mesh.vertices[t[1]], mesh.vertices[t[2]]);
  const double d = (p - search->local).norm();
  if (!(d < search->best)) return false;
  search->best = d;
  search->instance = id;
  search->found = EmbreeMesh::Nearest{args->primID, p, d};
  args->query->radius = toEmbreeFloat(d + search->pad);
  return true;
}

void checkQuery(const Vector3& point, double maxDistance) {
  if (!finite(point)) throw Error("RayScene::nearestSurfacePoint: point is not finite");
  if (point.cwiseAbs().maxCoeff() > kMaxRayCoordinate)
    throw Error("RayScene::nearestSurfacePoint: point is more than 1e20 mm from the world origin");
  if (std::isnan(maxDistance) || maxDistance < 0)
    throw Error("RayScene::nearestSurfacePoint: maxDistance must be >= 0");
}

SurfacePoint surfacePoint(const Instance& instance, const EmbreeMesh::Nearest& nearest) {
  const TriangleMesh& mesh = instance.mesh->mesh();
  const auto& t = mesh.triangles[nearest.triangle];
  const Vector3& a = mesh.vertices[t[0]];
  const Vector3 n = (mesh.vertices[t[1]] - a).cross(mesh.vertices[t[2]] - a);
  SurfacePoint result;
  result.body = instance.body;
  result.triangle = static_cast<int>(nearest.triangle);
  result.point = instance.pose * nearest.point;
  result.normal =
      n.norm() > 0 ? Vector3(instance.pose.linear() * n.normalized()) : Vector3::UnitZ();
  result.distance = nearest.distance;
  return result;
}

}  // namespace

std::optional<SurfacePoint> RayScene::nearestSurfacePoint(const Vector3& point, double maxDistance,
                                                          std::span<const BodyRef> only) const {
  checkQuery(point, maxDistance);
  const Impl& s = *impl_;
  if (!only.empty()) {
    // A few named bodies: query each mesh in its own frame, passing the best distance on.
    std::optional<SurfacePoint> best;
    for (const BodyRef& body : only) {
      auto found = nearestSurfacePoint(body, point, best ? best->distance : maxDistance);
      if (found && (!best || found->distance < best->distance)) best = found;
    }
    return best;
  }
  if (s.instances.empty()) return std::nullopt;
  // One body (a scene over the object alone): its own mesh scene, without the top level.
  if (s.instances.size() == 1) return nearestSurfacePoint(s.instances[0].body, point, maxDistance);
  WorldSearch search{&s.instances, point, s.pad(point),
                     std::nextafter(maxDistance, std::numeric_limits<double>::infinity())};
  RTCPointQuery query;
  query.x = toEmbreeFloat(point.x());
  query.y = toEmbreeFloat(point.y());
  query.z = toEmbreeFloat(point.z());
  query.time = 0.0f;
  query.radius = toEmbreeFloat(maxDistance + search.pad);
  RTCPointQueryContext context;
  rtcInitPointQueryContext(&context);
  rtcPointQuery(s.scene, &query, &context, &visitWorld, &search);
  if (search.instance == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
  return surfacePoint(s.instances[search.instance], search.found);
}

std::optional<SurfacePoint> RayScene::nearestSurfacePoint(const BodyRef& body, const Vector3& point,
                                                          double maxDistance) const {
  checkQuery(point, maxDistance);
  const Instance& instance = impl_->instanceOf(body);
  // In the body's frame on its own mesh scene: no top level, no instance transform in float.
  auto nearest = instance.mesh->nearest(instance.inverse * point, maxDistance);
  if (!nearest) return std::nullopt;
  return surfacePoint(instance, *nearest);
}

namespace raycast {

RTCScene SceneAccess::scene(const RayScene& scene) {
  return scene.impl_->scene;
}

std::vector<Transform> SceneAccess::instancePoses(const RayScene& scene) {
  std::vector<Transform> poses;
  for (const auto& instance : scene.impl_->instances) poses.push_back(instance.pose);
  return poses;
}

}  // namespace raycast

}  // namespace graspkit
