#include "graspkit/transform.hpp"

namespace graspkit {

Transform makeTransform(const Vector3& translation, const Quaternion& rotation) {
  Transform t = Transform::Identity();
  t.linear() = rotation.normalized().toRotationMatrix();
  t.translation() = translation;
  return t;
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

}  // namespace graspkit
