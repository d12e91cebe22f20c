#include "graspkit/model/material.hpp"

#include <algorithm>

namespace graspkit {
namespace {

using Table = std::array<std::array<double, kMaterialCount>, kMaterialCount>;

// GraspIt!'s World::setDefaults tables (upper triangle; the tables are symmetric and
// frictionless gives 0 with everything). Index order: frictionless, glass, metal, plastic,
// wood, rubber, stone.
constexpr Table symmetric(const Table& upper) {
  Table full = upper;
  for (std::size_t i = 0; i < kMaterialCount; ++i)
    for (std::size_t j = 0; j < i; ++j) full[i][j] = upper[j][i];
  return full;
}

constexpr Table kStatic = symmetric({{
    {0, 0, 0, 0, 0, 0, 0},
    {0, 0.2, 0.2, 0.2, 0.3, 1.0, 0.3},
    {0, 0, 0.2, 0.2, 0.3, 1.0, 0.4},
    {0, 0, 0, 0.3, 0.4, 1.0, 0.4},
    {0, 0, 0, 0, 0.4, 1.0, 0.6},
    {0, 0, 0, 0, 0, 2.0, 1.5},
    {0, 0, 0, 0, 0, 0, 0.7},
}});

constexpr Table kKinetic = symmetric({{
    {0, 0, 0, 0, 0, 0, 0},
    {0, 0.1, 0.1, 0.1, 0.2, 0.9, 0.2},
    {0, 0, 0.1, 0.1, 0.2, 0.9, 0.3},
    {0, 0, 0, 0.2, 0.3, 0.9, 0.3},
    {0, 0, 0, 0, 0.3, 0.9, 0.5},
    {0, 0, 0, 0, 0, 1.9, 1.4},
    {0, 0, 0, 0, 0, 0, 0.6},
}});

std::size_t index(Material m) {
  return static_cast<std::size_t>(m);
}

}  // namespace

std::span<const EnumName<Material>> enumNames(std::type_identity<Material>) {
  static constexpr EnumName<Material> kNames[] = {{Material::Frictionless, "frictionless"},
                                                  {Material::Glass, "glass"},
                                                  {Material::Metal, "metal"},
                                                  {Material::Plastic, "plastic"},
                                                  {Material::Wood, "wood"},
                                                  {Material::Rubber, "rubber"},
                                                  {Material::Stone, "stone"}};
  return kNames;
}

double staticFriction(Material a, Material b) {
  return kStatic[index(a)][index(b)];
}
double kineticFriction(Material a, Material b) {
  return kKinetic[index(a)][index(b)];
}

double frictionCoefficient(Material a, Material b, bool dynamic, double relative_speed) {
  return (dynamic && relative_speed > kKineticSpeedThreshold) ? kineticFriction(a, b)
                                                              : staticFriction(a, b);
}

Colour materialColour(Material material) {
  switch (material) {
    case Material::Frictionless:
      return {0.85f, 0.85f, 0.9f};
    case Material::Glass:
      return {0.6f, 0.8f, 0.9f};
    case Material::Metal:
      return {0.62f, 0.64f, 0.68f};
    case Material::Plastic:
      return {0.9f, 0.7f, 0.35f};
    case Material::Wood:
      return {0.7f, 0.5f, 0.3f};
    case Material::Rubber:
      return {0.25f, 0.25f, 0.28f};
    case Material::Stone:
      return {0.55f, 0.55f, 0.5f};
  }
  return {};
}

}  // namespace graspkit
