#pragma once
// Surface materials and GraspIt!'s friction table (World::setDefaults). The static coefficient
// applies at rest; the kinetic one when either body is dynamic and the contact slides faster
// than kKineticSpeedThreshold.

#include <array>
#include <optional>
#include <string_view>

#include "graspkit/base/enum_names.hpp"
#include "graspkit/geometry/mesh.hpp"

namespace graspkit {

// Order matters: it is GraspIt!'s internal index order, used by the friction tables.
enum class Material { Frictionless, Glass, Metal, Plastic, Wood, Rubber, Stone };

inline constexpr std::size_t kMaterialCount = 7;
inline constexpr double kKineticSpeedThreshold = 1.0;  // mm/s

// Lower-case names: frictionless, glass, metal, plastic, wood, rubber, stone (base/enum_names.hpp:
// nameOf, valueNamed, parseNamed).
std::span<const EnumName<Material>> enumNames(std::type_identity<Material>);

double staticFriction(Material a, Material b);
double kineticFriction(Material a, Material b);

// The coefficient for a contact sliding at `relative_speed` (mm/s); `dynamic` says whether
// either body takes part in dynamics.
double frictionCoefficient(Material a, Material b, bool dynamic, double relative_speed);

// Surface colours a body gets when its file gives none, by material (glass, metal, ...): the
// renderer and the glTF export show the same.
Colour materialColour(Material material);

}  // namespace graspkit
