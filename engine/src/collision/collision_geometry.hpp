#pragma once
// The collision geometry of one mesh (internal to the collision module): the FCL
// bounding-volume hierarchy (split by the surface-area rule, surface_area_splitter.hpp), the mesh's
// box in its body frame, for a cheap world-box test before any FCL call, and its convex hull, which
// proves most near pairs apart faster than the hierarchy can.

#include <memory>
#include <optional>

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/math/bv/OBBRSS.h>

#include "geometry/convex_hull.hpp"
#include "graspkit/collision/collision.hpp"

namespace graspkit {

// OBBRSS: FCL's oriented mesh traversal works in the frame of the first mesh, so no vertex is
// ever transformed per query; the OBB part gives tight overlap tests for collide, the RSS part
// cheap lower bounds for distance. bench/collision_bench.cpp compares the other BV types.
using BoundingVolume = fcl::OBBRSSd;
using Bvh = fcl::BVHModel<BoundingVolume>;

// The hull of one closed part of a mesh, with the box of the part's vertices (body frame, mm).
struct HullPart {
  geometry::ConvexHull hull;
  Vector3 boxCenter;
  Vector3 boxHalfSize;
};

struct CollisionGeometry {
  std::shared_ptr<const Bvh> bvh;            // never null
  Vector3 boxCenter;                         // body frame, mm
  Vector3 boxHalfSize;                       // half extents of the axis-aligned box, mm
  std::optional<geometry::ConvexHull> hull;  // of the hierarchy's vertices; none when flat
  // A mesh put together from 2 to kMaxHullParts closed parts (a URDF or MJCF link of several
  // geoms: a finger and its holder) has a hull per part, each with volume; empty otherwise. The
  // parts' hulls hug the mesh where the whole hull spans the gaps between them.
  std::vector<HullPart> parts;
};

inline constexpr int kMaxHullParts = 8;

// The world axis-aligned box of a body-frame box under `pose`: the centre moves with the pose,
// and the half extents become |R| times the half extents (Arvo's method).
struct WorldBox {
  Vector3 center;
  Vector3 halfSize;
  bool overlaps(const WorldBox& other) const {
    return ((center - other.center).cwiseAbs().array() <= (halfSize + other.halfSize).array())
        .all();
  }
};

inline WorldBox worldBox(const CollisionGeometry& geometry, const Transform& pose) {
  return {pose * geometry.boxCenter, pose.linear().cwiseAbs() * geometry.boxHalfSize};
}

// collisionGeometry(mesh) without its shared lock and reference count, for queries that look
// every body up at every call: a few recent meshes are remembered per thread. The pointer stays
// valid while `mesh` lives (the cache drops an entry only once its mesh has died). Null for an
// empty or flat mesh.
const CollisionGeometry* collisionGeometryOf(const std::shared_ptr<const TriangleMesh>& mesh);

// Whether the root bounding volumes of two placed meshes are apart: FCL's traversal would stop
// there, and so can a query, before FCL is called at all (a hand's links, checked against each
// other at every step, are mostly this far apart).
bool rootVolumesApart(const CollisionGeometry& a, const Transform& pose_a,
                      const CollisionGeometry& b, const Transform& pose_b);

// Whether the convex hulls of two placed meshes are certainly apart, so the meshes cannot touch.
// The axis that separated the pair last, then the axis between the boxes' centres, then the one
// GJK finds through the hulls' nearest points (geometry/hull_distance.hpp) are tried in turn; the
// certificate is that every hull vertex of one lies below, and every one of the other above, a
// plane across that axis, checked vertex by vertex, so GJK's tolerance never decides a collision.
// Where the whole hulls meet and a mesh has parts (CollisionGeometry::parts), every part's hull
// apart from every part's (or whole) hull of the other proves it the same way.
// False proves nothing. With `by` > 0: whether they are certainly more than `by` mm apart.
// A collision query tests rootVolumesApart first: a certificate is not worth its memory there.
bool hullsApart(const CollisionGeometry& a, const Transform& pose_a, const CollisionGeometry& b,
                const Transform& pose_b, double by = 0.0);

}  // namespace graspkit
