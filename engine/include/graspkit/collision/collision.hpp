#pragma once
// Collision and distance queries between the bodies of a world, over FCL. Like FCL, each query
// is a free function with narrow request and result structs.
//
// Meshes are compared as triangle surfaces, as GraspIt! does: two bodies collide when their
// surfaces intersect. A body entirely inside another, with no surface crossing, does not
// collide. A body whose mesh is empty (or has only zero-area triangles) never collides.
//
// Every mesh's bounding-volume hierarchy is built once, on first use, and shared by every world
// and clone that shows the mesh: see collisionGeometry() below.

#include <limits>
#include <memory>
#include <span>
#include <vector>

#include "graspkit/geometry/mesh.hpp"
#include "graspkit/math/transform.hpp"
#include "graspkit/model/body_ref.hpp"

namespace graspkit {

class World;

// Whether the surfaces of `a` and `b` intersect, whatever the world's CollisionFilter says.
// Stops at the first intersecting pair of triangles.
bool collide(const World& world, const BodyRef& a, const BodyRef& b);

struct DistanceResult {
  // The distance between the two surfaces, mm. 0 when they intersect: FCL measures no
  // penetration depth between meshes, so the result is never negative. +infinity when either
  // mesh is empty.
  double distance = std::numeric_limits<double>::infinity();
  // World coordinates, mm. When the surfaces are apart, the closest points on a and on b; when
  // they intersect, both are a point of the intersection. Zero when either mesh is empty.
  Vector3 pointOnA = Vector3::Zero();
  Vector3 pointOnB = Vector3::Zero();
};

// The distance between the surfaces of `a` and `b`, whatever the world's CollisionFilter says.
DistanceResult distance(const World& world, const BodyRef& a, const BodyRef& b);

// Whether the surfaces of `a` and `b` come closer than `threshold` mm (intersecting surfaces
// do), whatever the world's CollisionFilter says. The same answer as
// distance(...).distance < threshold, but FCL's traversal leaves out every pair of bounding
// volumes at least `threshold` apart, so near-miss pairs cost far less.
bool withinDistance(const World& world, const BodyRef& a, const BodyRef& b, double threshold);

struct CollisionRequest {
  // When not empty, only pairs with at least one body in this list are checked. The span must
  // stay valid during the call.
  std::span<const BodyRef> interest;
  // Stop at the first colliding pair (GraspIt!'s FAST_COLLISION): the report then holds at most
  // one pair, and which one is not specified beyond being a colliding active pair.
  bool firstOnly = false;
};

struct BodyPair {
  BodyRef first;  // first comes before second in worldBodies() order
  BodyRef second;
};
using CollidingPair = BodyPair;

// Every pair the world's CollisionFilter keeps active whose surfaces intersect, in worldBodies()
// order of the first body, then of the second.
std::vector<CollidingPair> collisionReport(const World& world,
                                           const CollisionRequest& request = {});

// Whether any active pair with at least one body in `interest` collides; an empty `interest`
// means every body.
bool anyCollision(const World& world, std::span<const BodyRef> interest);

// Every pair the world's CollisionFilter keeps active whose world bounding boxes come within
// `margin` mm of each other: the only pairs a contact search with threshold `margin` (or, with
// margin 0, a collision test) can find anything on. With `interest` not empty, only pairs with a
// body in it. In worldBodies() order of the first body, then of the second. A sweep finds them,
// so the cost follows the bodies and the pairs found, not the square of the bodies.
std::vector<BodyPair> nearbyPairs(const World& world, double margin,
                                  std::span<const BodyRef> interest = {});

// The collision geometry of a mesh: its FCL bounding-volume hierarchy and its bounding box.
// Opaque outside the collision module.
struct CollisionGeometry;

// The shared collision geometry of `mesh`, built on first request. It lives in a process-wide
// cache inside the engine (engine/src/collision/collision_geometry.cpp) keyed by the mesh; the
// cache holds the mesh weakly, so an entry goes stale when its mesh dies and is dropped later.
// Safe to call from several threads at once. Returns null for an empty mesh.
std::shared_ptr<const CollisionGeometry> collisionGeometry(
    const std::shared_ptr<const TriangleMesh>& mesh);

}  // namespace graspkit
