#pragma once
// Internal: the point of the Minkowski difference A - B of two convex hulls nearest the origin,
// by Gilbert, Johnson and Keerthi's iteration (van den Bergen, Collision Detection in Interactive
// 3D Environments, 4.3; Ericson, Real-Time Collision Detection, 9.5). Its length is the hulls'
// distance, and minus its direction the axis from A towards B.
//
// The collision module asks it only for an axis to try, and proves every gap it reports by a scan
// of all hull vertices, so a rounding slip here costs time, never truth. It differs from FCL's GJK
// in what it is for: it starts from the pair's last answer, and finds each support point by one
// vectorised pass over the hull's vertex matrix, with no allocation.

#include <optional>

#include "geometry/convex_hull.hpp"
#include "graspkit/math/transform.hpp"

namespace graspkit::geometry {

// The nearest point of A - B to the origin, in A's frame, B placed in that frame by `b_in_a`;
// `start` is where to begin (any nonzero vector; the last answer for a pair in a nearby placement
// needs few iterations). None when the hulls overlap or touch, or the iteration stalls.
std::optional<Vector3> nearestDifference(const ConvexHull& a, const ConvexHull& b,
                                         const Transform& b_in_a, const Vector3& start);

}  // namespace graspkit::geometry
