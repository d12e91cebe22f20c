#include "geometry/hull_distance.hpp"

#include <array>
#include <limits>
#include <utility>

namespace graspkit::geometry {
namespace {

// The vertex of a hull farthest along d.
Vector3 supportOf(const Eigen::Matrix3Xd& vertices, const Vector3& d) {
  Eigen::Index farthest = 0;
  (d.transpose() * vertices).maxCoeff(&farthest);
  return vertices.col(farthest);
}

// The points of A - B that GJK keeps: a point, a segment, a triangle or a tetrahedron.
struct Simplex {
  std::array<Vector3, 4> w;
  int size = 0;
  void keep(std::initializer_list<Vector3> points) {
    size = 0;
    for (const Vector3& p : points) w[static_cast<std::size_t>(size++)] = p;
  }
};

// Each nearest* function returns the simplex's point nearest the origin and reduces the simplex to
// the face that point lies on, so the next support point is added to the fewest points.

Vector3 nearestOnSegment(Simplex& s) {
  const Vector3 a = s.w[0], b = s.w[1], ab = b - a;
  const double t = -a.dot(ab), length2 = ab.squaredNorm();
  if (t <= 0) {
    s.keep({a});
    return a;
  }
  if (t >= length2) {
    s.keep({b});
    return b;
  }
  return a + (t / length2) * ab;
}

// Ericson's Voronoi-region walk (5.1.5) with the query point at the origin.
Vector3 nearestOnTriangle(Simplex& s) {
  const Vector3 a = s.w[0], b = s.w[1], c = s.w[2];
  const Vector3 ab = b - a, ac = c - a;
  const double d1 = -ab.dot(a), d2 = -ac.dot(a);
  if (d1 <= 0 && d2 <= 0) return s.keep({a}), a;
  const double d3 = -ab.dot(b), d4 = -ac.dot(b);
  if (d3 >= 0 && d4 <= d3) return s.keep({b}), b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return s.keep({a, b}), a + (d1 / (d1 - d3)) * ab;
  const double d5 = -ab.dot(c), d6 = -ac.dot(c);
  if (d6 >= 0 && d5 <= d6) return s.keep({c}), c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return s.keep({a, c}), a + (d2 / (d2 - d6)) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0)
    return s.keep({b, c}), b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b);
  const double area = va + vb + vc;
  if (!(area > 0)) {  // a sliver: its nearest edge is all it has
    std::pair<Vector3, Vector3> best{a, b};
    double best2 = std::numeric_limits<double>::infinity();
    for (const auto& edge : {std::pair{a, b}, std::pair{a, c}, std::pair{b, c}}) {
      s.keep({edge.first, edge.second});
      if (const double d2 = nearestOnSegment(s).squaredNorm(); d2 < best2) best2 = d2, best = edge;
    }
    s.keep({best.first, best.second});
    return nearestOnSegment(s);
  }
  return a + (vb / area) * ab + (vc / area) * ac;
}

// The nearest of the faces that the origin lies outside of; none when it is inside them all.
std::optional<Vector3> nearestOnTetrahedron(Simplex& s) {
  const Vector3 a = s.w[0], b = s.w[1], c = s.w[2], d = s.w[3];
  const std::array<std::array<Vector3, 4>, 4> faces = {
      {{a, b, c, d}, {a, c, d, b}, {a, d, b, c}, {b, d, c, a}}};  // three, then opposite
  std::optional<Vector3> nearest;
  std::array<Vector3, 3> best{a, b, c};
  for (const auto& [p, q, r, opposite] : faces) {
    const Vector3 normal = (q - p).cross(r - p);
    const double origin_side = -normal.dot(p), opposite_side = normal.dot(opposite - p);
    // Outside this face, or a flat tetrahedron whose faces must all be tried.
    if (!(origin_side * opposite_side < 0 || opposite_side == 0)) continue;
    s.keep({p, q, r});
    const Vector3 point = nearestOnTriangle(s);
    if (!nearest || point.squaredNorm() < nearest->squaredNorm()) nearest = point, best = {p, q, r};
  }
  if (nearest) {  // reduced again, now for the nearest face
    s.keep({best[0], best[1], best[2]});
    nearestOnTriangle(s);
  } else {
    s.keep({a, b, c, d});
  }
  return nearest;
}

}  // namespace

std::optional<Vector3> nearestDifference(const ConvexHull& a, const ConvexHull& b,
                                         const Transform& b_in_a, const Vector3& start) {
  const Matrix3 rotation = b_in_a.linear();
  const Vector3 translation = b_in_a.translation();
  auto support = [&](const Vector3& d) -> Vector3 {
    return supportOf(a.vertices, d) -
           (rotation * supportOf(b.vertices, rotation.transpose() * -d) + translation);
  };
  // Touching, to rounding: no axis separates them.
  constexpr double kTouching2 = 1e-20;
  // Converged once the support point along -v lies within this fraction of |v| of v's plane:
  // the hulls' distance is known to 1e-6 of itself, FCL's distance tolerance.
  constexpr double kRelativeTolerance = 1e-6;
  constexpr int kMaxIterations = 64;

  Simplex simplex;
  const bool usable = start.allFinite() && start.squaredNorm() > 0;
  simplex.keep({support(usable ? Vector3(-start) : Vector3(-Vector3::UnitX()))});
  Vector3 v = simplex.w[0];
  for (int iteration = 0; iteration < kMaxIterations; ++iteration) {
    const double v2 = v.squaredNorm();
    if (!(v2 > kTouching2)) return std::nullopt;  // also NaN
    const Vector3 w = support(-v);
    if (v2 - v.dot(w) <= kRelativeTolerance * v2) return v;  // no support point beyond v's plane
    for (int i = 0; i < simplex.size; ++i)
      if (simplex.w[static_cast<std::size_t>(i)] == w) return v;  // nothing new to add
    simplex.w[static_cast<std::size_t>(simplex.size++)] = w;
    Vector3 next;
    switch (simplex.size) {
      case 2:
        next = nearestOnSegment(simplex);
        break;
      case 3:
        next = nearestOnTriangle(simplex);
        break;
      default: {
        const auto outside = nearestOnTetrahedron(simplex);
        if (!outside) return std::nullopt;  // the origin is inside: the hulls overlap
        next = *outside;
      }
    }
    if (!(next.squaredNorm() < v2)) return v;  // rounding stalled it; v is as near as it gets
    v = next;
  }
  return v;
}

}  // namespace graspkit::geometry
