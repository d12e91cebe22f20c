// Procedural objects against closed forms: each kind is a closed, outward-facing surface of the
// drawn size; a box's volume is the product of its sides, a 32-facet cylinder's the prism's
// (n/2) r^2 sin(2 pi/n) L, a superquadric's vertices lie on its implicit surface, a convex hull
// holds every point it was built from and is convex; object i of a seed never changes.

#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <string>

#include "graspkit/base/error.hpp"
#include "graspkit/geometry/mass_properties.hpp"
#include "graspkit/model/object_generator.hpp"

namespace graspkit {
namespace {

Eigen::AlignedBox3d boundsOf(const TriangleMesh& mesh) {
  Eigen::AlignedBox3d box;
  for (const Vector3& v : mesh.vertices) box.extend(v);
  return box;
}

ObjectGeneratorOptions only(ObjectKind kind) {
  ObjectGeneratorOptions options;
  options.seed = 5;
  options.kinds = {kind};
  return options;
}

TEST(ObjectGenerator, EveryObjectIsClosedOutwardAndSizedForAHand) {
  ObjectGeneratorOptions options;
  options.seed = 9;
  std::set<ObjectKind> kinds;
  for (std::size_t i = 0; i < 60; ++i) {
    const GeneratedObject object = generateObject(options, i);
    SCOPED_TRACE(object.name);
    kinds.insert(object.kind);
    EXPECT_TRUE(isClosed(object.mesh));
    const MassProperties mass = computeMassProperties(object.mesh);
    ASSERT_TRUE(mass.valid);
    EXPECT_GT(mass.volume, 0.0);  // outward: an inside-out surface has a negative volume
    EXPECT_NEAR(object.mass, options.density * mass.volume, 1e-9 * object.mass);
    const Eigen::AlignedBox3d box = boundsOf(object.mesh);
    EXPECT_LT(box.center().norm(), 1e-9);  // centred on its box
    const Vector3 sizes = box.sizes();
    EXPECT_GE(sizes.maxCoeff(), options.minSize - 1e-9);
    EXPECT_LE(sizes.maxCoeff(), options.maxSize + 1e-9);
    EXPECT_GE(sizes.minCoeff(), std::min(sizes.maxCoeff() / 3.0, options.minSize / 2.0) - 1e-6);
  }
  EXPECT_EQ(kinds.size(), 5u);
}

TEST(ObjectGenerator, ABoxHasTheVolumeOfItsSides) {
  for (std::size_t i = 0; i < 5; ++i) {
    const GeneratedObject box = generateObject(only(ObjectKind::Box), i);
    const Vector3 sizes = boundsOf(box.mesh).sizes();
    EXPECT_NEAR(computeMassProperties(box.mesh).volume, sizes.prod(), 1e-9 * sizes.prod());
  }
}

TEST(ObjectGenerator, ACylinderIsAThirtyTwoSidedPrism) {
  for (std::size_t i = 0; i < 5; ++i) {
    const GeneratedObject cylinder = generateObject(only(ObjectKind::Cylinder), i);
    const Vector3 sizes = boundsOf(cylinder.mesh).sizes();
    const double r = 0.5 * sizes.x(), length = sizes.z();  // corners at angle 0 and pi on x
    const double prism = 16.0 * r * r * std::sin(2.0 * M_PI / 32.0) * length;
    EXPECT_NEAR(computeMassProperties(cylinder.mesh).volume, prism, 1e-9 * prism);
  }
}

TEST(ObjectGenerator, SuperquadricVerticesLieOnItsSurface) {
  for (std::size_t i = 0; i < 5; ++i) {
    const GeneratedObject object = generateObject(only(ObjectKind::Superquadric), i);
    // The exponents are in the listing text: "exponents E1 E2".
    const std::size_t at = object.shape.find("exponents ");
    ASSERT_NE(at, std::string::npos);
    const Vector3 a = 0.5 * boundsOf(object.mesh).sizes();
    double e1 = 0, e2 = 0;
    ASSERT_EQ(std::sscanf(object.shape.c_str() + at, "exponents %lf %lf", &e1, &e2), 2);
    // The listing rounds the exponents to 0.01, so the implicit function is only near 1.
    for (const Vector3& v : object.mesh.vertices) {
      const double xy = std::pow(
          std::pow(std::abs(v.x() / a.x()), 2.0 / e2) + std::pow(std::abs(v.y() / a.y()), 2.0 / e2),
          e2 / e1);
      const double f = xy + std::pow(std::abs(v.z() / a.z()), 2.0 / e1);
      EXPECT_NEAR(f, 1.0, 0.05);
    }
  }
}

TEST(ObjectGenerator, AConvexHullIsConvex) {
  for (std::size_t i = 0; i < 10; ++i) {
    const GeneratedObject object = generateObject(only(ObjectKind::ConvexHull), i);
    const TriangleMesh& mesh = object.mesh;
    for (const auto& t : mesh.triangles) {
      const Vector3& p = mesh.vertices[t[0]];
      const Vector3 n = (mesh.vertices[t[1]] - p).cross(mesh.vertices[t[2]] - p).normalized();
      for (const Vector3& v : mesh.vertices) EXPECT_LE(n.dot(v - p), 1e-9);  // all behind it
    }
  }
}

TEST(ObjectGenerator, ObjectIOfASeedNeverChanges) {
  ObjectGeneratorOptions options;
  options.seed = 21;
  const GeneratedObject first = generateObject(options, 7);
  const GeneratedObject again = generateObject(options, 7);
  EXPECT_EQ(first.mesh.vertices, again.mesh.vertices);
  EXPECT_EQ(first.name, "object_0007_sphere");  // kinds in turn: 7 % 5 = 2, the third
  options.seed = 22;
  EXPECT_NE(generateObject(options, 7).mesh.vertices, first.mesh.vertices);
}

TEST(ObjectGenerator, BadOptionsAreRefused) {
  ObjectGeneratorOptions options;
  options.minSize = 50;
  options.maxSize = 40;
  EXPECT_THROW(generateObject(options, 0), Error);
  options = {};
  options.density = 0;
  EXPECT_THROW(generateObject(options, 0), Error);
  options = {};
  options.kinds.clear();
  EXPECT_THROW(generateObject(options, 0), Error);
}

}  // namespace
}  // namespace graspkit
