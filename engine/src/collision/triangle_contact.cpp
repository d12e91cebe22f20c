#include "collision/triangle_contact.hpp"

#include <algorithm>
#include <cmath>

namespace graspkit::collision {
namespace {

// Points this close count as the same corner (GraspIt! compares positions with a tolerance).
constexpr double kSamePointSq = 1e-12;

bool samePoint(const Vector3& p, const Vector3& q) {
  return (p - q).squaredNorm() < kSamePointSq;
}

bool isCorner(const Triangle& t, const Vector3& p) {
  return samePoint(p, t.a) || samePoint(p, t.b) || samePoint(p, t.c);
}

// The plane of a triangle and the signed distances of another triangle's corners from it, in
// units of the normal's length (n is not normalised: the tests below only compare signs and
// scaled thresholds, which saves a square root per test).
struct PlaneDistances {
  Vector3 n;
  double norm_sq = 0.0;
  double norm = 0.0;
  double d[3] = {0.0, 0.0, 0.0};
};

PlaneDistances planeDistances(const Triangle& plane, const Triangle& t) {
  PlaneDistances out;
  out.n = (plane.b - plane.a).cross(plane.c - plane.a);
  out.norm_sq = out.n.squaredNorm();
  out.norm = std::sqrt(out.norm_sq);
  out.d[0] = out.n.dot(t.a - plane.a);
  out.d[1] = out.n.dot(t.b - plane.a);
  out.d[2] = out.n.dot(t.c - plane.a);
  return out;
}

// Does segment [p, q] meet triangle t (closed)? dp and dq are the ends' signed distances from
// t's plane, whose normal n (not normalised) has length `scale`. Non-coplanar case by the plane
// crossing, the coplanar case by the segment against the triangle's edges and containment.
bool segmentMeetsTriangle(const Vector3& p, const Vector3& q, double dp, double dq,
                          const Triangle& t, const Vector3& n, double scale) {
  if (scale == 0.0) return false;  // degenerate triangle: no area to meet
  dp /= scale;
  dq /= scale;
  constexpr double kFlat = 1e-12;
  if ((dp > kFlat && dq > kFlat) || (dp < -kFlat && dq < -kFlat)) return false;
  auto inside = [&](const Vector3& x) {
    return n.dot((t.b - t.a).cross(x - t.a)) >= 0 && n.dot((t.c - t.b).cross(x - t.b)) >= 0 &&
           n.dot((t.a - t.c).cross(x - t.c)) >= 0;
  };
  if (std::abs(dp) <= kFlat && std::abs(dq) <= kFlat) {
    // Coplanar: they meet if an end lies inside or the segment crosses an edge.
    if (inside(p) || inside(q)) return true;
    Vector3 c1, c2;
    for (int i = 0; i < 3; ++i) {
      if (closestPointsOnSegments(p, q, t.vertex(i), t.vertex((i + 1) % 3), c1, c2) < kSamePointSq)
        return true;
    }
    return false;
  }
  const double s = dp / (dp - dq);
  return inside(p + s * (q - p));
}

// Whether the triangles share a point, given each one's corners' distances from the other's
// plane (on1: t1's corners from t2's plane; on2: t2's corners from t1's plane).
bool trianglesIntersect(const Triangle& t1, const Triangle& t2, const PlaneDistances& on1,
                        const PlaneDistances& on2) {
  // Two triangles share a point iff an edge of one meets the other.
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    if (segmentMeetsTriangle(t1.vertex(i), t1.vertex(j), on1.d[i], on1.d[j], t2, on1.n, on1.norm))
      return true;
    if (segmentMeetsTriangle(t2.vertex(i), t2.vertex(j), on2.d[i], on2.d[j], t1, on2.n, on2.norm))
      return true;
  }
  return false;
}

enum class SideTest { Far, OneSide, Straddles };

// Where a triangle lies relative to a plane: entirely farther than the threshold on one side,
// entirely on one side, or touching or crossing it.
SideTest sideOf(const PlaneDistances& plane, double threshold_sq) {
  if (plane.norm_sq == 0.0) return SideTest::Straddles;  // degenerate: no plane to test against
  const double reach = std::sqrt(threshold_sq * plane.norm_sq);
  const double* d = plane.d;
  if ((d[0] >= reach && d[1] >= reach && d[2] >= reach) ||
      (d[0] <= -reach && d[1] <= -reach && d[2] <= -reach))
    return SideTest::Far;
  if ((d[0] > 0 && d[1] > 0 && d[2] > 0) || (d[0] < 0 && d[1] < 0 && d[2] < 0))
    return SideTest::OneSide;
  return SideTest::Straddles;
}

// Whether a point at plane distance d (unnormalised) is surely beyond the threshold from
// anything on the plane's triangle: the distance to a triangle is at least the distance to its
// plane. The factor keeps the shortcut off the borderline, where rounding could decide.
// Whether a triangle crosses a plane by more than rounding: corners farther than
// kTouchingTolerance on both sides.
bool crosses(const PlaneDistances& plane) {
  const double tolerance = kTouchingTolerance * plane.norm;
  const double* d = plane.d;
  return std::max({d[0], d[1], d[2]}) > tolerance && std::min({d[0], d[1], d[2]}) < -tolerance;
}

bool beyondReach(double d, const PlaneDistances& plane, double threshold_sq) {
  return plane.norm_sq > 0.0 && d * d > threshold_sq * plane.norm_sq * (1.0 + 1e-9);
}

}  // namespace

Vector3 closestPointOnTriangle(const Triangle& t, const Vector3& p) {
  // Ericson, Real-Time Collision Detection, 5.1.5: find the Voronoi region of p.
  const Vector3 ab = t.b - t.a, ac = t.c - t.a, ap = p - t.a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return t.a;
  const Vector3 bp = p - t.b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return t.b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return t.a + (d1 / (d1 - d3)) * ab;
  const Vector3 cp = p - t.c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return t.c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return t.a + (d2 / (d2 - d6)) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return t.b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (t.c - t.b);
  const double sum = va + vb + vc;
  if (sum <= 0) return t.a;  // degenerate triangle
  return t.a + ab * (vb / sum) + ac * (vc / sum);
}

double closestPointsOnSegments(const Vector3& p1, const Vector3& q1, const Vector3& p2,
                               const Vector3& q2, Vector3& c1, Vector3& c2) {
  // Ericson 5.1.9: minimise |(p1 + s d1) - (p2 + t d2)| over s, t in [0, 1].
  const Vector3 d1 = q1 - p1, d2 = q2 - p2, r = p1 - p2;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  constexpr double kTiny = 1e-18;
  double s = 0, t = 0;
  if (a <= kTiny && e <= kTiny) {
    s = t = 0;
  } else if (a <= kTiny) {
    t = std::clamp(f / e, 0.0, 1.0);
  } else {
    const double c = d1.dot(r);
    if (e <= kTiny) {
      s = std::clamp(-c / a, 0.0, 1.0);
    } else {
      const double b = d1.dot(d2), denom = a * e - b * b;
      s = denom > 0 ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
      t = (b * s + f) / e;
      if (t < 0) {
        t = 0;
        s = std::clamp(-c / a, 0.0, 1.0);
      } else if (t > 1) {
        t = 1;
        s = std::clamp((b - c) / a, 0.0, 1.0);
      }
    }
  }
  c1 = p1 + s * d1;
  c2 = p2 + t * d2;
  return (c1 - c2).squaredNorm();
}

bool trianglesIntersect(const Triangle& t1, const Triangle& t2) {
  return trianglesIntersect(t1, t2, planeDistances(t2, t1), planeDistances(t1, t2));
}

bool triangleContacts(const Triangle& t1, const Triangle& t2, double threshold_sq,
                      std::vector<PointPair>& pairs, bool touching_is_contact) {
  // Cheap rejections first: a triangle wholly beyond the threshold on one side of the other's
  // plane has no contact with it, and one wholly on one side cannot intersect it.
  const PlaneDistances on2 = planeDistances(t1, t2);  // t2's corners from t1's plane
  const SideTest side2 = sideOf(on2, threshold_sq);
  if (side2 == SideTest::Far) return true;
  const PlaneDistances on1 = planeDistances(t2, t1);  // t1's corners from t2's plane
  const SideTest side1 = sideOf(on1, threshold_sq);
  if (side1 == SideTest::Far) return true;
  bool may_intersect = side1 == SideTest::Straddles && side2 == SideTest::Straddles;
  if (touching_is_contact) may_intersect = may_intersect && crosses(on1) && crosses(on2);
  if (may_intersect && trianglesIntersect(t1, t2, on1, on2)) return false;
  const std::size_t first_pair = pairs.size();
  for (int i = 0; i < 3; ++i) {
    if (beyondReach(on2.d[i], on2, threshold_sq)) continue;
    const Vector3 v = t2.vertex(i);
    const Vector3 p = closestPointOnTriangle(t1, v);
    if ((p - v).squaredNorm() < threshold_sq) pairs.push_back({p, v});
  }
  for (int i = 0; i < 3; ++i) {
    if (beyondReach(on1.d[i], on1, threshold_sq)) continue;
    const Vector3 v = t1.vertex(i);
    const Vector3 p = closestPointOnTriangle(t2, v);
    if ((p - v).squaredNorm() < threshold_sq && !isCorner(t2, p)) pairs.push_back({v, p});
  }
  const double reach = std::sqrt(threshold_sq);
  for (int i = 0; i < 3; ++i) {
    const int i_next = (i + 1) % 3;
    // An edge beyond the threshold on one side of the other's plane is that far from its edges.
    if (beyondReach(on1.d[i], on1, threshold_sq) && beyondReach(on1.d[i_next], on1, threshold_sq) &&
        (on1.d[i] > 0) == (on1.d[i_next] > 0))
      continue;
    const Vector3 a1 = t1.vertex(i), b1 = t1.vertex(i_next);
    for (int j = 0; j < 3; ++j) {
      const int j_next = (j + 1) % 3;
      if (beyondReach(on2.d[j], on2, threshold_sq) &&
          beyondReach(on2.d[j_next], on2, threshold_sq) && (on2.d[j] > 0) == (on2.d[j_next] > 0))
        continue;
      const Vector3 a2 = t2.vertex(j), b2 = t2.vertex(j_next);
      // Edges whose boxes stay farther apart than the threshold need no closest points.
      if ((a1.cwiseMin(b1).array() > a2.cwiseMax(b2).array() + reach).any() ||
          (a2.cwiseMin(b2).array() > a1.cwiseMax(b1).array() + reach).any())
        continue;
      Vector3 c1, c2;
      if (closestPointsOnSegments(a1, b1, a2, b2, c1, c2) >= threshold_sq) continue;
      if (samePoint(c1, a1) || samePoint(c1, b1) || samePoint(c2, a2) || samePoint(c2, b2))
        continue;
      pairs.push_back({c1, c2});
    }
  }
  // A touching pair takes t2's face normal (the contact search's rule for points at distance
  // 0), which is a direction apart only if t1 lies on t2's outer side: a face meeting another
  // along an edge at right angles touches it there too, but its normal points along the other.
  if (touching_is_contact && on1.norm_sq > 0.0 &&
      std::min({on1.d[0], on1.d[1], on1.d[2]}) < -kTouchingTolerance * on1.norm) {
    constexpr double kTouchingSq = kTouchingTolerance * kTouchingTolerance;
    pairs.erase(std::remove_if(pairs.begin() + static_cast<std::ptrdiff_t>(first_pair), pairs.end(),
                               [](const PointPair& p) {
                                 return (p.onFirst - p.onSecond).squaredNorm() < kTouchingSq;
                               }),
                pairs.end());
  }
  return true;
}

}  // namespace graspkit::collision
