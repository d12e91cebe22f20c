#pragma once
// Procedural objects for grasp datasets, tests and benches: boxes, cylinders, spheres,
// superquadrics and random convex hulls, sized for a hand to hold, each a closed triangle mesh
// centred on its bounding box. Object i of a seed is the same whatever the count asked for, so
// a larger set extends a smaller one.

#include <cstdint>
#include <string>
#include <vector>

#include "graspkit/base/enum_names.hpp"
#include "graspkit/geometry/mesh.hpp"
#include "graspkit/model/material.hpp"

namespace graspkit {

enum class ObjectKind { Box, Cylinder, Sphere, Superquadric, ConvexHull };

// box, cylinder, sphere, superquadric, convex_hull (base/enum_names.hpp: nameOf, valueNamed,
// parseNamed).
std::span<const EnumName<ObjectKind>> enumNames(std::type_identity<ObjectKind>);

struct ObjectGeneratorOptions {
  std::uint64_t seed = 1;
  // Each object's largest extent, mm, is drawn from [minSize, maxSize]; its other extents are at
  // least a third of that (and at least minSize / 2), so nothing is a needle or a sheet.
  double minSize = 40.0;
  double maxSize = 120.0;
  double density = 0.5e-3;  // g/mm^3 (0.5 g/cm^3, a light plastic or wooden part)
  Material material = Material::Plastic;
  // The kinds drawn from, in turn by index (object i is kinds[i % kinds.size()]).
  std::vector<ObjectKind> kinds = {ObjectKind::Box, ObjectKind::Cylinder, ObjectKind::Sphere,
                                   ObjectKind::Superquadric, ObjectKind::ConvexHull};
};

struct GeneratedObject {
  std::string name;  // object_<index>_<kind>, e.g. object_0007_cylinder
  ObjectKind kind = ObjectKind::Box;
  TriangleMesh mesh;  // closed, counter-clockwise seen from outside, mm
  double mass = 0.0;  // g: the mesh's volume times the density
  std::string shape;  // the drawn parameters, for people reading a listing
};

// Object `index` of the set `options` describes. Throws graspkit::Error for sizes that are not
// 0 < minSize <= maxSize, a density that is not positive, or no kinds.
GeneratedObject generateObject(const ObjectGeneratorOptions& options, std::size_t index);

}  // namespace graspkit
