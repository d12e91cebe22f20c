#pragma once
// Internal: closest points between triangles, and GraspIt!'s rule for which point pairs of two
// nearby triangles count as contacts. Double precision throughout.

#include <vector>

#include "graspkit/math/transform.hpp"

namespace graspkit::collision {

struct Triangle {
  Vector3 a, b, c;
  Vector3 vertex(int i) const { return i == 0 ? a : (i == 1 ? b : c); }
};

// Surfaces apart or across by less than this touch (mm): files give 7 or 8 digits, so a face
// meant to lie in a plane can tilt out of it by 1e-6 mm.
constexpr double kTouchingTolerance = 1e-5;

struct PointPair {
  Vector3 onFirst;
  Vector3 onSecond;
};

// The point of triangle t nearest to p (Voronoi regions of vertices, edges and face).
Vector3 closestPointOnTriangle(const Triangle& t, const Vector3& p);

// Nearest points c1 on [p1, q1] and c2 on [p2, q2]; returns |c1 - c2|^2.
double closestPointsOnSegments(const Vector3& p1, const Vector3& q1, const Vector3& p2,
                               const Vector3& q2, Vector3& c1, Vector3& c2);

// Whether the two (closed) triangles share a point.
bool trianglesIntersect(const Triangle& t1, const Triangle& t2);

// GraspIt!'s contact rule for one triangle pair: every vertex of t2 nearer than the threshold to
// t1's face; every vertex of t1 near t2's face unless the nearest point is one of t2's corners
// (already counted); every edge pair whose nearest points are both interior to the edges.
// Appends the pairs (on t1, on t2) and returns true, or returns false when the triangles
// intersect (no contacts then: they interpenetrate). With `touching_is_contact`, triangles
// that share points but neither crosses the other's plane by more than kTouchingTolerance touch:
// they give their pairs at distance 0, kept only where t1 lies on the outer side of t2's face
// (whose normal the contact then takes).
bool triangleContacts(const Triangle& t1, const Triangle& t2, double threshold_sq,
                      std::vector<PointPair>& pairs, bool touching_is_contact = false);

}  // namespace graspkit::collision
