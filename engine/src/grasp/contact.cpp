#include "graspkit/contact.hpp"

#include <cmath>

namespace graspkit {

Contact Contact::mate() const {
  Contact m = *this;
  m.body1 = body2;
  m.body2 = body1;
  m.position1 = position2;
  m.position2 = position1;
  m.normal = -normal;
  m.frame = contactFrame(m.normal);
  return m;
}

const char* contactModelName(ContactModel model) {
  switch (model) {
    case ContactModel::Frictionless:
      return "frictionless";
    case ContactModel::PointWithFriction:
      return "point";
    case ContactModel::SoftFinger:
      return "soft_finger";
  }
  return "unknown";
}

Matrix3 contactFrame(const Vector3& normal) {
  // GraspIt! takes the tangent x = n x X, unless n is within 1e-9 (its MACHINE_ZERO) of +-X in
  // cosine, where n x X vanishes; then x = n x Z, which is well defined there.
  const Vector3 n = normal.normalized();
  const Vector3 x = std::abs(n.x()) > 1.0 - 1e-9 ? n.cross(Vector3::UnitZ()).normalized()
                                                 : n.cross(Vector3::UnitX()).normalized();
  Matrix3 frame;
  frame.col(0) = x;
  frame.col(1) = n.cross(x).normalized();
  frame.col(2) = n;
  return frame;
}

}  // namespace graspkit
