// Ray and nearest-surface queries (RayScene) against closed forms: icospheres built here by
// subdividing an icosahedron, whose surface lies between the inscribed radius (the nearest face
// plane) and the circumscribed radius R, and a rotated cube whose hits follow from its face
// planes. Batches are checked against single rays and against the sphere equation.

#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <random>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "graspkit/base/error.hpp"
#include "graspkit/model/body.hpp"
#include "graspkit/model/world.hpp"
#include "graspkit/raycast/ray_scene.hpp"
#include "test_meshes.hpp"

namespace graspkit {
namespace {

using test::icosphere;

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// Embree decides in float; results are recomputed in double on the triangle it found.
constexpr double kFloatTol = 1e-4;  // mm, for scenes of a few hundred mm

// ---------------------------------------------------------------------------------------------
// Independent references

// The inscribed radius: the distance from the centre (origin) to the nearest face plane.
double inscribedRadius(const TriangleMesh& mesh) {
  double r = kInf;
  for (const auto& t : mesh.triangles) {
    const Vector3& a = mesh.vertices[t[0]];
    const Vector3 n = (mesh.vertices[t[1]] - a).cross(mesh.vertices[t[2]] - a).normalized();
    r = std::min(r, std::abs(n.dot(a)));
  }
  return r;
}

// A cube of half-edge `h` about the origin, faces counter-clockwise seen from outside.
std::shared_ptr<TriangleMesh> cube(double h) {
  auto mesh = std::make_shared<TriangleMesh>();
  for (int i = 0; i < 8; ++i)
    mesh->vertices.push_back(Vector3(i & 1 ? h : -h, i & 2 ? h : -h, i & 4 ? h : -h));
  mesh->triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                     {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  return mesh;
}

Transform pose(const Vector3& translation, double angle, const Vector3& axis) {
  Transform t = Transform::Identity();
  t.translation() = translation;
  t.linear() = Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
  return t;
}

int addBody(World& world, std::shared_ptr<TriangleMesh> mesh, const Transform& where) {
  auto model = std::make_shared<BodyModel>();
  model->name = "shape";
  model->mesh = std::move(mesh);
  Body body;
  body.model = model;
  body.kind = BodyKind::Graspable;
  body.name = "shape";
  body.setPose(where);
  return world.addBody(std::move(body));
}

double angleBetween(const Vector3& a, const Vector3& b) {
  return std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0));
}

// One sphere of radius 50 mm, level 4 (5120 faces), moved and turned, and a far cube.
struct RaySceneSphere : ::testing::Test {
  static constexpr double R = 50.0;
  std::shared_ptr<TriangleMesh> mesh = icosphere(R, 4);
  double rIn = inscribedRadius(*mesh);
  // No face normal is farther than this from the radial line through any point of the face.
  double maxTilt = std::acos(rIn / R);
  Vector3 centre{120.0, -40.0, 75.0};
  World world;
  int body = addBody(world, mesh, pose(centre, 0.7, Vector3(1, 2, 3)));
  // A small cube far away, so queries go through the scene's top level of instances.
  int farCube =
      addBody(world, cube(1.0), pose(centre + Vector3(0, 5000, 0), 0.0, Vector3::UnitX()));

  void expectOnSphere(const Vector3& p, const Vector3& c) const {
    const double r = (p - c).norm();
    EXPECT_GE(r, rIn - kFloatTol);
    EXPECT_LE(r, R + kFloatTol);
  }
};

// ---------------------------------------------------------------------------------------------
// Rays

TEST_F(RaySceneSphere, TessellationBoundsAreTight) {
  // The references themselves: level 4 lies within 0.2% of the sphere, faces tilt < 3 degrees.
  EXPECT_GT(rIn, 0.998 * R);
  EXPECT_LT(maxTilt, 3.0 * M_PI / 180.0);
}

TEST_F(RaySceneSphere, RayTowardTheCentreHitsTheNearSide) {
  RayScene scene(world);
  std::mt19937 rng(7);
  std::normal_distribution<double> gauss;
  for (int i = 0; i < 200; ++i) {
    const Vector3 out = Vector3(gauss(rng), gauss(rng), gauss(rng)).normalized();
    const double range = 80.0 + 400.0 * (i % 10) / 10.0;
    const Ray ray{centre + range * out, -out};
    const auto hit = scene.intersect(ray);
    ASSERT_TRUE(hit) << i;
    EXPECT_EQ(hit->body, BodyRef::body(body));
    EXPECT_GE(hit->distance, range - R - kFloatTol);
    EXPECT_LE(hit->distance, range - rIn + kFloatTol);
    expectOnSphere(hit->point, centre);
    EXPECT_NEAR((hit->point - (ray.origin + hit->distance * ray.direction)).norm(), 0.0, 1e-9);
    EXPECT_NEAR(hit->normal.norm(), 1.0, 1e-12);
    EXPECT_LE(angleBetween(hit->normal, out), maxTilt + 1e-5);
  }
}

TEST_F(RaySceneSphere, DirectionNeedNotBeUnit) {
  RayScene scene(world);
  const Ray ray{centre + Vector3(0, 0, 300), Vector3(0, 0, -1e-3)};
  const auto hit = scene.intersect(ray);
  ASSERT_TRUE(hit);
  EXPECT_GE(hit->distance, 300 - R - kFloatTol);
  EXPECT_LE(hit->distance, 300 - rIn + kFloatTol);
}

TEST_F(RaySceneSphere, RayThatMissesFindsNothing) {
  RayScene scene(world);
  // Passing 1.05 R from the centre, and pointing away from the sphere.
  EXPECT_FALSE(scene.intersect({centre + Vector3(-300, 1.05 * R, 0), Vector3::UnitX()}));
  EXPECT_FALSE(scene.intersect({centre + Vector3(-300, 0, 0), -Vector3::UnitX()}));
}

TEST_F(RaySceneSphere, SegmentLimitsAreHonoured) {
  RayScene scene(world);
  const Vector3 origin = centre + Vector3(-300, 0, 0);
  // tmax short of the sphere: nothing; tmin past the near side: the far side.
  EXPECT_FALSE(scene.intersect({origin, Vector3::UnitX(), 0.0, 300 - R - 1.0}));
  const auto far = scene.intersect({origin, Vector3::UnitX(), 300.0, kInf});
  ASSERT_TRUE(far);
  EXPECT_GE(far->distance, 300 + rIn - kFloatTol);
  EXPECT_LE(far->distance, 300 + R + kFloatTol);
  EXPECT_FALSE(scene.intersect({origin, Vector3::UnitX(), 10.0, 5.0}));  // tmax < tmin
}

TEST_F(RaySceneSphere, RayFromInsideHitsTheFarSideFromWithin) {
  RayScene scene(world);
  std::mt19937 rng(11);
  std::normal_distribution<double> gauss;
  for (int i = 0; i < 100; ++i) {
    const Vector3 dir = Vector3(gauss(rng), gauss(rng), gauss(rng)).normalized();
    const auto hit = scene.intersect({centre, dir});
    ASSERT_TRUE(hit);
    EXPECT_GE(hit->distance, rIn - kFloatTol);
    EXPECT_LE(hit->distance, R + kFloatTol);
    expectOnSphere(hit->point, centre);
    // The outward normal, seen from inside: along the ray.
    EXPECT_LE(angleBetween(hit->normal, dir), maxTilt + 1e-5);
  }
}

TEST(RayScene, RotatedCubeHitsItsFacePlane) {
  // A cube of half-edge 10 turned 30 degrees about z: a ray along -x through the centre meets
  // the face whose outward normal is (cos 30, sin 30, 0), at 10 / cos 30 from the centre.
  World world;
  const double a = 30.0 * M_PI / 180.0;
  const Vector3 c(5, 6, 7);
  const int b = addBody(world, cube(10.0), pose(c, a, Vector3::UnitZ()));
  RayScene scene(world);
  const auto hit = scene.intersect({c + Vector3(100, 0, 0), -Vector3::UnitX()});
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->body, BodyRef::body(b));
  EXPECT_NEAR(hit->distance, 100 - 10 / std::cos(a), kFloatTol);
  EXPECT_NEAR((hit->normal - Vector3(std::cos(a), std::sin(a), 0)).norm(), 0.0, 1e-6);
  EXPECT_NEAR((hit->point - (c + Vector3(10 / std::cos(a), 0, 0))).norm(), 0.0, kFloatTol);
  // From the side along +y: the face with normal (-sin 30, cos 30, 0) seen from outside.
  const auto side = scene.intersect({c + Vector3(0, 100, 0), -Vector3::UnitY()});
  ASSERT_TRUE(side);
  EXPECT_NEAR(side->distance, 100 - 10 / std::cos(a), kFloatTol);
  EXPECT_NEAR((side->normal - Vector3(-std::sin(a), std::cos(a), 0)).norm(), 0.0, 1e-6);
}

TEST_F(RaySceneSphere, BatchesAgreeWithSingleRaysAndLieOnTheSphere) {
  RayScene scene(world);
  std::mt19937 rng(3);
  std::normal_distribution<double> gauss;
  std::vector<Ray> rays;
  for (int i = 0; i < 1000; ++i) {
    const Vector3 from = centre + 3 * R * Vector3(gauss(rng), gauss(rng), gauss(rng)).normalized();
    const Vector3 to = centre + 1.5 * R * Vector3(gauss(rng), gauss(rng), gauss(rng)) / 2.0;
    rays.push_back({from, to - from});
  }
  std::vector<std::optional<RayHit>> hits(rays.size());
  scene.intersect(rays, hits);
  int hitCount = 0;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const auto single = scene.intersect(rays[i]);
    ASSERT_EQ(single.has_value(), hits[i].has_value()) << i;
    if (!single) continue;
    ++hitCount;
    EXPECT_EQ(hits[i]->body, single->body);
    EXPECT_NEAR(hits[i]->distance, single->distance, kFloatTol) << i;
    EXPECT_NEAR((hits[i]->point - single->point).norm(), 0.0, kFloatTol) << i;
    expectOnSphere(hits[i]->point, centre);
    // A ray from outside meets the outward side.
    EXPECT_LT(hits[i]->normal.dot(rays[i].direction), 0.0) << i;
  }
  // Both cases occur: some rays aim beside the sphere.
  EXPECT_GT(hitCount, 300);
  EXPECT_LT(hitCount, 1000);
}

TEST_F(RaySceneSphere, UpdateMovesTheHits) {
  RayScene scene(world);
  const Vector3 origin = centre + Vector3(0, 0, 400);
  ASSERT_TRUE(scene.intersect({origin, -Vector3::UnitZ()}));
  const Vector3 moved = centre + Vector3(200, 0, 0);
  World later = world.clone();
  later.bodies()[body].setPose(pose(moved, 0.1, Vector3::UnitX()));
  scene.update(later);
  EXPECT_FALSE(scene.intersect({origin, -Vector3::UnitZ()}));
  const auto hit = scene.intersect({moved + Vector3(0, 0, 400), -Vector3::UnitZ()});
  ASSERT_TRUE(hit);
  EXPECT_GE(hit->distance, 400 - R - kFloatTol);
  EXPECT_LE(hit->distance, 400 - rIn + kFloatTol);
  expectOnSphere(hit->point, moved);
  const auto near = scene.nearestSurfacePoint(moved + Vector3(0, 100, 0));
  ASSERT_TRUE(near);
  expectOnSphere(near->point, moved);
}

// ---------------------------------------------------------------------------------------------
// Nearest surface points

TEST_F(RaySceneSphere, NearestPointFromOutsideIsDAway) {
  RayScene scene(world);
  std::mt19937 rng(5);
  std::normal_distribution<double> gauss;
  for (int i = 0; i < 200; ++i) {
    const Vector3 out = Vector3(gauss(rng), gauss(rng), gauss(rng)).normalized();
    const double d = 0.5 + 2.0 * i;
    const Vector3 q = centre + (R + d) * out;
    for (const auto& found :
         {scene.nearestSurfacePoint(q), scene.nearestSurfacePoint(BodyRef::body(body), q)}) {
      ASSERT_TRUE(found) << i;
      EXPECT_EQ(found->body, BodyRef::body(body));
      EXPECT_GE(found->distance, d - kFloatTol);
      EXPECT_LE(found->distance, d + R - rIn + kFloatTol);
      EXPECT_NEAR((found->point - q).norm(), found->distance, 1e-9);
      expectOnSphere(found->point, centre);
      EXPECT_LE(angleBetween(found->normal, out), 2 * maxTilt + 1e-6);
    }
  }
}

TEST_F(RaySceneSphere, TheFarCubeIsThereToo) {
  RayScene scene(world);
  ASSERT_EQ(scene.bodies().size(), 2u);
  const auto hit = scene.intersect({centre + Vector3(0, 4000, 0), Vector3::UnitY()});
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->body, BodyRef::body(farCube));
  EXPECT_NEAR(hit->distance, 999.0, kFloatTol);
  EXPECT_NEAR((hit->normal - Vector3(0, -1, 0)).norm(), 0.0, 1e-6);
  const auto near = scene.nearestSurfacePoint(centre + Vector3(0.5, 4990, 0.25));
  ASSERT_TRUE(near);
  EXPECT_EQ(near->body, BodyRef::body(farCube));
  EXPECT_NEAR(near->distance, 9.0, 1e-6);
  EXPECT_NEAR((near->point - (centre + Vector3(0.5, 4999, 0.25))).norm(), 0.0, 1e-6);
  EXPECT_NEAR((near->normal - Vector3(0, -1, 0)).norm(), 0.0, 1e-12);
}

TEST_F(RaySceneSphere, NearestPointBeyondMaxDistanceIsNone) {
  RayScene scene(world);
  const Vector3 q = centre + Vector3(R + 10.0, 0, 0);
  EXPECT_FALSE(scene.nearestSurfacePoint(q, 9.0));
  EXPECT_FALSE(scene.nearestSurfacePoint(BodyRef::body(body), q, 9.0));
  EXPECT_TRUE(scene.nearestSurfacePoint(q, 10.0 + (R - rIn) + 1e-3));
  EXPECT_TRUE(scene.nearestSurfacePoint(BodyRef::body(body), q, 10.0 + (R - rIn) + 1e-3));
}

TEST(RayScene, NearerBodyWinsAndRestrictionsHold) {
  World world;
  const double R = 20.0;
  auto mesh = icosphere(R, 3);
  const double rIn = inscribedRadius(*mesh);
  const int a = addBody(world, mesh, pose(Vector3(0, 0, 0), 0.3, Vector3::UnitY()));
  const int b = addBody(world, mesh, pose(Vector3(100, 0, 0), 1.1, Vector3::UnitZ()));
  RayScene scene(world);
  ASSERT_EQ(scene.bodies().size(), 2u);

  const auto fromLeft = scene.intersect({Vector3(-200, 0, 0), Vector3::UnitX()});
  ASSERT_TRUE(fromLeft);
  EXPECT_EQ(fromLeft->body, BodyRef::body(a));
  const auto fromRight = scene.intersect({Vector3(300, 0, 0), -Vector3::UnitX()});
  ASSERT_TRUE(fromRight);
  EXPECT_EQ(fromRight->body, BodyRef::body(b));

  const Vector3 q(40, 0, 0);  // 40 - R from a, 60 - R from b
  const auto nearest = scene.nearestSurfacePoint(q);
  ASSERT_TRUE(nearest);
  EXPECT_EQ(nearest->body, BodyRef::body(a));
  EXPECT_GE(nearest->distance, 40 - R - kFloatTol);
  EXPECT_LE(nearest->distance, 40 - rIn + kFloatTol);

  const BodyRef onlyB[] = {BodyRef::body(b)};
  const auto restricted = scene.nearestSurfacePoint(q, kInf, onlyB);
  ASSERT_TRUE(restricted);
  EXPECT_EQ(restricted->body, BodyRef::body(b));
  EXPECT_GE(restricted->distance, 60 - R - kFloatTol);
  EXPECT_LE(restricted->distance, 60 - rIn + kFloatTol);
  const auto perBody = scene.nearestSurfacePoint(BodyRef::body(b), q);
  ASSERT_TRUE(perBody);
  EXPECT_NEAR(perBody->distance, restricted->distance, 1e-12);

  // A scene built without body a sees only b.
  RayScene onlyBScene(world, {[&](const BodyRef& ref) { return ref == BodyRef::body(b); }});
  ASSERT_EQ(onlyBScene.bodies().size(), 1u);
  const auto through = onlyBScene.intersect({Vector3(-200, 0, 0), Vector3::UnitX()});
  ASSERT_TRUE(through);
  EXPECT_EQ(through->body, BodyRef::body(b));
  EXPECT_THROW(onlyBScene.nearestSurfacePoint(BodyRef::body(a), q), Error);
}

// ---------------------------------------------------------------------------------------------
// Bad input and empty scenes

TEST_F(RaySceneSphere, NonFiniteRaysAreErrors) {
  RayScene scene(world);
  EXPECT_THROW(scene.intersect({Vector3(kNaN, 0, 0), Vector3::UnitX()}), Error);
  EXPECT_THROW(scene.intersect({Vector3(kInf, 0, 0), Vector3::UnitX()}), Error);
  EXPECT_THROW(scene.intersect({Vector3::Zero(), Vector3(0, kNaN, 0)}), Error);
  EXPECT_THROW(scene.intersect({Vector3::Zero(), Vector3(0, kInf, 0)}), Error);
  EXPECT_THROW(scene.intersect({Vector3::Zero(), Vector3::Zero()}), Error);
  EXPECT_THROW(scene.intersect({Vector3::Zero(), Vector3::UnitX(), kNaN, 1.0}), Error);
  EXPECT_THROW(scene.intersect({Vector3::Zero(), Vector3::UnitX(), -1.0, 1.0}), Error);
  EXPECT_THROW(scene.intersect({Vector3::Zero(), Vector3::UnitX(), 0.0, kNaN}), Error);
  // Finite in double, infinite in Embree's float: refused, never passed on (Embree aborts).
  EXPECT_THROW(scene.intersect({Vector3(1e300, 0, 0), -Vector3::UnitX()}), Error);
  EXPECT_THROW(scene.intersect({Vector3::Zero(), Vector3::UnitX(), 1e300, kInf}), Error);
  // A segment end past float range is no end: the sphere is still hit.
  EXPECT_TRUE(scene.intersect({centre + Vector3(0, 0, 300), -Vector3::UnitZ(), 0.0, 1e300}));

  // A batch checks every ray before tracing any, and leaves the hits alone when one is bad.
  std::vector<Ray> rays(40, Ray{centre + Vector3(0, 0, 300), -Vector3::UnitZ()});
  rays[33].origin.x() = kNaN;
  std::vector<std::optional<RayHit>> hits(rays.size());
  EXPECT_THROW(scene.intersect(rays, hits), Error);
  for (const auto& hit : hits) EXPECT_FALSE(hit);
  std::vector<std::optional<RayHit>> tooFew(3);
  EXPECT_THROW(scene.intersect(rays, tooFew), Error);

  EXPECT_THROW(scene.nearestSurfacePoint(Vector3(kNaN, 0, 0)), Error);
  EXPECT_THROW(scene.nearestSurfacePoint(centre, -1.0), Error);
  EXPECT_THROW(scene.nearestSurfacePoint(centre, kNaN), Error);
}

TEST(RayScene, EmptyWorldHasNoHits) {
  World world;
  RayScene scene(world);
  EXPECT_TRUE(scene.bodies().empty());
  EXPECT_FALSE(scene.intersect({Vector3::Zero(), Vector3::UnitX()}));
  EXPECT_FALSE(scene.nearestSurfacePoint(Vector3::Zero()));
  std::vector<Ray> rays(20, Ray{Vector3::Zero(), Vector3::UnitY()});
  std::vector<std::optional<RayHit>> hits(rays.size(), RayHit{});
  scene.intersect(rays, hits);
  for (const auto& hit : hits) EXPECT_FALSE(hit);
  scene.update(world);
  EXPECT_FALSE(scene.intersect({Vector3::Zero(), Vector3::UnitX()}));
  // A body with an empty mesh is left out.
  addBody(world, std::make_shared<TriangleMesh>(), Transform::Identity());
  RayScene withEmpty(world);
  EXPECT_TRUE(withEmpty.bodies().empty());
}

TEST_F(RaySceneSphere, UpdateRejectsAWorldWithoutTheBody) {
  RayScene scene(world);
  EXPECT_THROW(scene.update(World{}), Error);
}

}  // namespace
}  // namespace graspkit
