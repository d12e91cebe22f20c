#pragma once
// Internal: what an object's bounding ball and box say of a virtual contact's contact-energy
// sample (its distance to the object's surface, and the cosine between its normal and the
// direction to the nearest surface point) before any nearest-point query. The contact energy
// stops its sum once the terms found and the least the others can be exceed the search's
// rejection bound, and the potential-quality energy passes over contacts whose bound already
// puts them out of its range.

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include "graspkit/geometry/mesh.hpp"
#include "graspkit/math/transform.hpp"

namespace graspkit::planning {

// An object placed in the world, seen from outside: the box of its vertices (body frame) and
// the ball around that box's centre holding every vertex (world).
struct ObjectBounds {
  Eigen::AlignedBox3d box;
  Transform inverse = Transform::Identity();  // world to body
  Vector3 ballCentre = Vector3::Zero();       // world, mm
  double ballRadius = -1.0;                   // negative: no triangles, nothing bounded
};

inline ObjectBounds objectBounds(const TriangleMesh& mesh, const Transform& pose) {
  ObjectBounds bounds;
  if (mesh.triangles.empty()) return bounds;  // no surface: every sample is 0 (nothing to reach)
  for (const Vector3& v : mesh.vertices) bounds.box.extend(v);
  double radius = 0.0;
  for (const Vector3& v : mesh.vertices)
    radius = std::max(radius, (v - bounds.box.center()).norm());
  bounds.inverse = pose.inverse();
  bounds.ballCentre = pose * bounds.box.center();
  bounds.ballRadius = radius;
  return bounds;
}

// A sample's distance is at least `distance` and its cosine at most `cosine`.
struct SampleBound {
  double distance = 0.0;
  double cosine = 1.0;
};

// Every surface point q lies in the box and in the ball (centre c, radius r). So |q - p| is at
// least p's distance to the box and |c - p| - r, and the direction from p to q lies in the cone
// of half-angle asin(r / |c - p|) around the direction to c, whose cosine with the unit normal n
// is at most cos(max(0, angle(n, c - p) - half-angle)). Both are loosened by far more than
// their rounding (1e-9 relative), so a bound never cuts off a true sample; a point within the
// ball gets none.
inline SampleBound sampleBound(const ObjectBounds& object, const Vector3& point,
                               const Vector3& normal) {
  const Vector3 toCentre = object.ballCentre - point;
  const double gap = toCentre.norm();
  if (!(object.ballRadius >= 0.0) || !(gap > object.ballRadius * (1.0 + 1e-6) + 1e-6)) return {};
  const Vector3 outside =
      ((object.inverse * point - object.box.center()).cwiseAbs() - 0.5 * object.box.sizes())
          .cwiseMax(0.0);
  SampleBound bound;
  bound.distance =
      std::max(0.0, std::max(gap - object.ballRadius, outside.norm()) * (1.0 - 1e-9) - 1e-9);
  const double sinHalf = object.ballRadius / gap;
  const double cosHalf = std::sqrt(1.0 - sinHalf * sinHalf);
  const double cosAngle = std::clamp(normal.dot(toCentre) / gap, -1.0, 1.0);
  if (cosAngle < cosHalf) {
    const double sinAngle = std::sqrt(1.0 - cosAngle * cosAngle);
    bound.cosine = std::min(1.0, cosAngle * cosHalf + sinAngle * sinHalf + 1e-9);
  }
  return bound;
}

}  // namespace graspkit::planning
