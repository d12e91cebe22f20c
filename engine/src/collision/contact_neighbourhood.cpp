#include "collision/contact_neighbourhood.hpp"

#include <algorithm>

#include "collision/triangle_contact.hpp"
#include "raycast/embree_mesh.hpp"

namespace graspkit::collision {
namespace {

// Cosines within this of 0 count as square (about 2e-7 degrees).
constexpr double kSquareCosine = 1e-9;
// Distances within this count as equal when merging (mm): rounding must not pick the survivor.
constexpr double kSameDistance = 1e-9;

bool lexicographicLess(const Vector3& p, const Vector3& q) {
  return std::lexicographical_compare(p.data(), p.data() + 3, q.data(), q.data() + 3);
}

std::size_t sortedPrefix(const Neighbourhood& points) {
  return static_cast<std::size_t>(
      std::is_sorted_until(points.begin(), points.end(), lexicographicLess) - points.begin());
}

// Whether `points` holds p. Points are kept sorted up to the contact point, which comes next,
// followed by any merged in: bisect the sorted prefix, scan the rest.
bool holds(const Neighbourhood& points, std::size_t sorted, const Vector3& p) {
  const auto sorted_end = points.begin() + static_cast<std::ptrdiff_t>(sorted);
  const auto it = std::lower_bound(points.begin(), sorted_end, p, lexicographicLess);
  if (it != sorted_end && *it == p) return true;
  return std::find(sorted_end, points.end(), p) != points.end();
}

// Appends the points of `from` that `into` lacks (GraspIt!'s mergeNeighborhoods).
void absorb(Neighbourhood& into, const Neighbourhood& from) {
  const std::size_t sorted = sortedPrefix(into);
  for (const Vector3& p : from)
    if (!holds(into, sorted, p)) into.push_back(p);
}

}  // namespace

Neighbourhood surfaceNeighbourhood(const raycast::EmbreeMesh& mesh, const Vector3& point,
                                   const Vector3& inward, double radius) {
  const TriangleMesh& surface = mesh.mesh();
  const double radius_sq = radius * radius;
  std::vector<unsigned> corners;
  mesh.forEachTriangleNear(point, radius, [&](unsigned index) {
    const auto& t = surface.triangles[index];
    const Triangle triangle{surface.vertices[t[0]], surface.vertices[t[1]], surface.vertices[t[2]]};
    // Faces turned towards the inward normal belong to the other side of a thin part. GraspIt!
    // drops them when the cosine is above 0; a face square to the normal (a box's side) would
    // then come and go with the last bit of the normal, so the cut is a hair above 0 here.
    const Vector3 face = (triangle.b - triangle.a).cross(triangle.c - triangle.a);
    if (face.dot(inward) > kSquareCosine * face.norm() * inward.norm()) return;
    if ((closestPointOnTriangle(triangle, point) - point).squaredNorm() > radius_sq) return;
    corners.insert(corners.end(), {t[0], t[1], t[2]});
  });
  // Each position once, whichever vertex indices carry it (GraspIt! compares positions).
  Neighbourhood points;
  points.reserve(corners.size() + 1);
  for (unsigned v : corners) points.push_back(surface.vertices[v]);
  std::sort(points.begin(), points.end(), lexicographicLess);
  points.erase(std::unique(points.begin(), points.end()), points.end());
  points.push_back(point);
  return points;
}

bool neighbourhoodsOverlap(const Neighbourhood& a, const Neighbourhood& b) {
  const Neighbourhood& small = a.size() <= b.size() ? a : b;
  const Neighbourhood& large = a.size() <= b.size() ? b : a;
  const std::size_t sorted = sortedPrefix(large);
  return std::any_of(small.begin(), small.end(),
                     [&](const Vector3& p) { return holds(large, sorted, p); });
}

void mergeOverlappingPatches(std::vector<PatchCandidate>& candidates) {
  // GraspIt! restarts its scan after every merge; so do we, so the survivors are its own.
  for (bool merged = true; merged;) {
    merged = false;
    for (std::size_t i = 0; i < candidates.size() && !merged; ++i) {
      for (std::size_t j = 0; j < candidates.size() && !merged; ++j) {
        if (i == j || !neighbourhoodsOverlap(candidates[i].onFirst, candidates[j].onFirst))
          continue;
        const bool keep_i = candidates[i].distance < candidates[j].distance - kSameDistance;
        PatchCandidate& survivor = keep_i ? candidates[i] : candidates[j];
        const PatchCandidate& gone = keep_i ? candidates[j] : candidates[i];
        absorb(survivor.onFirst, gone.onFirst);
        absorb(survivor.onSecond, gone.onSecond);
        candidates.erase(candidates.begin() + static_cast<std::ptrdiff_t>(keep_i ? j : i));
        merged = true;
      }
    }
  }
}

}  // namespace graspkit::collision
