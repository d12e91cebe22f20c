#pragma once
// graspkit's units, and the SI units in them. Everything in memory is mm, g, s and radians (as
// GraspIt! keeps it); readers of SI formats (URDF, MJCF, glTF, STL) multiply by these once, where
// they read, and writers divide by them where they write.

#include <numbers>

namespace graspkit::units {

inline constexpr double kMetre = 1000.0;                     // mm
inline constexpr double kKilogram = 1000.0;                  // g
inline constexpr double kNewton = 1.0e6;                     // g mm / s^2
inline constexpr double kNewtonMetre = 1.0e9;                // g mm^2 / s^2
inline constexpr double kDegree = std::numbers::pi / 180.0;  // rad

}  // namespace graspkit::units
