#pragma once
// Surface materials and GraspIt!'s friction table (World::setDefaults). The static coefficient
// applies at rest; the kinetic one when either body is dynamic and the contact slides faster
// than kKineticSpeedThreshold.

#include <array>
#include <optional>
#include <string_view>

namespace graspkit {

// Order matters: it is GraspIt!'s internal index order, used by the friction tables.
enum class Material { Frictionless, Glass, Metal, Plastic, Wood, Rubber, Stone };

inline constexpr std::size_t kMaterialCount = 7;
inline constexpr double kKineticSpeedThreshold = 1.0;  // mm/s

std::string_view materialName(Material material);
std::optional<Material> materialFromName(std::string_view name);  // exact, lower-case names

double staticFriction(Material a, Material b);
double kineticFriction(Material a, Material b);

// The coefficient for a contact sliding at `relative_speed` (mm/s); `dynamic` says whether
// either body takes part in dynamics.
double frictionCoefficient(Material a, Material b, bool dynamic, double relative_speed);

}  // namespace graspkit
