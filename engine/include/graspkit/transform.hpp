#pragma once
// Rigid transforms. Column-vector convention as in GraspIt!: p_parent = R * p_child + t.
// Lengths in mm, angles in radians.

#include <Eigen/Geometry>

namespace graspkit {

using Transform = Eigen::Isometry3d;
using Vector3 = Eigen::Vector3d;
using Matrix3 = Eigen::Matrix3d;
using Quaternion = Eigen::Quaterniond;

// A transform from a translation (mm) and a w-first unit quaternion.
Transform makeTransform(const Vector3& translation, const Quaternion& rotation);

// Standard Denavit-Hartenberg frame: T = Rz(theta) * Tz(d) * Tx(a) * Rx(alpha).
Transform denavitHartenberg(double theta, double d, double a, double alpha);

inline double degreesToRadians(double degrees) {
  return degrees * (M_PI / 180.0);
}
inline double radiansToDegrees(double radians) {
  return radians * (180.0 / M_PI);
}

}  // namespace graspkit
