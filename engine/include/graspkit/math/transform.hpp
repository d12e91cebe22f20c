#pragma once
// Rigid transforms. Column-vector convention as in GraspIt!: p_parent = R * p_child + t.
// Lengths in mm, angles in radians.

#include <optional>

#include <Eigen/Geometry>

namespace graspkit {

using Transform = Eigen::Isometry3d;
using Vector3 = Eigen::Vector3d;
using Matrix3 = Eigen::Matrix3d;
using Quaternion = Eigen::Quaterniond;

// A transform from a translation (mm) and a w-first unit quaternion.
Transform makeTransform(const Vector3& translation, const Quaternion& rotation);

// The unit quaternion of (w, x, y, z), scaled by its largest component before it is normalised
// so that (1e300, 1e300, 0, 0) and (1e-300, 0, 0, 0) still name their rotations; nullopt for a
// zero or non-finite quaternion, which names none. Every front end reads quaternions through it.
std::optional<Quaternion> unitQuaternion(double w, double x, double y, double z);

// The largest coordinate a pose may hold, mm (a thousand kilometres): past it, float geometry
// (Embree) and squared distances lose all precision. Model geometry has the same bound.
inline constexpr double kMaxCoordinate = 1e9;

// Why `translation` cannot be a pose's ("is not finite", "lies past 1e9 mm"), or nullptr when
// it can. Every front end checks poses' translations through it, as quaternions through
// unitQuaternion.
const char* translationProblem(const Vector3& translation);

// Standard Denavit-Hartenberg frame: T = Rz(theta) * Tz(d) * Tx(a) * Rx(alpha).
Transform denavitHartenberg(double theta, double d, double a, double alpha);

inline double degreesToRadians(double degrees) {
  return degrees * (M_PI / 180.0);
}
inline double radiansToDegrees(double radians) {
  return radians * (180.0 / M_PI);
}

// GraspIt!'s contact frame around a unit normal (columns x, y, z = normal).
Matrix3 contactFrame(const Vector3& normal);

}  // namespace graspkit
