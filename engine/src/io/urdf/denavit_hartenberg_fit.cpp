#include "io/urdf/denavit_hartenberg_fit.hpp"

#include <cmath>

namespace graspkit::io {

namespace {

// Lines closer to parallel than this (1 - cos) share no common normal.
constexpr double kParallel = 1e-12;
constexpr double kSamePoint = 1e-9;  // mm

}  // namespace

Matrix3 frameWithZ(const Vector3& z, const Vector3& hint) {
  Vector3 x = hint - hint.dot(z) * z;
  if (x.norm() < 1e-6) {
    x = Vector3::UnitY() - z.y() * z;
    if (x.norm() < 1e-6) x = Vector3::UnitX() - z.x() * z;
  }
  x.normalize();
  Matrix3 frame;
  frame.col(0) = x;
  frame.col(1) = z.cross(x);
  frame.col(2) = z;
  return frame;
}

void denavitHartenbergTo(const Transform& before, const Vector3& p, const Vector3& u, Joint& joint,
                         Transform& after) {
  const Vector3 o = before.translation();
  const Vector3 z = before.linear().col(2);
  const Vector3 x_before = before.linear().col(0);
  const Vector3 w = o - p;
  const double b = z.dot(u);
  const double denom = 1.0 - b * b;
  Vector3 c1, c2, x;
  if (denom > kParallel) {
    const double s = (b * u.dot(w) - z.dot(w)) / denom;
    const double t = (u.dot(w) - b * z.dot(w)) / denom;
    c1 = o + s * z;
    c2 = p + t * u;
    x = (c2 - c1).norm() > kSamePoint ? Vector3((c2 - c1).normalized())
                                      : Vector3(z.cross(u).normalized());
  } else {
    c1 = o;
    c2 = p + u.dot(o - p) * u;
    x = (c2 - c1).norm() > kSamePoint ? Vector3((c2 - c1).normalized()) : x_before;
  }
  joint.theta = std::atan2(x_before.cross(x).dot(z), x_before.dot(x));
  joint.d = (c1 - o).dot(z);
  joint.a = (c2 - c1).dot(x);
  joint.alpha = std::atan2(z.cross(u).dot(x), z.dot(u));
  after = before * joint.transform(0.0);
}

}  // namespace graspkit::io
