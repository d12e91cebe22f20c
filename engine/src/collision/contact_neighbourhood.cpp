#include "collision/contact_neighbourhood.hpp"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>
#include <unordered_map>

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

// Exact positions as hash keys; -0 and +0 are one position, as == says.
struct PointHash {
  std::size_t operator()(const Vector3& p) const {
    std::uint64_t h = 0;
    for (int i = 0; i < 3; ++i) {
      const double v = p[i] + 0.0;
      std::uint64_t bits = 0;
      std::memcpy(&bits, &v, sizeof bits);
      h = (h ^ bits) * 0x9E3779B97F4A7C15ull;
      h ^= h >> 29;
    }
    return static_cast<std::size_t>(h);
  }
};

// Which candidates' neighbourhoods on the first body share a point: a symmetric bit matrix,
// n x n bits (a few MB for thousands of contacts).
class OverlapMatrix {
 public:
  explicit OverlapMatrix(std::size_t n) : n_(n), words_((n + 63) / 64), bits_(n * words_, 0) {}

  void orRow(std::size_t i, const std::vector<std::uint64_t>& mask) {
    std::uint64_t* r = row(i);
    for (std::size_t w = 0; w < words_; ++w) r[w] |= mask[w];
    clear(i, i);
  }
  // The lowest candidate overlapping i, or n when none does.
  std::size_t first(std::size_t i) const {
    const std::uint64_t* r = row(i);
    for (std::size_t w = 0; w < words_; ++w)
      if (r[w]) return w * 64 + static_cast<std::size_t>(std::countr_zero(r[w]));
    return n_;
  }
  // `survivor` takes over every overlap of `gone`, which leaves the matrix.
  void merge(std::size_t survivor, std::size_t gone) {
    std::uint64_t* s = row(survivor);
    const std::uint64_t* g = row(gone);
    for (std::size_t w = 0; w < words_; ++w) {
      s[w] |= g[w];
      for (std::uint64_t bits = g[w]; bits; bits &= bits - 1) {
        const std::size_t k = w * 64 + static_cast<std::size_t>(std::countr_zero(bits));
        set(k, survivor);
        clear(k, gone);
      }
    }
    clear(survivor, survivor);
    clear(survivor, gone);
    std::fill(row(gone), row(gone) + words_, 0);
  }

 private:
  std::uint64_t* row(std::size_t i) { return bits_.data() + i * words_; }
  const std::uint64_t* row(std::size_t i) const { return bits_.data() + i * words_; }
  void set(std::size_t i, std::size_t j) { row(i)[j / 64] |= std::uint64_t{1} << (j % 64); }
  void clear(std::size_t i, std::size_t j) { row(i)[j / 64] &= ~(std::uint64_t{1} << (j % 64)); }

  std::size_t n_, words_;
  std::vector<std::uint64_t> bits_;
};

OverlapMatrix overlapsOnFirst(const std::vector<PatchCandidate>& candidates) {
  const std::size_t n = candidates.size();
  std::unordered_map<Vector3, std::vector<std::size_t>, PointHash> holders;
  for (std::size_t i = 0; i < n; ++i)
    for (const Vector3& p : candidates[i].onFirst) {
      auto& list = holders[p];
      if (list.empty() || list.back() != i) list.push_back(i);
    }
  OverlapMatrix overlaps(n);
  std::vector<std::uint64_t> mask((n + 63) / 64);
  for (const auto& [point, list] : holders) {
    if (list.size() < 2) continue;
    std::fill(mask.begin(), mask.end(), 0);
    for (std::size_t i : list) mask[i / 64] |= std::uint64_t{1} << (i % 64);
    for (std::size_t i : list) overlaps.orRow(i, mask);
  }
  return overlaps;
}

// Every point of `members`' neighbourhoods (one side), each once.
Neighbourhood pooled(const std::vector<PatchCandidate>& candidates,
                     const std::vector<std::size_t>& members, Neighbourhood PatchCandidate::*side) {
  if (members.size() == 1) return candidates[members.front()].*side;
  Neighbourhood points;
  for (std::size_t m : members)
    points.insert(points.end(), (candidates[m].*side).begin(), (candidates[m].*side).end());
  std::sort(points.begin(), points.end(), lexicographicLess);
  points.erase(std::unique(points.begin(), points.end()), points.end());
  return points;
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

void mergeOverlappingPatches(std::vector<PatchCandidate>& candidates) {
  // GraspIt! takes the first contact (in order) that overlaps any other, and the first one it
  // overlaps; the nearer keeps both patches, the other goes; then it starts again. The same
  // sequence here, without the rescans: a merged patch overlaps exactly what its two parts
  // did, and a contact that overlapped nothing never comes to (its neighbours would have had
  // to overlap it), so the search for the next first contact resumes where it stood.
  const std::size_t n = candidates.size();
  OverlapMatrix overlaps = overlapsOnFirst(candidates);
  std::vector<std::vector<std::size_t>> members(n);
  for (std::size_t i = 0; i < n; ++i) members[i] = {i};
  std::vector<bool> gone(n, false);
  for (std::size_t i = 0; i < n;) {
    const std::size_t j = gone[i] ? n : overlaps.first(i);
    if (j == n) {
      ++i;
      continue;
    }
    const bool keep_i = candidates[i].distance < candidates[j].distance - kSameDistance;
    const std::size_t survivor = keep_i ? i : j, loser = keep_i ? j : i;
    overlaps.merge(survivor, loser);
    members[survivor].insert(members[survivor].end(), members[loser].begin(), members[loser].end());
    gone[loser] = true;
  }
  std::vector<PatchCandidate> survivors;
  for (std::size_t i = 0; i < n; ++i) {
    if (gone[i]) continue;
    PatchCandidate c = candidates[i];
    c.onFirst = pooled(candidates, members[i], &PatchCandidate::onFirst);
    c.onSecond = pooled(candidates, members[i], &PatchCandidate::onSecond);
    survivors.push_back(std::move(c));
  }
  candidates = std::move(survivors);
}

}  // namespace graspkit::collision
