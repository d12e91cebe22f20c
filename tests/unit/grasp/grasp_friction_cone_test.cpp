// Friction cones, contact frames and contact wrenches against closed-form truths: edge counts
// and latitudes as GraspIt! samples them, orthonormal right-handed frames, and wrenches whose
// normal and tangential parts follow from the contact alone.

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "graspkit/base/error.hpp"
#include "graspkit/grasp/friction_cone.hpp"

namespace graspkit {
namespace {

constexpr double kConeTolerance = 1e-12;

// The latitude of an edge's direction in (fx, fy, tz), in degrees. GraspIt! picks the direction
// at latitude phi and scales it onto the ellipsoid, which keeps the direction.
double latitudeDegrees(const Vector6& e) {
  return radiansToDegrees(std::atan2(e[5], std::hypot(e[0], e[1])));
}

TEST(FrictionCone, PointContactHasEightEdgesEvery45DegreesFromX) {
  const std::vector<Vector6> edges = frictionEdges(ContactModel::PointWithFriction);
  ASSERT_EQ(edges.size(), 8u);
  Vector6 sum = Vector6::Zero();
  for (int k = 0; k < 8; ++k) {
    const Vector6& e = edges[k];
    const double angle = k * M_PI / 4.0;
    EXPECT_NEAR(e[0], std::cos(angle), kConeTolerance) << "edge " << k;
    EXPECT_NEAR(e[1], std::sin(angle), kConeTolerance) << "edge " << k;
    EXPECT_DOUBLE_EQ(e[2], 1.0);  // unit normal force
    EXPECT_EQ(e[3], 0.0);
    EXPECT_EQ(e[4], 0.0);
    EXPECT_EQ(e[5], 0.0);  // no torsion
    EXPECT_NEAR(std::hypot(e[0], e[1]), 1.0, kConeTolerance);
    sum += e;
  }
  // Opposite edges cancel: the tangential parts sum to zero.
  EXPECT_NEAR(sum[0], 0.0, kConeTolerance);
  EXPECT_NEAR(sum[1], 0.0, kConeTolerance);
  EXPECT_DOUBLE_EQ(sum[2], 8.0);
}

TEST(FrictionCone, FrictionlessIsThePureNormal) {
  const std::vector<Vector6> edges = frictionEdges(ContactModel::Frictionless);
  ASSERT_EQ(edges.size(), 1u);
  Vector6 normal = Vector6::Zero();
  normal[2] = 1.0;
  EXPECT_EQ(edges[0], normal);
  EXPECT_TRUE(frictionLatitudes(ContactModel::Frictionless).empty());
}

TEST(FrictionCone, SoftFingerSamplesFiveLatitudesOnTheEllipsoid) {
  const double e_tau = 2.5;  // mm
  const std::vector<Vector6> edges = frictionEdges(ContactModel::SoftFinger, e_tau);
  ASSERT_EQ(edges.size(), 20u);
  const double latitudes[] = {90, 45, 0, -45, -90};
  const int counts[] = {1, 5, 8, 5, 1};
  std::size_t index = 0;
  for (int ring = 0; ring < 5; ++ring) {
    Vector6 ring_sum = Vector6::Zero();
    for (int j = 0; j < counts[ring]; ++j, ++index) {
      const Vector6& e = edges[index];
      // On the ellipsoid with semi-axes (1, 1, e_tau)...
      EXPECT_NEAR(e[0] * e[0] + e[1] * e[1] + (e[5] / e_tau) * (e[5] / e_tau), 1.0, kConeTolerance);
      // ...at the ring's latitude...
      EXPECT_NEAR(latitudeDegrees(e), latitudes[ring], 1e-9) << "edge " << index;
      // ...and the ring's j-th longitude, counted from the frame's x axis.
      if (std::abs(latitudes[ring]) < 90) {
        EXPECT_NEAR(std::atan2(e[1], e[0]),
                    std::remainder(j * 2.0 * M_PI / counts[ring], 2.0 * M_PI), 1e-12);
      }
      EXPECT_DOUBLE_EQ(e[2], 1.0);
      EXPECT_EQ(e[3], 0.0);
      EXPECT_EQ(e[4], 0.0);
      ring_sum += e;
    }
    // Each ring is symmetric about the normal.
    EXPECT_NEAR(ring_sum[0], 0.0, 1e-12);
    EXPECT_NEAR(ring_sum[1], 0.0, 1e-12);
  }
  // The poles are the pure torsion edges +-e_tau.
  EXPECT_NEAR(edges.front()[5], e_tau, kConeTolerance);
  EXPECT_NEAR(edges.back()[5], -e_tau, kConeTolerance);
  // The first edge of each 45-degree ring lies in the x-torsion plane.
  EXPECT_NEAR(edges[1][1], 0.0, kConeTolerance);
  EXPECT_GT(edges[1][0], 0.0);
  EXPECT_NEAR(edges[14][1], 0.0, kConeTolerance);
  EXPECT_GT(edges[14][0], 0.0);
}

TEST(FrictionCone, SoftFingerWithoutTorsionKeepsOnlyTheEquator) {
  const std::vector<Vector6> edges = frictionEdges(ContactModel::SoftFinger, 0.0);
  ASSERT_EQ(edges.size(), 20u);
  for (const Vector6& e : edges) {
    EXPECT_TRUE(e.allFinite());
    EXPECT_EQ(e[5], 0.0);
  }
  EXPECT_NEAR(std::hypot(edges[6][0], edges[6][1]), 1.0, kConeTolerance);  // equator
  EXPECT_EQ(std::hypot(edges[1][0], edges[1][1]), 0.0);                    // off the equator
}

TEST(FrictionCone, RejectsNegativeTorsion) {
  EXPECT_THROW(frictionEdges(ContactModel::SoftFinger, -1.0), Error);
  EXPECT_THROW(frictionEdges(ContactModel::SoftFinger, NAN), Error);
}

void expectRightHandedFrame(const Matrix3& frame, const Vector3& normal) {
  EXPECT_NEAR((frame.transpose() * frame - Matrix3::Identity()).norm(), 0.0, 1e-12);
  EXPECT_NEAR(frame.determinant(), 1.0, 1e-12);
  EXPECT_NEAR((frame.col(2) - normal).norm(), 0.0, 1e-12);
}

TEST(ContactFrame, OrthonormalRightHandedWithZAlongTheNormal) {
  std::mt19937 rng(3);
  std::normal_distribution<double> gauss;
  for (int i = 0; i < 200; ++i) {
    const Vector3 n = Vector3(gauss(rng), gauss(rng), gauss(rng)).normalized();
    const Matrix3 frame = contactFrame(n);
    expectRightHandedFrame(frame, n);
    // Away from +-X, x is n x X normalised.
    const Vector3 expected_x = Vector3(0.0, n.z(), -n.y()) / std::hypot(n.y(), n.z());
    EXPECT_NEAR((frame.col(0) - expected_x).norm(), 0.0, 1e-12);
  }
}

TEST(ContactFrame, NormalAlongXUsesZInstead) {
  // n x X vanishes for n = +-X; then x = n x Z: (1,0,0) x (0,0,1) = (0,-1,0).
  Matrix3 frame = contactFrame(Vector3::UnitX());
  expectRightHandedFrame(frame, Vector3::UnitX());
  EXPECT_NEAR((frame.col(0) - Vector3(0, -1, 0)).norm(), 0.0, kConeTolerance);
  EXPECT_NEAR((frame.col(1) - Vector3(0, 0, -1)).norm(), 0.0, kConeTolerance);

  frame = contactFrame(-Vector3::UnitX());
  expectRightHandedFrame(frame, -Vector3::UnitX());
  EXPECT_NEAR((frame.col(0) - Vector3(0, 1, 0)).norm(), 0.0, kConeTolerance);

  // Within GraspIt!'s tolerance (cosine within 1e-9 of 1) the Z branch is taken too...
  const Vector3 near_x = Vector3(1.0, 1e-6, 0.0).normalized();
  frame = contactFrame(near_x);
  expectRightHandedFrame(frame, near_x);
  EXPECT_NEAR((frame.col(0) - near_x.cross(Vector3::UnitZ()).normalized()).norm(), 0.0,
              kConeTolerance);
  // ...and outside it, n x X.
  const Vector3 off_x = Vector3(1.0, 1e-3, 0.0).normalized();
  frame = contactFrame(off_x);
  EXPECT_NEAR((frame.col(0) - off_x.cross(Vector3::UnitX()).normalized()).norm(), 0.0,
              kConeTolerance);
}

Contact makeContact(const Vector3& point, const Vector3& normal, double mu,
                    ContactModel model = ContactModel::PointWithFriction) {
  Contact c;
  c.position1 = point;
  c.position2 = point - 0.1 * normal;
  c.normal = normal.normalized();
  c.frame = contactFrame(c.normal);
  c.mu = mu;
  c.model = model;
  return c;
}

TEST(Contact, MateSwapsBodiesAndFlipsTheNormal) {
  Contact c = makeContact(Vector3(1, 2, 3), Vector3(0, 0.6, 0.8), 0.4);
  c.body1 = BodyRef::body(0);
  c.body2 = BodyRef::robotLink(0, LinkRef{1, 2});
  c.patchRadius1 = 5.0;
  c.patchRadius2 = 7.0;
  c.torsion = 0.8;
  const Contact m = c.mate();
  EXPECT_EQ(m.body1, c.body2);
  EXPECT_EQ(m.body2, c.body1);
  EXPECT_EQ(m.position1, c.position2);
  EXPECT_EQ(m.position2, c.position1);
  EXPECT_EQ(m.normal, -c.normal);
  expectRightHandedFrame(m.frame, m.normal);
  EXPECT_EQ(m.mu, c.mu);
  // The relative radii and e_tau belong to the pair, seen from either side.
  EXPECT_EQ(m.patchRadius1, 5.0);
  EXPECT_EQ(m.patchRadius2, 7.0);
  EXPECT_EQ(m.torsion, 0.8);
  EXPECT_EQ(m.mate().normal, c.normal);
}

TEST(ContactWrenches, NormalAndFrictionPartsOfAPointContact) {
  const Vector3 cog(1.0, -2.0, 0.5);
  const double max_radius = 40.0;
  const double mu = 0.5;
  const Contact c = makeContact(Vector3(21.0, 3.0, -4.0), Vector3(-1.0, 0.2, 0.1), mu);
  const std::vector<Vector6> wrenches = contactWrenches(c, cog, max_radius);
  ASSERT_EQ(wrenches.size(), 8u);
  const Vector3 r = c.position1 - cog;
  Vector3 force_sum = Vector3::Zero();
  for (const Vector6& w : wrenches) {
    const Vector3 f = w.head<3>();
    EXPECT_NEAR(f.dot(c.normal), 1.0, kConeTolerance);       // unit normal force
    EXPECT_NEAR((f - c.normal).norm(), mu, kConeTolerance);  // friction of size mu
    EXPECT_NEAR((w.tail<3>() - r.cross(f) / max_radius).norm(), 0.0,
                kConeTolerance);  // tau = r x f / R
    force_sum += f;
  }
  EXPECT_NEAR((force_sum - 8.0 * c.normal).norm(), 0.0, 1e-12);
}

TEST(ContactWrenches, ZeroFrictionGivesTheNormalAlone) {
  const Contact c = makeContact(Vector3(0, 0, 10), Vector3(0, 0, -1), 0.0);
  const std::vector<Vector6> wrenches = contactWrenches(c, Vector3::Zero(), 10.0);
  ASSERT_EQ(wrenches.size(), 1u);
  Vector6 expected;
  expected << 0, 0, -1, 0, 0, 0;
  EXPECT_NEAR((wrenches[0] - expected).norm(), 0.0, kConeTolerance);
}

TEST(ContactWrenches, SoftFingerAddsTorsionAboutTheNormal) {
  Contact c = makeContact(Vector3(0, 0, 10), Vector3(0, 0, -1), 0.5, ContactModel::SoftFinger);
  c.torsion = 3.0;
  const double max_radius = 12.0;
  const std::vector<Vector6> wrenches = contactWrenches(c, Vector3::Zero(), max_radius);
  ASSERT_EQ(wrenches.size(), 20u);
  // The poles: pure normal force plus torsion +-mu e_tau about the normal, scaled by 1/R.
  EXPECT_NEAR(wrenches.front().tail<3>().dot(c.normal), 0.5 * 3.0 / max_radius, 1e-12);
  EXPECT_NEAR(wrenches.back().tail<3>().dot(c.normal), -0.5 * 3.0 / max_radius, 1e-12);
}

TEST(ContactWrenches, RejectsANonPositiveMaxRadius) {
  const Contact c = makeContact(Vector3(0, 0, 10), Vector3(0, 0, -1), 0.5);
  EXPECT_THROW(contactWrenches(c, Vector3::Zero(), 0.0), Error);
}

}  // namespace
}  // namespace graspkit
