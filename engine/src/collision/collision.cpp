// Collision queries. Each body is placed once per query: its shared geometry, its world pose and
// the world box of its mesh. Pairs come from the broad phase (overlapping boxes), go through
// the filter, and only then to FCL, straight on the shared BVHs with the two poses: no FCL
// CollisionObject is made, so a query allocates nothing per pair but FCL's own traversal state.
// The placed world is one walk of the world into vectors this thread keeps, and the geometry of
// each mesh a lookup in a per-thread memo: a close asks for a report at every step (about 10 %
// of GraspIt!'s plannerMug autograsp went to looking bodies up, the cache's lock and allocation).

#include "graspkit/collision/collision.hpp"

#include <algorithm>

#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>

#include "collision/broad_phase.hpp"
#include "collision/collision_geometry.hpp"
#include "collision/working_memory.hpp"
#include "graspkit/model/collision_filter.hpp"
#include "graspkit/model/world.hpp"

namespace graspkit {
namespace {

struct Placed {
  BodyRef ref;
  const CollisionGeometry* geometry;  // null: an empty mesh, never collides; lives with the mesh
  Transform pose;
  WorldBox box;
};

Placed place(const BodyRef& ref, const BodyModel& model, const Transform& pose) {
  Placed placed{ref, collisionGeometryOf(model.mesh), pose, {}};
  if (placed.geometry) placed.box = worldBox(*placed.geometry, placed.pose);
  return placed;
}

Placed place(const World& world, const BodyRef& ref) {
  return place(ref, bodyModel(world, ref), bodyPose(world, ref));
}

// FCL collide with one contact and no contact data: the traversal stops at the first pair of
// intersecting triangles. Most near pairs are proved apart by their hulls first.
bool narrowCollide(const Placed& a, const Placed& b) {
  if (rootVolumesApart(*a.geometry, a.pose, *b.geometry, b.pose)) return false;
  if (hullsApart(*a.geometry, a.pose, *b.geometry, b.pose)) return false;
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

bool withinDistance(const World& world, const BodyRef& a, const BodyRef& b, double threshold) {
  const Placed pa = place(world, a), pb = place(world, b);
  if (!pa.geometry || !pb.geometry || !(threshold > 0)) return false;
  WorldBox reach = pa.box;
  reach.halfSize.array() += threshold;
  if (!reach.overlaps(pb.box)) return false;
  if (hullsApart(*pa.geometry, pa.pose, *pb.geometry, pb.pose, threshold)) return false;
  // FCL prunes a pair of bounding volumes once its lower bound reaches the smallest distance
  // found so far, and only ever lowers that: starting it at the threshold asks exactly whether
  // some pair of triangles is closer. Crossing triangles are at distance 0.
  const fcl::DistanceRequestd request(false);
  fcl::DistanceResultd result;
  result.min_distance = threshold;
  fcl::distance(pa.geometry->bvh.get(), pa.pose, pb.geometry->bvh.get(), pb.pose, request, result);
  return result.min_distance < threshold;
}

namespace {

// The bodies with geometry, placed, and whether each is of interest (all are when none is named).
struct PlacedWorld {
  std::vector<Placed> placed;
  std::vector<WorldBox> boxes;
  std::vector<char> interesting;
};

// The world placed into this thread's scene, whose vectors are kept between queries: a close
// asks for a report at every step. No query calls another while it holds the scene. The scene is
// handed out by reference, so the last query's vectors are measured against the working-memory
// rule here, before they are filled again, rather than after use.
const PlacedWorld& placeWorld(const World& world, std::span<const BodyRef> interest,
                              double margin) {
  thread_local std::vector<PlacedBody> bodies;
  thread_local PlacedWorld out;
  collision::keepOrRelease(bodies);
  collision::keepOrRelease(out.placed);
  collision::keepOrRelease(out.boxes);
  collision::keepOrRelease(out.interesting);
  placeWorldBodies(world, bodies);
  out.placed.clear();
  out.boxes.clear();
  out.interesting.clear();
  for (const PlacedBody& body : bodies) {
    const Placed placed = place(body.ref, *body.model, body.pose);
    if (!placed.geometry) continue;
    out.boxes.push_back(collision::grown(placed.box, 0.5 * margin));
    out.interesting.push_back(interest.empty() || std::find(interest.begin(), interest.end(),
                                                            body.ref) != interest.end());
    out.placed.push_back(placed);
  }
  return out;
}

// Calls visit(a, b) for each active pair with a body of interest whose boxes overlap (grown by
// half the margin each), in worldBodies() order, until visit returns false.
template <class Visit>
void forEachActivePair(const World& world, const PlacedWorld& scene, Visit&& visit) {
  const CollisionFilter& filter = world.collisionFilter();
  collision::forEachOverlappingPair(scene.boxes, [&](std::size_t i, std::size_t j) {
    if (!scene.interesting[i] && !scene.interesting[j]) return true;
    if (!filter.isActive(world, scene.placed[i].ref, scene.placed[j].ref)) return true;
    return visit(scene.placed[i], scene.placed[j]);
  });
}

}  // namespace

std::vector<CollidingPair> collisionReport(const World& world, const CollisionRequest& request) {
  const PlacedWorld& scene = placeWorld(world, request.interest, 0.0);
  std::vector<CollidingPair> report;
  forEachActivePair(world, scene, [&](const Placed& a, const Placed& b) {
    if (!narrowCollide(a, b)) return true;
    report.push_back({a.ref, b.ref});
    return !request.firstOnly;
  });
  return report;
}

std::vector<BodyPair> nearbyPairs(const World& world, double margin,
                                  std::span<const BodyRef> interest) {
  const PlacedWorld& scene = placeWorld(world, interest, std::max(margin, 0.0));
  std::vector<BodyPair> pairs;
  forEachActivePair(world, scene, [&](const Placed& a, const Placed& b) {
    pairs.push_back({a.ref, b.ref});
    return true;
  });
  return pairs;
}

bool anyCollision(const World& world, std::span<const BodyRef> interest) {
  return !collisionReport(world, {interest, true}).empty();
}

}  // namespace graspkit
