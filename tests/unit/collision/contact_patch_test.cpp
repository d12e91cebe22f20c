// The soft-finger patch against hand computations: paraboloids fitted through points of known
// quadrics; principal radii of paraboloids built from chosen curvatures; relative radii of
// spheres, planes and cylinders from Johnson's closed forms (sphere on sphere 1/R' = 1/R1 +
// 1/R2, parallel cylinders R/2, crossed cylinders R1 and R2); the mattress ellipse worked out
// by hand; and whole contacts between meshed spheres, a cylinder and a slab, which must give
// the radii and e_tau of the ideal shapes.

#include "graspkit/collision/contact_patch.hpp"

#include <cmath>
#include <memory>
#include <numbers>
#include <optional>
#include <random>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "collision/contact_neighbourhood.hpp"
#include "graspkit/collision/contact_search.hpp"
#include "graspkit/model/body.hpp"
#include "graspkit/model/material.hpp"
#include "graspkit/model/world.hpp"
#include "test_meshes.hpp"

namespace graspkit {
namespace {

constexpr double kRubber = 1.5e6;  // Pa

// ---------------------------------------------------------------------------------------------
// Fitting

std::vector<Vector3> sampled(const Paraboloid& s, double extent, int steps) {
  std::vector<Vector3> points;
  for (int i = -steps; i <= steps; ++i)
    for (int j = -steps; j <= steps; ++j) {
      const double x = extent * i / steps, y = extent * j / steps;
      points.emplace_back(x, y, s.a * x * x + s.b * y * y + s.c * x * y);
    }
  return points;
}

TEST(FitParaboloid, RecoversAnExactQuadric) {
  const Paraboloid truth{0.02, 0.05, -0.03};
  const Paraboloid fit = fitParaboloid(sampled(truth, 3.0, 4));
  EXPECT_NEAR(fit.a, truth.a, 1e-12);
  EXPECT_NEAR(fit.b, truth.b, 1e-12);
  EXPECT_NEAR(fit.c, truth.c, 1e-12);
}

TEST(FitParaboloid, AlmostPlanarCoefficientsAreZero) {
  const Paraboloid fit = fitParaboloid(sampled({5e-7, 0.01, -5e-7}, 3.0, 4));
  EXPECT_EQ(fit.a, 0.0);
  EXPECT_NEAR(fit.b, 0.01, 1e-12);
  EXPECT_EQ(fit.c, 0.0);
}

TEST(FitParaboloid, PointsOnALineLeaveItFlat) {
  const std::vector<Vector3> line = {{0, 0, 0}, {1, 0, 0.1}, {2, 0, 0.4}, {3, 0, 0.9}};
  const Paraboloid fit = fitParaboloid(line);
  EXPECT_EQ(fit.a, 0.0);
  EXPECT_EQ(fit.b, 0.0);
  EXPECT_EQ(fit.c, 0.0);
  EXPECT_EQ(fitParaboloid({}).a, 0.0);
}

// ---------------------------------------------------------------------------------------------
// Principal radii

// The paraboloid with curvatures k1 along (cos t, sin t) and k2 across it.
Paraboloid turned(double k1, double k2, double t) {
  const double c = std::cos(t), s = std::sin(t);
  return {(k1 * c * c + k2 * s * s) / 2.0, (k1 * s * s + k2 * c * c) / 2.0, (k1 - k2) * s * c};
}

double curvatureAlong(const Paraboloid& p, const Vector3& d) {
  return 2.0 * (p.a * d.x() * d.x() + p.b * d.y() * d.y() + p.c * d.x() * d.y());
}

TEST(PrincipalRadii, SphereCapHasItsRadiusBothWays) {
  const PrincipalRadii r = principalRadii({1.0 / 40.0, 1.0 / 40.0, 0.0});
  EXPECT_DOUBLE_EQ(r.r1, 20.0);
  EXPECT_DOUBLE_EQ(r.r2, 20.0);
}

TEST(PrincipalRadii, TurnedEllipticPatch) {
  for (double t : {0.4, -1.1, 2.0}) {
    const Paraboloid p = turned(1.0 / 8.0, 1.0 / 30.0, t);
    const PrincipalRadii r = principalRadii(p);
    // Whichever is called r1, the two radii are 8 and 30 and r1 is the one along `direction`.
    EXPECT_NEAR(std::min(r.r1, r.r2), 8.0, 1e-9) << t;
    EXPECT_NEAR(std::max(r.r1, r.r2), 30.0, 1e-9) << t;
    EXPECT_NEAR(curvatureAlong(p, r.direction), 1.0 / r.r1, 1e-12) << t;
    EXPECT_NEAR(r.direction.norm(), 1.0, 1e-12);
  }
}

TEST(PrincipalRadii, EqualDiagonalWithATwistIsStillDiagonalised) {
  // a = b: the principal directions are the diagonals, curvatures 2a +- c.
  const PrincipalRadii r = principalRadii({0.05, 0.05, 0.04});
  EXPECT_NEAR(std::min(r.r1, r.r2), 1.0 / 0.14, 1e-9);
  EXPECT_NEAR(std::max(r.r1, r.r2), 1.0 / 0.06, 1e-9);
}

TEST(PrincipalRadii, FlatAndCylindricalPatches) {
  const PrincipalRadii flat = principalRadii({0.0, 0.0, 0.0});
  EXPECT_EQ(flat.r1, -1.0);
  EXPECT_EQ(flat.r2, -1.0);
  const PrincipalRadii cylinder = principalRadii({0.0, 1.0 / 30.0, 0.0});
  EXPECT_EQ(cylinder.r1, -1.0);
  EXPECT_DOUBLE_EQ(cylinder.r2, 15.0);
}

// ---------------------------------------------------------------------------------------------
// Relative radii (Johnson, Contact Mechanics, 4.2)

PrincipalRadii radii(double r1, double r2) {
  return {r1, r2, Vector3::UnitX()};
}

TEST(RelativeRadii, SphereOnSphereAddsCurvatures) {
  const RelativeRadii r = relativeRadii(radii(20, 20), radii(30, 30), 0.7);
  EXPECT_NEAR(r.r1, 12.0, 1e-12);  // 1/R' = 1/20 + 1/30
  EXPECT_NEAR(r.r2, 12.0, 1e-12);
}

TEST(RelativeRadii, SphereOnPlaneIsTheSphere) {
  const RelativeRadii r = relativeRadii(radii(25, 25), radii(-1, -1), 0.0);
  EXPECT_NEAR(r.r1, 25.0, 1e-12);
  EXPECT_NEAR(r.r2, 25.0, 1e-12);
}

TEST(RelativeRadii, ParallelCylindersTouchAlongALine) {
  const RelativeRadii r = relativeRadii(radii(10, -1), radii(10, -1), 0.0);
  EXPECT_NEAR(r.r1, 5.0, 1e-12);
  EXPECT_EQ(r.r2, -1.0);
}

TEST(RelativeRadii, CrossedCylinders) {
  const double right = std::numbers::pi / 2.0;
  const RelativeRadii equal = relativeRadii(radii(10, -1), radii(10, -1), right);
  EXPECT_NEAR(equal.r1, 10.0, 1e-12);  // like a sphere of radius 10 on a plane
  EXPECT_NEAR(equal.r2, 10.0, 1e-12);
  const RelativeRadii unequal = relativeRadii(radii(10, -1), radii(20, -1), right);
  EXPECT_NEAR(unequal.r1, 10.0, 1e-12);
  EXPECT_NEAR(unequal.r2, 20.0, 1e-12);
}

TEST(RelativeRadii, ConcaveAndFlatCountAsFlat) {
  const RelativeRadii r = relativeRadii(radii(-40, -1), radii(-1, -1), 0.3);
  EXPECT_EQ(r.r1, -1.0);
  EXPECT_EQ(r.r2, -1.0);
}

// ---------------------------------------------------------------------------------------------
// The mattress

TEST(MattressEllipse, WorkedExample) {
  // R1' = R2' = 10 mm, E = 1.5e6 Pa, N = 5 N, h = 3 mm, by hand in SI units:
  //   delta = sqrt(5 * 0.003 / (1.5e6 * pi * 0.01)) = 5.64190e-4 m
  //   a = b = sqrt(2 * delta * 0.01) = 3.35914e-3 m
  //   e_tau = 8 sqrt(ab) / 15 = 1.79154e-3 m
  const ContactEllipse e = mattressEllipse({10.0, 10.0}, kRubber, 5.0);
  EXPECT_NEAR(e.semiMajor, 3.35914, 1e-5);
  EXPECT_NEAR(e.semiMinor, 3.35914, 1e-5);
  EXPECT_NEAR(e.torsion, 1.79154, 1e-5);
}

TEST(MattressEllipse, TorsionGrowsWithTheFourthRootOfTheForce) {
  const double at5 = mattressEllipse({8.0, 13.0}, kRubber, 5.0).torsion;
  EXPECT_NEAR(mattressEllipse({8.0, 13.0}, kRubber, 80.0).torsion / at5, 2.0, 1e-12);
  EXPECT_NEAR(mattressEllipse({8.0, 13.0}, 16.0 * kRubber, 5.0).torsion / at5, 0.5, 1e-12);
}

TEST(MattressEllipse, DegenerateRadiiStandAtTwentyMillimetres) {
  const ContactEllipse flat = mattressEllipse({-1.0, -1.0}, kRubber, 5.0);
  const ContactEllipse twenty = mattressEllipse({20.0, 20.0}, kRubber, 5.0);
  EXPECT_DOUBLE_EQ(flat.torsion, twenty.torsion);
  EXPECT_NEAR(twenty.torsion, 2.13051, 1e-5);
}

TEST(MattressEllipse, NoForceNoPatch) {
  EXPECT_EQ(mattressEllipse({10.0, 10.0}, kRubber, 0.0).torsion, 0.0);
  EXPECT_EQ(mattressEllipse({10.0, 10.0}, kRubber, -3.0).torsion, 0.0);
  EXPECT_EQ(mattressEllipse({10.0, 10.0}, 0.0, 5.0).torsion, 0.0);
}

TEST(PatchNeighbourhood, RadiusFromTheModulus) {
  // 0.4 * 1000 * (1 / 1.5e6)^0.333: ln 1.5e6 = 14.22098, times 0.333 = 4.73559, e^- = 8.7773e-3.
  EXPECT_NEAR(patchNeighbourhoodRadius(kRubber), 3.51093, 1e-4);
}

// ---------------------------------------------------------------------------------------------
// Merging contacts that share a patch

// GraspIt!'s mergeSoftNeighborhoods, transcribed: scan for the first pair that overlaps, merge,
// start again.
std::vector<collision::PatchCandidate> mergedByGraspItsLoop(
    std::vector<collision::PatchCandidate> list) {
  auto overlap = [](const collision::Neighbourhood& a, const collision::Neighbourhood& b) {
    for (const Vector3& p : a)
      for (const Vector3& q : b)
        if (p == q) return true;
    return false;
  };
  auto absorb = [](collision::Neighbourhood& into, const collision::Neighbourhood& from) {
    for (const Vector3& p : from)
      if (std::find(into.begin(), into.end(), p) == into.end()) into.push_back(p);
  };
  for (bool merged = true; merged;) {
    merged = false;
    for (std::size_t i = 0; i < list.size() && !merged; ++i)
      for (std::size_t j = 0; j < list.size() && !merged; ++j) {
        if (i == j || !overlap(list[i].onFirst, list[j].onFirst)) continue;
        const bool keep_i = list[i].distance < list[j].distance - 1e-9;
        auto& survivor = keep_i ? list[i] : list[j];
        const auto& gone = keep_i ? list[j] : list[i];
        absorb(survivor.onFirst, gone.onFirst);
        absorb(survivor.onSecond, gone.onSecond);
        list.erase(list.begin() + static_cast<std::ptrdiff_t>(keep_i ? j : i));
        merged = true;
      }
  }
  return list;
}

std::set<std::array<double, 3>> asSet(const collision::Neighbourhood& points) {
  std::set<std::array<double, 3>> out;
  for (const Vector3& p : points) out.insert({p.x(), p.y(), p.z()});
  return out;
}

TEST(MergePatches, SameSurvivorsAndPointsAsGraspItsLoop) {
  // Random patches over a small grid of points, so that many overlap; distances from a short
  // list, so that many tie.
  std::mt19937 random(11);
  for (int trial = 0; trial < 300; ++trial) {
    const int count = 1 + static_cast<int>(random() % 40);
    const int grid = 4 + static_cast<int>(random() % 200);
    std::vector<collision::PatchCandidate> candidates;
    for (int c = 0; c < count; ++c) {
      collision::PatchCandidate candidate{
          static_cast<std::size_t>(c), 0.05 * static_cast<double>(random() % 4), {}, {}};
      const int size = 1 + static_cast<int>(random() % 6);
      for (int k = 0; k < size; ++k) {
        const int g = static_cast<int>(random() % static_cast<unsigned>(grid));
        const Vector3 p(g % 7, g / 7, 0.5);
        if (std::find(candidate.onFirst.begin(), candidate.onFirst.end(), p) ==
            candidate.onFirst.end())
          candidate.onFirst.push_back(p);
        candidate.onSecond.push_back(Vector3(c, k, -1.0));
      }
      candidates.push_back(candidate);
    }
    const auto expected = mergedByGraspItsLoop(candidates);
    collision::mergeOverlappingPatches(candidates);
    ASSERT_EQ(candidates.size(), expected.size()) << trial;
    for (std::size_t i = 0; i < expected.size(); ++i) {
      EXPECT_EQ(candidates[i].contact, expected[i].contact) << trial;
      EXPECT_EQ(asSet(candidates[i].onFirst), asSet(expected[i].onFirst)) << trial;
      EXPECT_EQ(asSet(candidates[i].onSecond), asSet(expected[i].onSecond)) << trial;
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Whole contacts between meshed shapes

Body bodyOf(const std::string& name, std::shared_ptr<const TriangleMesh> mesh, Material material,
            std::optional<double> youngs, const Transform& pose) {
  auto model = std::make_shared<BodyModel>();
  model->name = name;
  model->mesh = std::move(mesh);
  model->material = material;
  model->youngs = youngs;
  Body body;
  body.model = model;
  body.kind = BodyKind::Graspable;
  body.name = name;
  body.setPose(pose);
  return body;
}

Transform at(const Vector3& position, const Matrix3& rotation = Matrix3::Identity()) {
  Transform pose = Transform::Identity();
  pose.linear() = rotation;
  pose.translation() = position;
  return pose;
}

// A mesh moved within its own frame: the patch must not depend on where the body's origin is.
std::shared_ptr<TriangleMesh> shifted(std::shared_ptr<TriangleMesh> mesh, const Vector3& offset) {
  for (Vector3& v : mesh->vertices) v += offset;
  return mesh;
}

// Lowest point of a mesh placed with `pose`.
double lowest(const TriangleMesh& mesh, const Transform& pose) {
  double z = INFINITY;
  for (const Vector3& v : mesh.vertices) z = std::min(z, (pose * v).z());
  return z;
}

// A slab whose top face is z = 0, far wider than any patch.
Body slab() {
  return bodyOf("slab", test::box({-100, -100, -20}, {100, 100, 0}), Material::Wood, std::nullopt,
                Transform::Identity());
}

// `mesh` lowered onto the slab (0.1 mm above it) with the rotation given; contacts between them.
std::vector<Contact> restingOnSlab(std::shared_ptr<TriangleMesh> mesh, const Matrix3& rotation,
                                   std::optional<double> youngs) {
  World world;
  const BodyRef floor = BodyRef::body(world.addBody(slab()));
  Transform pose = at(Vector3(3.0, -2.0, 0.0), rotation);
  pose.translation().z() = 0.1 - lowest(*mesh, pose);
  const BodyRef top =
      BodyRef::body(world.addBody(bodyOf("top", mesh, Material::Rubber, youngs, pose)));
  return findContacts(world, top, floor).contacts;
}

// The contact that survives sits on the rim of the touching patch, up to 1.5 mm off the lowest
// point, where the contact normal (vertical) leans some 7 degrees from the sphere's: the fit
// then tilts one radius up and the other down by up to 6 % and their product by up to 3 % (GraspIt!
// fits the same way). e_tau, which goes with (R1' R2')^(1/8), stays within 1 %.
void expectRadii(const Contact& c, double radius) {
  EXPECT_NEAR(std::sqrt(c.patchRadius1 * c.patchRadius2), radius, 0.03 * radius);
  EXPECT_NEAR(c.patchRadius1, radius, 0.08 * radius);
  EXPECT_NEAR(c.patchRadius2, radius, 0.08 * radius);
}

double expectedTorsion(double r1, double r2) {
  return mattressEllipse({r1, r2}, kRubber, 5.0).torsion;
}

TEST(SoftContacts, SphereOnASlabHasTheSphereRadius) {
  // R = 12 on a plane: R1' = R2' = 12, e_tau = 1.87509 mm by the worked example's steps.
  const Matrix3 turn = Eigen::AngleAxisd(0.7, Vector3(1, 2, 3).normalized()).toRotationMatrix();
  for (const Vector3& offset : {Vector3::Zero().eval(), Vector3(40, -25, 60)}) {
    const auto contacts = restingOnSlab(shifted(test::icosphere(12.0, 5), offset), turn, kRubber);
    // The touching vertices lie well inside one patch: they are one soft contact.
    ASSERT_EQ(contacts.size(), 1u) << offset.transpose();
    const Contact& c = contacts.front();
    EXPECT_EQ(c.model, ContactModel::SoftFinger);
    expectRadii(c, 12.0);
    EXPECT_NEAR(c.torsion, 1.87509, 0.01 * 1.87509);
  }
}

TEST(SoftContacts, TwoSpheresAddTheirCurvatures) {
  World world;
  auto small = test::icosphere(20.0, 5), large = test::icosphere(30.0, 5);
  const BodyRef lower =
      BodyRef::body(world.addBody(bodyOf("lower", large, Material::Wood, kRubber, at({0, 0, 0}))));
  const Transform up = at(Vector3(
      0, 0,
      0.1 - lowest(*small, Transform::Identity()) + (-lowest(*large, Transform::Identity()))));
  const BodyRef upper =
      BodyRef::body(world.addBody(bodyOf("upper", small, Material::Rubber, kRubber, up)));
  const auto contacts = findContacts(world, upper, lower).contacts;
  ASSERT_EQ(contacts.size(), 1u);
  // 1/R' = 1/20 + 1/30: R' = 12 both ways.
  expectRadii(contacts[0], 12.0);
  EXPECT_NEAR(contacts[0].torsion, expectedTorsion(12.0, 12.0), 0.01 * 1.87509);
}

TEST(SoftContacts, CylinderOnASlabTouchesAlongALine) {
  // Lying on its side: R1' = 15 across the axis; along it the pair is flat (20 mm stands in).
  // An open tube: the contacts sit at its ends, where a cap's centre (15 mm up, right above
  // the contact) would join the patch and bend the fit, in GraspIt! as here.
  const Matrix3 lying =
      Eigen::AngleAxisd(std::numbers::pi / 2, Vector3::UnitX()).toRotationMatrix();
  const auto contacts =
      restingOnSlab(test::cylinder(15.0, 60.0, 720, /*caps=*/false), lying, kRubber);
  ASSERT_EQ(contacts.size(), 1u);
  EXPECT_NEAR(contacts[0].patchRadius1, 15.0, 0.45);
  EXPECT_EQ(contacts[0].patchRadius2, kFlatRelativeRadius);
  EXPECT_NEAR(contacts[0].torsion, expectedTorsion(15.0, 20.0), 0.01 * 2.05526);
}

TEST(SoftContacts, RigidBodiesKeepPointContacts) {
  const auto contacts = restingOnSlab(test::icosphere(12.0, 5), Matrix3::Identity(), std::nullopt);
  ASSERT_FALSE(contacts.empty());
  for (const Contact& c : contacts) {
    EXPECT_EQ(c.model, ContactModel::PointWithFriction);
    EXPECT_EQ(c.torsion, 0.0);
  }
}

TEST(SoftContacts, ContactsSharingAPatchMergeIntoTheNearest) {
  // A 40 mm cube on the slab, tilted so one bottom edge is lower: the rigid search finds the
  // corners of the touching patch; soft, the big faces put every corner in every patch.
  const Matrix3 tilt = Eigen::AngleAxisd(0.001, Vector3::UnitY()).toRotationMatrix();
  auto cube = test::box({-20, -20, -20}, {20, 20, 20});
  const auto rigid = restingOnSlab(cube, tilt, std::nullopt);
  const auto soft = restingOnSlab(cube, tilt, kRubber);
  ASSERT_GT(rigid.size(), 1u);
  ASSERT_EQ(soft.size(), 1u);
  double nearest = INFINITY;
  for (const Contact& c : rigid) nearest = std::min(nearest, c.distance);
  EXPECT_DOUBLE_EQ(soft[0].distance, nearest);
  EXPECT_EQ(soft[0].model, ContactModel::SoftFinger);
}

}  // namespace
}  // namespace graspkit
