// Collision queries. Each body is placed once per query: its shared geometry, its world pose and
// the world box of its mesh. Pairs go through the filter, then the box test, and only then to
// FCL, straight on the shared BVHs with the two poses: no FCL CollisionObject is made, so a query
// allocates nothing per pair but FCL's own traversal state.

#include "graspkit/collision.hpp"

#include <algorithm>

#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>

#include "collision/collision_geometry.hpp"
#include "graspkit/collision_filter.hpp"
#include "graspkit/world.hpp"

namespace graspkit {
namespace {

struct Placed {
  BodyRef ref;
  std::shared_ptr<const CollisionGeometry> geometry;  // null: an empty mesh, never collides
  Transform pose;
  WorldBox box;
};

Placed place(const World& world, const BodyRef& ref) {
  Placed placed{ref, collisionGeometry(bodyModel(world, ref).mesh), bodyPose(world, ref), {}};
  if (placed.geometry) placed.box = worldBox(*placed.geometry, placed.pose);
  return placed;
}

// FCL collide with one contact and no contact data: the traversal stops at the first pair of
// intersecting triangles.
bool narrowCollide(const Placed& a, const Placed& b) {
  const fcl::CollisionRequestd request(1, false);
  fcl::CollisionResultd result;
  return fcl::collide(a.geometry->bvh.get(), a.pose, b.geometry->bvh.get(), b.pose, request,
                      result) > 0;
}

bool collides(const Placed& a, const Placed& b) {
  return a.geometry && b.geometry && a.box.overlaps(b.box) && narrowCollide(a, b);
}

}  // namespace

bool collide(const World& world, const BodyRef& a, const BodyRef& b) {
  return collides(place(world, a), place(world, b));
}

DistanceResult distance(const World& world, const BodyRef& a, const BodyRef& b) {
  const Placed pa = place(world, a), pb = place(world, b);
  if (!pa.geometry || !pb.geometry) return {};
  if (pa.box.overlaps(pb.box)) {
    // Mesh distance in FCL reports the closest triangle pair, which for intersecting surfaces is
    // 0 only if it happens to find the crossing pair; a collide call settles it first.
    const fcl::CollisionRequestd request(1, true);
    fcl::CollisionResultd result;
    if (fcl::collide(pa.geometry->bvh.get(), pa.pose, pb.geometry->bvh.get(), pb.pose, request,
                     result) > 0) {
      const Vector3 point = result.getContact(0).pos;
      return {0.0, point, point};
    }
  }
  fcl::DistanceRequestd request(true);
  fcl::DistanceResultd result;
  fcl::distance(pa.geometry->bvh.get(), pa.pose, pb.geometry->bvh.get(), pb.pose, request, result);
  // The oriented BVH traversal returns the nearest points in world coordinates.
  return {result.min_distance, result.nearest_points[0], result.nearest_points[1]};
}

std::vector<CollidingPair> collisionReport(const World& world, const CollisionRequest& request) {
  const std::vector<BodyRef> refs = worldBodies(world);
  std::vector<Placed> placed;
  std::vector<char> interesting;
  placed.reserve(refs.size());
  interesting.reserve(refs.size());
  for (const BodyRef& ref : refs) {
    placed.push_back(place(world, ref));
    interesting.push_back(request.interest.empty() ||
                          std::find(request.interest.begin(), request.interest.end(), ref) !=
                              request.interest.end());
  }
  const CollisionFilter& filter = world.collisionFilter();
  std::vector<CollidingPair> report;
  for (std::size_t i = 0; i < placed.size(); ++i) {
    if (!placed[i].geometry) continue;
    for (std::size_t j = i + 1; j < placed.size(); ++j) {
      if (!interesting[i] && !interesting[j]) continue;
      // The box test first: it is a few flops, the filter a few lookups.
      if (!placed[j].geometry || !placed[i].box.overlaps(placed[j].box)) continue;
      if (!filter.isActive(world, placed[i].ref, placed[j].ref)) continue;
      if (!narrowCollide(placed[i], placed[j])) continue;
      report.push_back({placed[i].ref, placed[j].ref});
      if (request.firstOnly) return report;
    }
  }
  return report;
}

bool anyCollision(const World& world, std::span<const BodyRef> interest) {
  return !collisionReport(world, {interest, true}).empty();
}

}  // namespace graspkit
