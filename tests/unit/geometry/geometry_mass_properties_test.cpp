// Mass properties against closed forms: boxes, regular prisms and their limit the cylinder,
// a tessellated sphere bounded by its inscribed and circumscribed balls, and the failure cases
// (open, flat, inside-out, tiny, far away) that must come back invalid and free of NaN.

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <utility>

#include "graspkit/geometry/mass_properties.hpp"
#include "graspkit/geometry/mesh.hpp"

namespace graspkit {
namespace {

using Triangle = std::array<std::uint32_t, 3>;

// An axis-aligned box centred on the origin, sides a (x), b (y), c (z), wound outward.
TriangleMesh makeBox(double a, double b, double c) {
  TriangleMesh box;
  for (int i = 0; i < 8; ++i) {
    box.vertices.emplace_back((i & 1 ? 0.5 : -0.5) * a, (i & 2 ? 0.5 : -0.5) * b,
                              (i & 4 ? 0.5 : -0.5) * c);
  }
  // Vertex i has x from bit 0, y from bit 1, z from bit 2.
  box.triangles = {{0, 2, 3}, {0, 3, 1},   // z-
                   {4, 5, 7}, {4, 7, 6},   // z+
                   {0, 1, 5}, {0, 5, 4},   // y-
                   {2, 6, 7}, {2, 7, 3},   // y+
                   {0, 4, 6}, {0, 6, 2},   // x-
                   {1, 3, 7}, {1, 7, 5}};  // x+
  return box;
}

// A right prism over the regular n-gon with circumradius r, axis z, height h, centred.
TriangleMesh makePrism(int n, double r, double h) {
  TriangleMesh prism;
  for (int i = 0; i < n; ++i) {
    const double angle = 2.0 * M_PI * i / n;
    prism.vertices.emplace_back(r * std::cos(angle), r * std::sin(angle), -h / 2);
    prism.vertices.emplace_back(r * std::cos(angle), r * std::sin(angle), h / 2);
  }
  const auto bottom_centre = static_cast<std::uint32_t>(prism.vertices.size());
  prism.vertices.emplace_back(0, 0, -h / 2);
  prism.vertices.emplace_back(0, 0, h / 2);
  const std::uint32_t top_centre = bottom_centre + 1;
  for (int i = 0; i < n; ++i) {
    const auto b0 = static_cast<std::uint32_t>(2 * i), t0 = b0 + 1;
    const auto b1 = static_cast<std::uint32_t>(2 * ((i + 1) % n)), t1 = b1 + 1;
    prism.triangles.push_back({b0, b1, t1});
    prism.triangles.push_back({b0, t1, t0});
    prism.triangles.push_back({bottom_centre, b1, b0});
    prism.triangles.push_back({top_centre, t0, t1});
  }
  return prism;
}

// An icosahedron subdivided `levels` times with every vertex pushed onto the sphere of radius r.
TriangleMesh makeIcosphere(double r, int levels) {
  const double p = (1.0 + std::sqrt(5.0)) / 2.0;
  TriangleMesh sphere;
  for (const auto& v :
       {Vector3(-1, p, 0), Vector3(1, p, 0), Vector3(-1, -p, 0), Vector3(1, -p, 0),
        Vector3(0, -1, p), Vector3(0, 1, p), Vector3(0, -1, -p), Vector3(0, 1, -p),
        Vector3(p, 0, -1), Vector3(p, 0, 1), Vector3(-p, 0, -1), Vector3(-p, 0, 1)}) {
    sphere.vertices.push_back(r * v.normalized());
  }
  sphere.triangles = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                      {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                      {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                      {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (int level = 0; level < levels; ++level) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> midpoints;
    auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
      const auto key = std::minmax(a, b);
      if (auto it = midpoints.find(key); it != midpoints.end()) return it->second;
      sphere.vertices.push_back(r * (sphere.vertices[a] + sphere.vertices[b]).normalized());
      const auto index = static_cast<std::uint32_t>(sphere.vertices.size() - 1);
      midpoints.emplace(key, index);
      return index;
    };
    std::vector<Triangle> finer;
    for (const Triangle& t : sphere.triangles) {
      const std::uint32_t ab = midpoint(t[0], t[1]), bc = midpoint(t[1], t[2]),
                          ca = midpoint(t[2], t[0]);
      finer.insert(finer.end(), {{t[0], ab, ca}, {t[1], bc, ab}, {t[2], ca, bc}, {ab, bc, ca}});
    }
    sphere.triangles = std::move(finer);
  }
  return sphere;
}

// Distance from the origin to the nearest face plane: the radius of the largest ball centred
// at the origin inside a convex mesh.
double inscribedRadius(const TriangleMesh& mesh) {
  double radius = std::numeric_limits<double>::infinity();
  for (const Triangle& t : mesh.triangles) {
    const Vector3& a = mesh.vertices[t[0]];
    const Vector3 normal = (mesh.vertices[t[1]] - a).cross(mesh.vertices[t[2]] - a).normalized();
    radius = std::min(radius, std::abs(normal.dot(a)));
  }
  return radius;
}

void expectMatrixNear(const Matrix3& actual, const Matrix3& expected, double tolerance) {
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      EXPECT_NEAR(actual(i, j), expected(i, j), tolerance) << "element (" << i << ", " << j << ")";
    }
  }
}

void expectInvalidAndZero(const MassProperties& props) {
  EXPECT_FALSE(props.valid);
  EXPECT_EQ(props.volume, 0.0);
  EXPECT_TRUE(props.centroid.isZero());
  EXPECT_TRUE(props.inertia.isZero());
}

TEST(MassProperties, BoxMatchesClosedForm) {
  const double a = 20, b = 30, c = 50;
  const MassProperties props = computeMassProperties(makeBox(a, b, c));
  ASSERT_TRUE(props.valid);
  EXPECT_NEAR(props.volume, a * b * c, 1e-9);
  EXPECT_NEAR(props.centroid.norm(), 0.0, 1e-12);
  const Matrix3 expected =
      Vector3((b * b + c * c) / 12, (a * a + c * c) / 12, (a * a + b * b) / 12).asDiagonal();
  expectMatrixNear(props.inertia, expected, 1e-9);
}

TEST(MassProperties, UnitCubeInertiaIsOneSixth) {
  const MassProperties props = computeMassProperties(makeBox(1, 1, 1));
  ASSERT_TRUE(props.valid);
  EXPECT_DOUBLE_EQ(props.volume, 1.0);
  expectMatrixNear(props.inertia, Matrix3::Identity() / 6.0, 1e-14);
}

TEST(MassProperties, MovedBoxShiftsCentroidAndRotatesInertia) {
  const double a = 10, b = 40, c = 25;
  const Matrix3 rotation = Eigen::AngleAxisd(0.7, Vector3(1, 2, 3).normalized()).toRotationMatrix();
  const Vector3 translation(120, -45, 80);
  TriangleMesh box = makeBox(a, b, c);
  Eigen::Affine3d pose = Eigen::Affine3d::Identity();
  pose.linear() = rotation;
  pose.translation() = translation;
  transformMesh(box, pose);

  const MassProperties props = computeMassProperties(box);
  ASSERT_TRUE(props.valid);
  EXPECT_NEAR(props.volume, a * b * c, 1e-6);
  EXPECT_NEAR((props.centroid - translation).norm(), 0.0, 1e-9);
  const Matrix3 body =
      Vector3((b * b + c * c) / 12, (a * a + c * c) / 12, (a * a + b * b) / 12).asDiagonal();
  expectMatrixNear(props.inertia, rotation * body * rotation.transpose(), 1e-9);
}

TEST(MassProperties, RegularPrismMatchesPolygonClosedForm) {
  // Per unit area, the polar moment of a regular n-gon is rho^2/2 + s^2/24 (inradius rho,
  // side s): sum over the n isosceles triangles from the centre.
  const int n = 7;
  const double r = 15, h = 40;
  const double rho = r * std::cos(M_PI / n), side = 2 * r * std::sin(M_PI / n);
  const double area = 0.5 * n * r * r * std::sin(2 * M_PI / n);
  const double polar = rho * rho / 2 + side * side / 24;

  const MassProperties props = computeMassProperties(makePrism(n, r, h));
  ASSERT_TRUE(props.valid);
  EXPECT_NEAR(props.volume, area * h, 1e-9 * area * h);
  EXPECT_NEAR(props.centroid.norm(), 0.0, 1e-10);
  // In-plane moments of a regular polygon (n >= 3) are equal: half the polar moment each.
  const Matrix3 expected =
      Vector3(polar / 2 + h * h / 12, polar / 2 + h * h / 12, polar).asDiagonal();
  expectMatrixNear(props.inertia, expected, 1e-9);
}

TEST(MassProperties, FinePrismApproachesCylinder) {
  // With n sides the polygon's area is short of the disc's by (2 pi / n)^2 / 6 relatively, and
  // its moments by about as much: 1e-4 at n = 256.
  const int n = 256;
  const double r = 30, h = 90;
  const double tolerance = std::pow(2 * M_PI / n, 2) / 6 * 1.01;
  const MassProperties props = computeMassProperties(makePrism(n, r, h));
  ASSERT_TRUE(props.valid);
  EXPECT_NEAR(props.volume / (M_PI * r * r * h), 1.0, tolerance);
  EXPECT_NEAR(props.inertia(0, 0) / ((3 * r * r + h * h) / 12), 1.0, tolerance);
  EXPECT_NEAR(props.inertia(1, 1) / ((3 * r * r + h * h) / 12), 1.0, tolerance);
  EXPECT_NEAR(props.inertia(2, 2) / (r * r / 2), 1.0, tolerance);
}

TEST(MassProperties, IcosphereLiesBetweenInscribedAndCircumscribedBalls) {
  const double r = 50;
  const TriangleMesh sphere = makeIcosphere(r, 4);
  const double r_in = inscribedRadius(sphere);
  ASSERT_GT(r_in, 0.99 * r);  // 5120 faces: within 1% of the sphere
  const MassProperties props = computeMassProperties(sphere);
  ASSERT_TRUE(props.valid);

  // The solid contains the inscribed ball and lies in the circumscribed one.
  const double ball_in = 4.0 / 3.0 * M_PI * std::pow(r_in, 3);
  EXPECT_GE(props.volume, ball_in);
  EXPECT_LE(props.volume, 4.0 / 3.0 * M_PI * std::pow(r, 3));
  EXPECT_NEAR(props.centroid.norm(), 0.0, 1e-9);

  // Icosahedral symmetry makes the inertia isotropic: Ixx = 2/3 E|x|^2. E|x|^2 is at least the
  // inscribed ball's 3/5 r_in^2 (points outside it are farther out) and at most that ball's
  // share plus r^2 for the rest of the volume.
  const double mean_square_low = 0.6 * r_in * r_in;
  const double mean_square_high =
      (0.6 * r_in * r_in * ball_in + r * r * (props.volume - ball_in)) / props.volume;
  for (int i = 0; i < 3; ++i) {
    EXPECT_GE(props.inertia(i, i), 2.0 / 3.0 * mean_square_low);
    EXPECT_LE(props.inertia(i, i), 2.0 / 3.0 * mean_square_high);
    EXPECT_NEAR(props.inertia(i, i), props.inertia(0, 0), 1e-9 * r * r);
  }
  EXPECT_NEAR(props.inertia(0, 1), 0.0, 1e-9 * r * r);
  EXPECT_NEAR(props.inertia(0, 2), 0.0, 1e-9 * r * r);
  EXPECT_NEAR(props.inertia(1, 2), 0.0, 1e-9 * r * r);
}

TEST(MassProperties, UnweldedSeamsStillCountAsClosed) {
  // GraspIt!'s meshes are often closed only geometrically: here the top face has its own copy
  // of its four corners, so no edge is shared, yet the surface encloses the box exactly.
  TriangleMesh box = makeBox(10, 20, 30);
  for (const int corner : {4, 5, 6, 7}) box.vertices.push_back(box.vertices[corner]);
  box.triangles[2] = {8, 9, 11};
  box.triangles[3] = {8, 11, 10};
  ASSERT_FALSE(isClosed(box));
  const MassProperties props = computeMassProperties(box);
  ASSERT_TRUE(props.valid);
  EXPECT_NEAR(props.volume, 6000, 1e-9);
}

// GraspIt! integrates open meshes too (its models often are), and its method decides the
// numbers: the volume is the sum over faces of n_x times the integral of x, the first moments
// half the sums of n_i times the integrals of x_i^2, the second moments a third of the sums of
// n_i times the integrals of x_i^3. For the 10 mm cube centred at the origin without its z+ face,
// by hand: volume 1000 (the x faces are all there), T1_z = -2500/2 (the z- face alone), so the
// centroid is (0, 0, -1.25); T2 = (25000/3, 25000/3, 12500/3), so about the origin Ixx = Iyy =
// 12.5 and Izz = 50/3 per unit mass, and about the centroid Ixx = Iyy = 12.5 - 1.5625.
TEST(MassProperties, OpenBoxGivesGraspItsIntegrals) {
  TriangleMesh box = makeBox(10, 10, 10);
  box.triangles.erase(box.triangles.begin() + 2, box.triangles.begin() + 4);  // no z+ lid
  const MassProperties props = computeMassProperties(box);
  ASSERT_TRUE(props.valid);
  EXPECT_NEAR(props.volume, 1000, 1e-9);
  EXPECT_TRUE(props.centroid.isApprox(Vector3(0, 0, -1.25), 1e-12));
  Matrix3 expected = Matrix3::Zero();
  expected.diagonal() << 12.5 - 1.5625, 12.5 - 1.5625, 50.0 / 3.0;
  EXPECT_TRUE(props.inertia.isApprox(expected, 1e-12)) << props.inertia;
}

// A tube open at both ends: volume 10 x 10 x 30 from the x faces; T2 = (25000, 25000, 0), so
// Ixx = Iyy = 25000/3000 and Izz = 50000/3000 (the closed box would give 83.3, 83.3, 16.7).
TEST(MassProperties, TubeWithBothEndsOpenGivesGraspItsIntegrals) {
  TriangleMesh box = makeBox(10, 10, 30);
  box.triangles.erase(box.triangles.begin(), box.triangles.begin() + 4);  // no z- and z+ faces
  const MassProperties props = computeMassProperties(box);
  ASSERT_TRUE(props.valid);
  EXPECT_NEAR(props.volume, 3000, 1e-9);
  EXPECT_TRUE(props.centroid.isZero(1e-12));
  Matrix3 expected = Matrix3::Zero();
  expected.diagonal() << 25.0 / 3.0, 25.0 / 3.0, 50.0 / 3.0;
  EXPECT_TRUE(props.inertia.isApprox(expected, 1e-12)) << props.inertia;
}

// Inside out, every integral changes sign: with density 1/volume the centroid and inertia are the
// box's own (GraspIt! checks |volume| only), and the volume comes back negative.
TEST(MassProperties, InsideOutBoxGivesTheBoxsInertia) {
  TriangleMesh box = makeBox(10, 10, 10);
  for (Triangle& t : box.triangles) std::swap(t[1], t[2]);
  const MassProperties props = computeMassProperties(box);
  ASSERT_TRUE(props.valid);
  EXPECT_NEAR(props.volume, -1000, 1e-9);
  EXPECT_TRUE(props.inertia.isApprox(Matrix3::Identity() * (200.0 / 12.0), 1e-12)) << props.inertia;
}

// A zero-area triangle has no normal: GraspIt!'s integrals turn NaN and it falls back.
TEST(MassProperties, ZeroAreaTriangleMakesTheIntegralsUnusable) {
  TriangleMesh box = makeBox(10, 10, 10);
  box.triangles.push_back({0, 1, 1});
  expectInvalidAndZero(computeMassProperties(box));
}

TEST(MassProperties, FlatDoubleSidedTriangleIsInvalid) {
  TriangleMesh flat;
  flat.vertices = {{0, 0, 0}, {10, 0, 0}, {0, 10, 0}};
  flat.triangles = {{0, 1, 2}, {0, 2, 1}};
  EXPECT_TRUE(isClosed(flat));  // topologically closed, but it encloses nothing
  expectInvalidAndZero(computeMassProperties(flat));
}

TEST(MassProperties, VolumeBelowGraspItThresholdIsInvalid) {
  // GraspIt! rejects volumes under 1e-5 mm^3; this box has 1e-6.
  expectInvalidAndZero(computeMassProperties(makeBox(0.01, 0.01, 0.01)));
}

TEST(MassProperties, CentroidBeyond500MillimetresIsInvalid) {
  TriangleMesh near_box = makeBox(10, 10, 10);
  TriangleMesh far_box = makeBox(10, 10, 10);
  transformMesh(near_box, Eigen::Affine3d(Eigen::Translation3d(0, 0, 490)));
  transformMesh(far_box, Eigen::Affine3d(Eigen::Translation3d(0, 0, 510)));
  EXPECT_TRUE(computeMassProperties(near_box).valid);
  expectInvalidAndZero(computeMassProperties(far_box));
}

TEST(MassProperties, NonFiniteVertexIsInvalidWithoutNaN) {
  TriangleMesh box = makeBox(10, 10, 10);
  box.vertices[3].x() = std::numeric_limits<double>::quiet_NaN();
  expectInvalidAndZero(computeMassProperties(box));
}

TEST(MassProperties, EmptyMeshIsInvalid) {
  expectInvalidAndZero(computeMassProperties({}));
}

TEST(MassPropertiesSurface, CentroidOfOpenBoxIsAreaWeighted) {
  // Unit cube [0,1]^3 without its lid: the floor's centroid is at z = 0 and the four walls' at
  // z = 1/2, all of area 1, so the surface centroid is at z = 2/5.
  TriangleMesh box = makeBox(1, 1, 1);
  box.triangles.erase(box.triangles.begin() + 2, box.triangles.begin() + 4);
  transformMesh(box, Eigen::Affine3d(Eigen::Translation3d(0.5, 0.5, 0.5)));
  const Vector3 centroid = surfaceCentroid(box);
  EXPECT_NEAR(centroid.x(), 0.5, 1e-12);
  EXPECT_NEAR(centroid.y(), 0.5, 1e-12);
  EXPECT_NEAR(centroid.z(), 0.4, 1e-12);
}

TEST(MassPropertiesSurface, CentroidOfUnevenlyTriangulatedSurfaceIgnoresTriangleCount) {
  // The prism's caps are fans of thin triangles and its sides are long quads; the surface
  // centroid must still be the centre.
  const Vector3 centroid = surfaceCentroid(makePrism(9, 10, 50));
  EXPECT_NEAR(centroid.norm(), 0.0, 1e-12);
}

TEST(MassPropertiesSurface, MaxRadiusIsFarthestVertex) {
  const TriangleMesh box = makeBox(2, 4, 6);
  EXPECT_NEAR(maxRadius(box, Vector3::Zero()), std::sqrt(1 + 4 + 9), 1e-12);
  EXPECT_NEAR(maxRadius(box, Vector3(-1, -2, -3)), std::sqrt(4 + 16 + 36), 1e-12);
  EXPECT_EQ(maxRadius(TriangleMesh{}, Vector3::Zero()), 0.0);
}

TEST(MassPropertiesClosedness, BoxAndSphereAreClosed) {
  EXPECT_TRUE(isClosed(makeBox(1, 2, 3)));
  EXPECT_TRUE(isClosed(makeIcosphere(1, 2)));
  EXPECT_TRUE(isClosed(makePrism(5, 1, 1)));
}

TEST(MassPropertiesClosedness, HolesAndBadWindingAreNotClosed) {
  TriangleMesh open = makeBox(1, 1, 1);
  open.triangles.pop_back();
  EXPECT_FALSE(isClosed(open));

  TriangleMesh flipped = makeBox(1, 1, 1);
  std::swap(flipped.triangles[0][1], flipped.triangles[0][2]);
  EXPECT_FALSE(isClosed(flipped));

  TriangleMesh doubled = makeBox(1, 1, 1);
  doubled.triangles.push_back(doubled.triangles[0]);  // an edge used three times
  EXPECT_FALSE(isClosed(doubled));

  EXPECT_FALSE(isClosed(TriangleMesh{}));
}

}  // namespace
}  // namespace graspkit
