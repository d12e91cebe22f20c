#include "graspkit/model/object_generator.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "geometry/convex_hull.hpp"
#include "geometry/primitive_meshes.hpp"
#include "graspkit/base/error.hpp"
#include "graspkit/geometry/mass_properties.hpp"

namespace graspkit {
namespace {

// SplitMix64: a fixed, portable stream (std::uniform_real_distribution differs between standard
// libraries, and a dataset must be the same wherever it is generated).
class Random {
 public:
  explicit Random(std::uint64_t state) : state_(state) {}
  std::uint64_t next() {
    std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  double uniform(double low, double high) {
    return low + (high - low) * static_cast<double>(next() >> 11) * 0x1.0p-53;
  }

 private:
  std::uint64_t state_;
};

// The three extents: the largest first, the others between a third of it (and half the
// smallest size) and it.
Vector3 drawExtents(Random& random, const ObjectGeneratorOptions& options) {
  const double largest = random.uniform(options.minSize, options.maxSize);
  const double low = std::min(largest, std::max(largest / 3.0, options.minSize / 2.0));
  return {largest, random.uniform(low, largest), random.uniform(low, largest)};
}

// sign(x) |x|^e, the superquadric's signed power.
double signedPower(double x, double e) {
  return std::copysign(std::pow(std::abs(x), e), x);
}

// The unit sphere's mesh moved onto the superquadric with semi-axes `a` and exponents e1
// (latitude) and e2 (longitude): each vertex keeps its latitude and longitude. The equator and
// the meridian at longitude 0 are vertex rings, so the extents are exactly 2a.
TriangleMesh superquadricMesh(const Vector3& a, double e1, double e2) {
  TriangleMesh mesh = geometry::sphereMesh(1.0, 24, 48);
  for (Vector3& v : mesh.vertices) {
    const double latitude = std::asin(std::clamp(v.z(), -1.0, 1.0));
    const double longitude = std::atan2(v.y(), v.x());
    const double ring = signedPower(std::cos(latitude), e1);
    v = Vector3(a.x() * ring * signedPower(std::cos(longitude), e2),
                a.y() * ring * signedPower(std::sin(longitude), e2),
                a.z() * signedPower(std::sin(latitude), e1));
  }
  return mesh;
}

// Points on random rays of the ellipsoid with semi-axes `a`, between 0.6 and 1 of the way out;
// their hull, stretched so that its extents are exactly 2a.
TriangleMesh convexHullMesh(Random& random, const Vector3& a) {
  for (;;) {
    std::vector<Vector3> points;
    for (int k = 0; k < 24; ++k) {
      const double z = random.uniform(-1.0, 1.0), angle = random.uniform(0.0, 2.0 * M_PI);
      const double r = std::sqrt(1.0 - z * z), out = random.uniform(0.6, 1.0);
      points.emplace_back(out * a.x() * r * std::cos(angle), out * a.y() * r * std::sin(angle),
                          out * a.z() * z);
    }
    std::optional<TriangleMesh> mesh = geometry::convexHullMesh(points);
    if (!mesh) continue;  // flat or degenerate draws: draw again (the stream stays fixed)
    Eigen::AlignedBox3d box;
    for (const Vector3& v : mesh->vertices) box.extend(v);
    const Vector3 stretch = (2.0 * a).cwiseQuotient(box.sizes());
    for (Vector3& v : mesh->vertices) v = (v - box.center()).cwiseProduct(stretch);
    return *mesh;
  }
}

void centreOnBox(TriangleMesh& mesh) {
  Eigen::AlignedBox3d box;
  for (const Vector3& v : mesh.vertices) box.extend(v);
  const Vector3 centre = box.center();
  for (Vector3& v : mesh.vertices) v -= centre;
}

void checkOptions(const ObjectGeneratorOptions& options) {
  if (!(options.minSize > 0.0) || !(options.maxSize >= options.minSize) ||
      !std::isfinite(options.maxSize))
    throw Error(fmt::format("object sizes must satisfy 0 < min <= max, found {} and {} mm",
                            options.minSize, options.maxSize));
  if (!(options.density > 0.0) || !std::isfinite(options.density))
    throw Error(
        fmt::format("the density must be a positive number, found {} g/mm^3", options.density));
  if (options.kinds.empty()) throw Error("no object kinds to generate");
}

}  // namespace

std::span<const EnumName<ObjectKind>> enumNames(std::type_identity<ObjectKind>) {
  static constexpr EnumName<ObjectKind> kNames[] = {{ObjectKind::Box, "box"},
                                                    {ObjectKind::Cylinder, "cylinder"},
                                                    {ObjectKind::Sphere, "sphere"},
                                                    {ObjectKind::Superquadric, "superquadric"},
                                                    {ObjectKind::ConvexHull, "convex_hull"}};
  return kNames;
}

GeneratedObject generateObject(const ObjectGeneratorOptions& options, std::size_t index) {
  checkOptions(options);
  // Each object has its own stream, so object i does not depend on the objects before it.
  Random random(options.seed * 0xD1B54A32D192ED03ull + index);
  random.next();
  GeneratedObject object;
  object.kind = options.kinds[index % options.kinds.size()];
  object.name = fmt::format("object_{:04d}_{}", index, nameOf(object.kind));
  const Vector3 extents = drawExtents(random, options);
  switch (object.kind) {
    case ObjectKind::Box:
      object.mesh = geometry::boxMesh(extents);
      object.shape =
          fmt::format("box {:.1f} x {:.1f} x {:.1f} mm", extents.x(), extents.y(), extents.z());
      break;
    case ObjectKind::Cylinder: {
      // Long or squat at random: the largest extent is the length or the diameter.
      const bool long_one = random.uniform(0.0, 1.0) < 0.5;
      const double length = long_one ? extents.x() : extents.y();
      const double diameter = long_one ? extents.y() : extents.x();
      object.mesh = geometry::cylinderMesh(0.5 * diameter, length, 32);
      object.shape = fmt::format("cylinder diameter {:.1f} mm, length {:.1f} mm", diameter, length);
      break;
    }
    case ObjectKind::Sphere:
      object.mesh = geometry::sphereMesh(0.5 * extents.x(), 16, 32);
      object.shape = fmt::format("sphere diameter {:.1f} mm", extents.x());
      break;
    case ObjectKind::Superquadric: {
      const double e1 = random.uniform(0.3, 1.4), e2 = random.uniform(0.3, 1.4);
      object.mesh = superquadricMesh(0.5 * extents, e1, e2);
      object.shape =
          fmt::format("superquadric {:.1f} x {:.1f} x {:.1f} mm, exponents {:.2f} {:.2f}",
                      extents.x(), extents.y(), extents.z(), e1, e2);
      break;
    }
    case ObjectKind::ConvexHull:
      object.mesh = convexHullMesh(random, 0.5 * extents);
      object.shape = fmt::format("convex hull of 24 points, {:.1f} x {:.1f} x {:.1f} mm",
                                 extents.x(), extents.y(), extents.z());
      break;
  }
  centreOnBox(object.mesh);
  object.mass = options.density * computeMassProperties(object.mesh).volume;
  return object;
}

}  // namespace graspkit
