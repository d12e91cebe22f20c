#include "graspkit/material.hpp"

#include <algorithm>

namespace graspkit {
namespace {

constexpr std::array<std::string_view, kMaterialCount> kNames = {
    "frictionless", "glass", "metal", "plastic", "wood", "rubber", "stone"};

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

std::string_view materialName(Material material) {
  return kNames[index(material)];
}

std::optional<Material> materialFromName(std::string_view name) {
  auto it = std::find(kNames.begin(), kNames.end(), name);
  if (it == kNames.end()) return std::nullopt;
  return static_cast<Material>(it - kNames.begin());
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

}  // namespace graspkit
