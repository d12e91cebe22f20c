// Triangle-level contact routines against hand computation: closest points on a triangle in
// each Voronoi region, closest points between segments (closed forms), triangle intersection,
// and GraspIt!'s rule for the point pairs of two nearby triangles.

#include "collision/triangle_contact.hpp"

#include <random>
#include <vector>

#include <gtest/gtest.h>

namespace graspkit::collision {
namespace {

constexpr double kTol = 1e-12;

void expectNear(const Vector3& actual, const Vector3& expected, const char* what = "") {
  EXPECT_LT((actual - expected).norm(), kTol)
      << what << ": " << actual.transpose() << " vs " << expected.transpose();
}

// The right triangle (0,0,0), (1,0,0), (0,1,0) in the plane z = 0.
const Triangle kUnit{Vector3(0, 0, 0), Vector3(1, 0, 0), Vector3(0, 1, 0)};

TEST(ClosestPointOnTriangle, VertexRegions) {
  expectNear(closestPointOnTriangle(kUnit, Vector3(-1, -1, 0.5)), kUnit.a, "a");
  expectNear(closestPointOnTriangle(kUnit, Vector3(2, -0.5, 0)), kUnit.b, "b");
  expectNear(closestPointOnTriangle(kUnit, Vector3(-0.5, 2, 1)), kUnit.c, "c");
}

TEST(ClosestPointOnTriangle, EdgeRegions) {
  // Projection onto the edge's line, which falls inside the edge.
  expectNear(closestPointOnTriangle(kUnit, Vector3(0.3, -1, 2)), Vector3(0.3, 0, 0), "ab");
  expectNear(closestPointOnTriangle(kUnit, Vector3(-2, 0.4, -1)), Vector3(0, 0.4, 0), "ac");
  // Edge bc is x + y = 1: (1, 1, 0.5) projects to (0.5, 0.5, 0).
  expectNear(closestPointOnTriangle(kUnit, Vector3(1, 1, 0.5)), Vector3(0.5, 0.5, 0), "bc");
  expectNear(closestPointOnTriangle(kUnit, Vector3(0.9, 0.3, -3)), Vector3(0.8, 0.2, 0), "bc2");
}

TEST(ClosestPointOnTriangle, FaceRegion) {
  expectNear(closestPointOnTriangle(kUnit, Vector3(0.2, 0.3, 5)), Vector3(0.2, 0.3, 0), "above");
  expectNear(closestPointOnTriangle(kUnit, Vector3(0.2, 0.3, -5)), Vector3(0.2, 0.3, 0), "below");
  // A tilted triangle in the plane x + y + z = 1: a point on the normal through its centroid
  // (1, 1, 1) / 3 projects back to the centroid.
  const Triangle tilted{Vector3(1, 0, 0), Vector3(0, 1, 0), Vector3(0, 0, 1)};
  expectNear(closestPointOnTriangle(tilted, Vector3(1, 1, 1) / 3.0 + Vector3(2, 2, 2)),
             Vector3(1, 1, 1) / 3.0, "tilted");
}

TEST(ClosestPointsOnSegments, Crossing) {
  Vector3 c1, c2;
  const double d2 = closestPointsOnSegments(Vector3(-1, 0, 0), Vector3(1, 0, 0), Vector3(0, -1, 0),
                                            Vector3(0, 1, 0), c1, c2);
  EXPECT_NEAR(d2, 0.0, kTol);
  expectNear(c1, Vector3::Zero(), "c1");
  expectNear(c2, Vector3::Zero(), "c2");
}

TEST(ClosestPointsOnSegments, ParallelOffset) {
  // [0, 2] on the x axis and [1, 3] one unit above: the nearest points are not unique; any
  // x in [1, 2] with c2 = c1 + (0, 0, 1) is right, at squared distance 1.
  Vector3 c1, c2;
  const double d2 = closestPointsOnSegments(Vector3(0, 0, 0), Vector3(2, 0, 0), Vector3(1, 0, 1),
                                            Vector3(3, 0, 1), c1, c2);
  EXPECT_NEAR(d2, 1.0, kTol);
  EXPECT_GE(c1.x(), 1.0 - kTol);
  EXPECT_LE(c1.x(), 2.0 + kTol);
  EXPECT_NEAR(c1.y(), 0.0, kTol);
  EXPECT_NEAR(c1.z(), 0.0, kTol);
  expectNear(c2, c1 + Vector3(0, 0, 1), "c2");
}

TEST(ClosestPointsOnSegments, Skew) {
  // Segment 1: (s, 0, 0), s in [-1, 3]. Segment 2: (1, -2 + 4u, 4u), u in [0, 1]. The squared
  // distance (s - 1)^2 + (4u - 2)^2 + (4u)^2 is least at s = 1, u = 1/4: points (1, 0, 0) and
  // (1, -1, 1), squared distance 2.
  Vector3 c1, c2;
  const double d2 = closestPointsOnSegments(Vector3(-1, 0, 0), Vector3(3, 0, 0), Vector3(1, -2, 0),
                                            Vector3(1, 2, 4), c1, c2);
  EXPECT_NEAR(d2, 2.0, kTol);
  expectNear(c1, Vector3(1, 0, 0), "c1");
  expectNear(c2, Vector3(1, -1, 1), "c2");
}

TEST(ClosestPointsOnSegments, ClampedToEnd) {
  // The lines cross at (2, 0, 0), beyond segment 1's end (1, 0, 0).
  Vector3 c1, c2;
  const double d2 = closestPointsOnSegments(Vector3(0, 0, 0), Vector3(1, 0, 0), Vector3(2, 1, 0),
                                            Vector3(2, -1, 0), c1, c2);
  EXPECT_NEAR(d2, 1.0, kTol);
  expectNear(c1, Vector3(1, 0, 0), "c1");
  expectNear(c2, Vector3(2, 0, 0), "c2");
}

// The right triangle with legs 2 in the plane z = 0.
const Triangle kBase{Vector3(0, 0, 0), Vector3(2, 0, 0), Vector3(0, 2, 0)};

TEST(TrianglesIntersect, Crossing) {
  // In the plane x = 0.5, crossing z = 0 along y in [-1, 0.5], which meets kBase for y in
  // [0, 0.5].
  const Triangle t{Vector3(0.5, 0.5, -1), Vector3(0.5, 0.5, 1), Vector3(0.5, -1, 0)};
  EXPECT_TRUE(trianglesIntersect(kBase, t));
  EXPECT_TRUE(trianglesIntersect(t, kBase));
}

TEST(TrianglesIntersect, Separated) {
  const Triangle t{Vector3(0, 0, 1), Vector3(1, 0, 1), Vector3(0, 1, 1)};
  EXPECT_FALSE(trianglesIntersect(kBase, t));
  EXPECT_FALSE(trianglesIntersect(t, kBase));
  // Its plane crosses kBase's plane, but beyond kBase's hypotenuse.
  const Triangle beside{Vector3(3, 3, -1), Vector3(3, 3, 1), Vector3(4, 2, 0)};
  EXPECT_FALSE(trianglesIntersect(kBase, beside));
}

TEST(TrianglesIntersect, TouchingAtAVertex) {
  // Closed triangles sharing only the point (0, 0, 0).
  const Triangle t{Vector3(0, 0, 0), Vector3(-1, 0, 1), Vector3(0, -1, 1)};
  EXPECT_TRUE(trianglesIntersect(kBase, t));
  EXPECT_TRUE(trianglesIntersect(t, kBase));
}

TEST(TrianglesIntersect, Coplanar) {
  const Triangle overlapping{Vector3(0.5, 0.5, 0), Vector3(3, 0.5, 0), Vector3(0.5, 3, 0)};
  EXPECT_TRUE(trianglesIntersect(kBase, overlapping));
  EXPECT_TRUE(trianglesIntersect(overlapping, kBase));
  // Wholly inside: no edges cross, containment decides.
  const Triangle inside{Vector3(0.2, 0.2, 0), Vector3(0.6, 0.2, 0), Vector3(0.2, 0.6, 0)};
  EXPECT_TRUE(trianglesIntersect(kBase, inside));
  EXPECT_TRUE(trianglesIntersect(inside, kBase));
  const Triangle apart{Vector3(3, 3, 0), Vector3(4, 3, 0), Vector3(3, 4, 0)};
  EXPECT_FALSE(trianglesIntersect(kBase, apart));
  EXPECT_FALSE(trianglesIntersect(apart, kBase));
}

// Whether `pairs` holds (on first, on second) = (p, q), each once at most.
bool hasPair(const std::vector<PointPair>& pairs, const Vector3& p, const Vector3& q) {
  int found = 0;
  for (const PointPair& pair : pairs)
    if ((pair.onFirst - p).norm() < kTol && (pair.onSecond - q).norm() < kTol) ++found;
  return found == 1;
}

constexpr double kThresholdSq = 0.2 * 0.2;

TEST(TriangleContacts, FacingTrianglesAPointOneApartSmallAboveLarge) {
  // t1 in z = 0 facing +z; t2 0.1 above it, facing down (reversed winding), its projection
  // inside t1. t2's corners lie over t1's face: three pairs (projection, corner). t1's corners
  // are at least sqrt(2) from t2; every edge pair is at least 1 apart in the plane.
  const Triangle t1{Vector3(0, 0, 0), Vector3(10, 0, 0), Vector3(0, 10, 0)};
  const Triangle t2{Vector3(1, 1, 0.1), Vector3(1, 3, 0.1), Vector3(3, 1, 0.1)};
  std::vector<PointPair> pairs;
  ASSERT_TRUE(triangleContacts(t1, t2, kThresholdSq, pairs));
  ASSERT_EQ(pairs.size(), 3u);
  for (const Vector3& corner : {t2.a, t2.b, t2.c}) {
    EXPECT_TRUE(hasPair(pairs, corner - Vector3(0, 0, 0.1), corner)) << corner.transpose();
  }
  for (const PointPair& pair : pairs) EXPECT_NEAR((pair.onFirst - pair.onSecond).norm(), 0.1, kTol);
}

TEST(TriangleContacts, FacingTrianglesAPointOneApartSmallBelowLarge) {
  // The other way round: t1's corners lie under t2's face (second rule).
  const Triangle t1{Vector3(1, 1, 0), Vector3(3, 1, 0), Vector3(1, 3, 0)};
  const Triangle t2{Vector3(0, 0, 0.1), Vector3(0, 10, 0.1), Vector3(10, 0, 0.1)};
  std::vector<PointPair> pairs;
  ASSERT_TRUE(triangleContacts(t1, t2, kThresholdSq, pairs));
  ASSERT_EQ(pairs.size(), 3u);
  for (const Vector3& corner : {t1.a, t1.b, t1.c}) {
    EXPECT_TRUE(hasPair(pairs, corner, corner + Vector3(0, 0, 0.1))) << corner.transpose();
  }
}

TEST(TriangleContacts, CongruentFacingTrianglesCountEachCornerOnce) {
  // t2 exactly over t1: t2's corners give three pairs (to t1's corners); t1's corners find
  // t2's corners, already counted; edge pairs meet only at corners.
  const Triangle t1{Vector3(0, 0, 0), Vector3(10, 0, 0), Vector3(0, 10, 0)};
  const Triangle t2{Vector3(0, 0, 0.1), Vector3(0, 10, 0.1), Vector3(10, 0, 0.1)};
  std::vector<PointPair> pairs;
  ASSERT_TRUE(triangleContacts(t1, t2, kThresholdSq, pairs));
  ASSERT_EQ(pairs.size(), 3u);
  for (const Vector3& corner : {t1.a, t1.b, t1.c}) {
    EXPECT_TRUE(hasPair(pairs, corner, corner + Vector3(0, 0, 0.1))) << corner.transpose();
  }
}

TEST(TriangleContacts, CrossedEdgesGiveTheirInteriorPoints) {
  // t1 hangs below the x axis in the plane y = 0; t2 stands 0.1 above the y axis in x = 0.
  // Only their edges along x and y come near: nearest points (0,0,0) and (0,0,0.1).
  const Triangle t1{Vector3(-5, 0, 0), Vector3(5, 0, 0), Vector3(0, 0, -5)};
  const Triangle t2{Vector3(0, -5, 0.1), Vector3(0, 5, 0.1), Vector3(0, 0, 5.1)};
  std::vector<PointPair> pairs;
  ASSERT_TRUE(triangleContacts(t1, t2, kThresholdSq, pairs));
  ASSERT_EQ(pairs.size(), 1u);
  EXPECT_TRUE(hasPair(pairs, Vector3(0, 0, 0), Vector3(0, 0, 0.1)));
}

TEST(TriangleContacts, BeyondTheThresholdGiveNone) {
  const Triangle t1{Vector3(0, 0, 0), Vector3(10, 0, 0), Vector3(0, 10, 0)};
  const Triangle t2{Vector3(1, 1, 0.3), Vector3(1, 3, 0.3), Vector3(3, 1, 0.3)};
  std::vector<PointPair> pairs;
  EXPECT_TRUE(triangleContacts(t1, t2, kThresholdSq, pairs));
  EXPECT_TRUE(pairs.empty());
  EXPECT_TRUE(triangleContacts(t2, t1, kThresholdSq, pairs));
  EXPECT_TRUE(pairs.empty());
}

TEST(TriangleContacts, IntersectingTrianglesReturnFalse) {
  const Triangle t{Vector3(0.5, 0.5, -1), Vector3(0.5, 0.5, 1), Vector3(0.5, -1, 0)};
  std::vector<PointPair> pairs;
  EXPECT_FALSE(triangleContacts(kBase, t, kThresholdSq, pairs));
  EXPECT_FALSE(triangleContacts(t, kBase, kThresholdSq, pairs));
  EXPECT_TRUE(pairs.empty());
}

// Coplanar triangles that overlap touch: GraspIt! counts them as intersecting, the dynamics
// (touching_is_contact) as in contact at distance 0, and so for a tilt within rounding.
TEST(TriangleContacts, CoplanarTouchingIsContactWhenAsked) {
  const Triangle floor{Vector3(-10, -10, 0), Vector3(10, -10, 0), Vector3(0, 10, 0)};
  for (const double tilt : {0.0, 1e-6}) {
    SCOPED_TRACE(tilt);
    const Triangle bottom{Vector3(-1, -1, tilt), Vector3(1, -1, -tilt), Vector3(0, 1, 0)};
    std::vector<PointPair> pairs;
    EXPECT_FALSE(triangleContacts(floor, bottom, kThresholdSq, pairs));
    pairs.clear();
    ASSERT_TRUE(triangleContacts(floor, bottom, kThresholdSq, pairs, true));
    EXPECT_EQ(pairs.size(), 3u);  // the bottom's corners on the floor's face
    for (const PointPair& p : pairs) EXPECT_LT((p.onFirst - p.onSecond).norm(), 1e-5);
  }
  // A wall standing on the floor along an edge touches it: its pairs take the floor's normal
  // (t2's face), a direction apart. Seen the other way the wall's face normal runs along the
  // floor, no direction apart, and those pairs are dropped.
  const Triangle wall{Vector3(-1, 0, 0), Vector3(1, 0, 0), Vector3(0, 0, 2)};
  std::vector<PointPair> on_floor, on_wall;
  ASSERT_TRUE(triangleContacts(wall, floor, kThresholdSq, on_floor, true));
  EXPECT_FALSE(on_floor.empty());
  ASSERT_TRUE(triangleContacts(floor, wall, kThresholdSq, on_wall, true));
  for (const PointPair& p : on_wall) EXPECT_GT((p.onFirst - p.onSecond).norm(), 1e-5);
  // Across by more than the tolerance is interpenetration either way.
  const Triangle through{Vector3(-1, -1, 0.01), Vector3(1, -1, -0.01), Vector3(0, 1, 0)};
  std::vector<PointPair> pairs;
  EXPECT_FALSE(triangleContacts(floor, through, kThresholdSq, pairs, true));
}

// GraspIt!'s rule evaluated literally, with no early rejection: every corner against the other
// face, every edge pair. triangleContacts skips work by plane distances; its pairs must be these.
std::vector<PointPair> contactsByTheRule(const Triangle& t1, const Triangle& t2,
                                         double threshold_sq) {
  auto corner = [](const Triangle& t, const Vector3& p) {
    for (int i = 0; i < 3; ++i)
      if ((t.vertex(i) - p).squaredNorm() < 1e-12) return true;
    return false;
  };
  std::vector<PointPair> pairs;
  for (int i = 0; i < 3; ++i) {
    const Vector3 p = closestPointOnTriangle(t1, t2.vertex(i));
    if ((p - t2.vertex(i)).squaredNorm() < threshold_sq) pairs.push_back({p, t2.vertex(i)});
  }
  for (int i = 0; i < 3; ++i) {
    const Vector3 p = closestPointOnTriangle(t2, t1.vertex(i));
    if ((p - t1.vertex(i)).squaredNorm() < threshold_sq && !corner(t2, p))
      pairs.push_back({t1.vertex(i), p});
  }
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      const Vector3 a1 = t1.vertex(i), b1 = t1.vertex((i + 1) % 3);
      const Vector3 a2 = t2.vertex(j), b2 = t2.vertex((j + 1) % 3);
      Vector3 c1, c2;
      if (closestPointsOnSegments(a1, b1, a2, b2, c1, c2) >= threshold_sq) continue;
      if (corner({a1, b1, b1}, c1) || corner({a2, b2, b2}, c2)) continue;
      pairs.push_back({c1, c2});
    }
  }
  return pairs;
}

TEST(TriangleContacts, RandomNearbyPairsFollowTheRuleLiterally) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  auto point = [&](double spread) -> Vector3 {
    return Vector3(unit(random), unit(random), unit(random)) * spread;
  };
  int with_contacts = 0, intersecting = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const Triangle t1{point(1.0), point(1.0), point(1.0)};
    // The second triangle's corners near the first's plane, some across it.
    const Vector3 n = (t1.b - t1.a).cross(t1.c - t1.a).normalized();
    const double lift = 0.3 * unit(random);
    Triangle t2{point(1.0), point(1.0), point(1.0)};
    for (Vector3* v : {&t2.a, &t2.b, &t2.c}) *v += (lift + 0.2 * unit(random) - n.dot(*v)) * n;
    const double threshold_sq = 0.04;
    std::vector<PointPair> pairs;
    if (!triangleContacts(t1, t2, threshold_sq, pairs)) {
      EXPECT_TRUE(trianglesIntersect(t1, t2));
      ++intersecting;
      continue;
    }
    EXPECT_FALSE(trianglesIntersect(t1, t2)) << "trial " << trial;
    const std::vector<PointPair> expected = contactsByTheRule(t1, t2, threshold_sq);
    ASSERT_EQ(pairs.size(), expected.size()) << "trial " << trial;
    for (std::size_t k = 0; k < pairs.size(); ++k) {
      EXPECT_EQ(pairs[k].onFirst, expected[k].onFirst) << "trial " << trial;
      EXPECT_EQ(pairs[k].onSecond, expected[k].onSecond) << "trial " << trial;
    }
    with_contacts += !pairs.empty();
  }
  // The sample covers all three outcomes, or the comparison above says little.
  EXPECT_GT(with_contacts, 1000);
  EXPECT_GT(intersecting, 1000);
  EXPECT_GT(20000 - with_contacts - intersecting, 1000);
}

}  // namespace
}  // namespace graspkit::collision
