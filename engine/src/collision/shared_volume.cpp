#include "collision/shared_volume.hpp"

#include <embree3/rtcore.h>

#include <algorithm>
#include <array>
#include <limits>
#include <map>
#include <utility>

#include "graspkit/model/body.hpp"
#include "graspkit/model/world.hpp"
#include "raycast/embree_mesh.hpp"

namespace graspkit {
namespace {

// Whether every edge of `mesh` is shared by exactly two triangles, vertices welded by position
// (an STL file repeats each vertex in every triangle that uses it).
bool isClosed(const TriangleMesh& mesh) {
  std::map<std::array<double, 3>, std::uint32_t> welded;
  std::vector<std::uint32_t> id(mesh.vertices.size());
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
    const Vector3& p = mesh.vertices[v];
    id[v] = welded.try_emplace({p.x(), p.y(), p.z()}, static_cast<std::uint32_t>(welded.size()))
                .first->second;
  }
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> uses;
  for (const auto& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = id[t[k]], b = id[t[(k + 1) % 3]];
      if (a == b) continue;  // a degenerate triangle's collapsed edge
      ++uses[std::minmax(a, b)];
    }
  }
  return !uses.empty() &&
         std::all_of(uses.begin(), uses.end(), [](const auto& edge) { return edge.second == 2; });
}

// The parity of the surface crossings along a ray from `origin` (mesh frame).
bool oddCrossings(const raycast::EmbreeMesh& mesh, const Vector3& origin,
                  const Vector3& direction) {
  const float reach = static_cast<float>(mesh.bounds().sizes().norm() * 4.0 + 1.0);
  const float step = reach * 1e-6f;  // past the last hit, so it is not found again
  float from = 0.0f;
  int crossings = 0;
  for (std::size_t hits = 0; hits <= mesh.mesh().triangleCount(); ++hits) {
    RTCRayHit query{};
    query.ray.org_x = raycast::toEmbreeFloat(origin.x());
    query.ray.org_y = raycast::toEmbreeFloat(origin.y());
    query.ray.org_z = raycast::toEmbreeFloat(origin.z());
    query.ray.dir_x = static_cast<float>(direction.x());
    query.ray.dir_y = static_cast<float>(direction.y());
    query.ray.dir_z = static_cast<float>(direction.z());
    query.ray.tnear = from;
    query.ray.tfar = std::numeric_limits<float>::infinity();
    query.ray.mask = 0xFFFFFFFFu;
    query.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    rtcIntersect1(mesh.scene(), &context, &query);
    if (query.hit.geomID == RTC_INVALID_GEOMETRY_ID) break;
    ++crossings;
    from = query.ray.tfar + step;
  }
  return crossings % 2 == 1;
}

// Inside a closed mesh: an odd number of crossings along most of three rays in unrelated
// directions (a ray through an edge counts it twice; three rays outvote one such accident).
bool inside(const raycast::EmbreeMesh& mesh, const Vector3& point) {
  static const Vector3 kDirections[] = {Vector3(0.5393, 0.6214, 0.5683).normalized(),
                                        Vector3(-0.7071, 0.3127, -0.6341).normalized(),
                                        Vector3(0.2311, -0.8919, 0.3886).normalized()};
  int votes = 0;
  for (const Vector3& direction : kDirections) votes += oddCrossings(mesh, point, direction);
  return votes >= 2;
}

// Whether a point of `a` lies inside `b` deeper than `depth`.
bool pointsOfFirstInside(const BodyModel& a, const Transform& a_pose, const BodyModel& b,
                         const Transform& b_pose, double depth) {
  const auto b_embree = raycast::embreeMesh(b.mesh);
  const Transform a_to_b = b_pose.inverse() * a_pose;
  Eigen::AlignedBox3d core = b_embree->bounds();
  core.min().array() += depth;
  core.max().array() -= depth;
  if (core.isEmpty()) return false;
  const auto deep_inside_b = [&](const Vector3& in_b) {
    return core.contains(in_b) && inside(*b_embree, in_b) && !b_embree->nearest(in_b, depth);
  };
  const TriangleMesh& mesh = *a.mesh;
  for (const auto& t : mesh.triangles) {
    const Vector3 centroid =
        (mesh.vertices[t[0]] + mesh.vertices[t[1]] + mesh.vertices[t[2]]) / 3.0;
    if (deep_inside_b(a_to_b * centroid)) return true;
  }
  // Two equal bodies at one pose share every surface point: a's centre of mass, when inside a,
  // is a point of its volume.
  return inside(*raycast::embreeMesh(a.mesh), a.cog) && deep_inside_b(a_to_b * a.cog);
}

}  // namespace

bool sharesVolume(const World& world, const BodyRef& body1, const BodyRef& body2, double depth) {
  const BodyModel& model1 = bodyModel(world, body1);
  const BodyModel& model2 = bodyModel(world, body2);
  if (!model1.mesh || !model2.mesh || model1.mesh->empty() || model2.mesh->empty()) return false;
  if (!isClosed(*model1.mesh) || !isClosed(*model2.mesh)) return false;
  const Transform pose1 = bodyPose(world, body1);
  const Transform pose2 = bodyPose(world, body2);
  return pointsOfFirstInside(model1, pose1, model2, pose2, depth) ||
         pointsOfFirstInside(model2, pose2, model1, pose1, depth);
}

}  // namespace graspkit
