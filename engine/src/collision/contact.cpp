#include "graspkit/contact.hpp"

#include <cmath>

namespace graspkit {

Contact Contact::mate() const {
  Contact m = *this;
  std::swap(m.body1, m.body2);
  std::swap(m.position1, m.position2);
  m.normal = -normal;
  m.frame = contactFrame(m.normal);
  return m;
}

Matrix3 contactFrame(const Vector3& normal) {
  // x = n x X, unless n is (nearly) along X; then n x Z. y completes a right-handed frame.
  Vector3 x = normal.cross(Vector3::UnitX());
  if (x.squaredNorm() < 1e-12) x = normal.cross(Vector3::UnitZ());
  x.normalize();
  Matrix3 frame;
  frame.col(0) = x;
  frame.col(1) = normal.cross(x);
  frame.col(2) = normal;
  return frame;
}

}  // namespace graspkit
