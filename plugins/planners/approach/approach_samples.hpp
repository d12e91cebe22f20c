#pragma once
// Where the approach planner brings the hand in from: directions spread evenly over a sphere
// (the Fibonacci lattice) and roll angles about each direction.

#include <cmath>
#include <numbers>
#include <vector>

#include "graspkit/math/transform.hpp"

namespace graspkit::approach {

// `count` unit vectors nearly evenly spread over the sphere: point i sits at height
// z = 1 - (2i + 1)/count and turns by the golden angle from point i - 1, so every point covers
// about the same area.
inline std::vector<Vector3> fibonacciSphere(int count) {
  const double goldenAngle = std::numbers::pi * (3.0 - std::sqrt(5.0));
  std::vector<Vector3> points;
  points.reserve(static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i) {
    const double z = 1.0 - (2.0 * i + 1.0) / count;
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    const double turn = goldenAngle * i;
    points.emplace_back(r * std::cos(turn), r * std::sin(turn), z);
  }
  return points;
}

// A frame whose z axis is `approach` (unit) and whose x axis is `reference` made perpendicular
// to it (or `fallback`, when `reference` is nearly parallel), turned by `roll` about z.
inline Matrix3 approachRotation(const Vector3& approach, const Vector3& reference,
                                const Vector3& fallback, double roll) {
  const Vector3 seed = std::abs(reference.dot(approach)) < 0.9 ? reference : fallback;
  const Vector3 x0 = (seed - seed.dot(approach) * approach).normalized();
  const Vector3 y0 = approach.cross(x0);
  const Vector3 x = std::cos(roll) * x0 + std::sin(roll) * y0;
  Matrix3 rotation;
  rotation.col(0) = x;
  rotation.col(1) = approach.cross(x);
  rotation.col(2) = approach;
  return rotation;
}

}  // namespace graspkit::approach
