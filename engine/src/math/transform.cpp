#include "graspkit/math/transform.hpp"

#include <algorithm>
#include <cmath>

namespace graspkit {

Transform makeTransform(const Vector3& translation, const Quaternion& rotation) {
  Transform t = Transform::Identity();
  t.linear() = rotation.normalized().toRotationMatrix();
  t.translation() = translation;
  return t;
}

const char* translationProblem(const Vector3& translation) {
  if (!translation.allFinite()) return "is not finite";
  if (translation.cwiseAbs().maxCoeff() > kMaxCoordinate) return "lies past 1e9 mm";
  return nullptr;
}

std::optional<Quaternion> unitQuaternion(double w, double x, double y, double z) {
  const double largest = std::max({std::abs(w), std::abs(x), std::abs(y), std::abs(z)});
  if (!(largest > 0.0) || !std::isfinite(largest)) return std::nullopt;
  return Quaternion(w / largest, x / largest, y / largest, z / largest).normalized();
}

Transform denavitHartenberg(double theta, double d, double a, double alpha) {
  // Written out rather than composed, so the product is exact for the common 0/90 degree cases.
  const double ct = std::cos(theta), st = std::sin(theta);
  const double ca = std::cos(alpha), sa = std::sin(alpha);
  Transform t = Transform::Identity();
  t.linear() << ct, -st * ca, st * sa,  //
      st, ct * ca, -ct * sa,            //
      0, sa, ca;
  t.translation() << a * ct, a * st, d;
  return t;
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
