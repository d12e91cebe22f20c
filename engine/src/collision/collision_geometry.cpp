// The process-wide cache of collision geometry, one entry per live mesh. Meshes are immutable and
// shared by every world, clone and link that shows them, so their BVHs can be too: a planner's
// clones on several threads all read the same hierarchy.

#include "collision/collision_geometry.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <mutex>
#include <shared_mutex>
#include <unordered_map>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "collision/surface_area_splitter.hpp"
#include "geometry/hull_distance.hpp"
#include "graspkit/base/error.hpp"

namespace graspkit {
namespace {

// The triangles' closed parts (groups joined by shared vertices), each as its vertices.
std::vector<std::vector<Vector3>> closedParts(const TriangleMesh& mesh,
                                              const std::vector<fcl::Triangle>& triangles) {
  std::vector<std::uint32_t> root(mesh.vertices.size());
  for (std::uint32_t v = 0; v < root.size(); ++v) root[v] = v;
  const auto find = [&](std::uint32_t v) {
    while (root[v] != v) v = root[v] = root[root[v]];
    return v;
  };
  for (const fcl::Triangle& tri : triangles)
    for (int k = 1; k < 3; ++k)
      root[find(static_cast<std::uint32_t>(tri[k]))] = find(static_cast<std::uint32_t>(tri[0]));
  std::unordered_map<std::uint32_t, std::size_t> index;  // a part's root: its place in `parts`
  std::vector<std::vector<Vector3>> parts;
  std::vector<char> seen(mesh.vertices.size(), 0);
  for (const fcl::Triangle& tri : triangles)
    for (int k = 0; k < 3; ++k) {
      const auto v = static_cast<std::uint32_t>(tri[k]);
      if (seen[v]) continue;
      seen[v] = 1;
      const auto [it, added] = index.try_emplace(find(v), parts.size());
      if (added) parts.emplace_back();
      parts[it->second].push_back(mesh.vertices[v]);
    }
  return parts;
}

// The hulls of a mesh's closed parts, when it has 2 to kMaxHullParts of them and every one has
// volume (a flat part, a decal, has no hull to prove anything with); none otherwise.
std::vector<HullPart> hullParts(const TriangleMesh& mesh,
                                const std::vector<fcl::Triangle>& triangles) {
  const std::vector<std::vector<Vector3>> parts = closedParts(mesh, triangles);
  if (parts.size() < 2 || parts.size() > static_cast<std::size_t>(kMaxHullParts)) return {};
  std::vector<HullPart> hulls;
  for (const std::vector<Vector3>& points : parts) {
    std::optional<geometry::ConvexHull> hull = geometry::convexHull(points);
    if (!hull) return {};
    Eigen::AlignedBox3d box;
    for (const Vector3& p : points) box.extend(p);
    hulls.push_back({std::move(*hull), box.center(), 0.5 * box.sizes()});
  }
  return hulls;
}

std::shared_ptr<const CollisionGeometry> build(const TriangleMesh& mesh) {
  const std::size_t vertex_count = mesh.vertices.size();
  std::vector<fcl::Triangle> triangles;
  triangles.reserve(mesh.triangles.size());
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& tri = mesh.triangles[t];
    for (std::uint32_t v : tri) {
      if (v >= vertex_count) {
        throw Error(fmt::format("mesh triangle {} names vertex {}, the mesh has {} vertices", t, v,
                                vertex_count));
      }
    }
    // A zero-area triangle has no surface to hit, and its bounding volume has no well-defined
    // orientation; leave it out of the hierarchy.
    const Vector3& a = mesh.vertices[tri[0]];
    const Vector3 normal = (mesh.vertices[tri[1]] - a).cross(mesh.vertices[tri[2]] - a);
    if (!(normal.squaredNorm() > 0.0) || !normal.allFinite()) continue;
    triangles.emplace_back(tri[0], tri[1], tri[2]);
  }
  if (triangles.empty()) return nullptr;

  auto bvh = std::make_shared<Bvh>();
  // FCL cuts each node's longest axis at the triangles' mean centre; the surface-area rule's
  // trees cost about half as much to descend where a finger rests on the mug (collision_bench).
  bvh->bv_splitter = std::make_shared<collision::SurfaceAreaSplitter>();
  bvh->beginModel(static_cast<int>(triangles.size()), static_cast<int>(vertex_count));
  bvh->addSubModel(mesh.vertices, triangles);
  bvh->endModel();

  Eigen::AlignedBox3d box;
  std::vector<char> used(vertex_count, 0);
  std::vector<Vector3> points;  // the vertices of the kept triangles, once each
  for (const fcl::Triangle& tri : triangles)
    for (int k = 0; k < 3; ++k) {
      box.extend(mesh.vertices[tri[k]]);
      if (!used[tri[k]]) points.push_back(mesh.vertices[tri[k]]);
      used[tri[k]] = 1;
    }
  auto geometry = std::make_shared<CollisionGeometry>();
  geometry->bvh = std::move(bvh);
  geometry->boxCenter = box.center();
  geometry->boxHalfSize = 0.5 * box.sizes();
  geometry->hull = geometry::convexHull(points);
  if (geometry->hull) geometry->parts = hullParts(mesh, triangles);
  return geometry;
}

struct Entry {
  std::weak_ptr<const TriangleMesh> mesh;  // expired: the address may now be another mesh's
  std::shared_ptr<const CollisionGeometry> geometry;
};

class Cache {
 public:
  std::shared_ptr<const CollisionGeometry> get(const std::shared_ptr<const TriangleMesh>& mesh) {
    {
      std::shared_lock lock(mutex_);
      auto it = entries_.find(mesh.get());
      if (it != entries_.end() && !it->second.mesh.expired()) return it->second.geometry;
    }
    // Build outside the lock so other meshes' queries proceed; if two threads race on one mesh,
    // the first to insert wins and both return its geometry.
    auto geometry = build(*mesh);
    std::unique_lock lock(mutex_);
    auto [it, inserted] = entries_.try_emplace(mesh.get(), Entry{mesh, geometry});
    if (!inserted) {
      if (!it->second.mesh.expired()) return it->second.geometry;
      it->second = Entry{mesh, geometry};
    }
    if (++inserts_since_prune_ >= 64) prune();
    return geometry;
  }

 private:
  void prune() {
    std::erase_if(entries_, [](const auto& kv) { return kv.second.mesh.expired(); });
    inserts_since_prune_ = 0;
  }

  std::shared_mutex mutex_;
  std::unordered_map<const TriangleMesh*, Entry> entries_;
  int inserts_since_prune_ = 0;
};

Cache& cache() {
  static Cache instance;  // built on first use, thread-safe since C++11
  return instance;
}

}  // namespace

namespace {

// A hull and the box of the points it wraps: a whole mesh's or one of its parts'.
struct Shape {
  const geometry::ConvexHull& hull;
  const Vector3& boxCenter;
  const Vector3& boxHalfSize;
};

Shape wholeOf(const CollisionGeometry& g) {
  return {*g.hull, g.boxCenter, g.boxHalfSize};
}
Shape partOf(const HullPart& part) {
  return {part.hull, part.boxCenter, part.boxHalfSize};
}

// The largest extent of a placed hull along a world direction.
double support(const geometry::ConvexHull& hull, const Transform& pose, const Vector3& direction) {
  const Vector3 local = pose.linear().transpose() * direction;
  return (local.transpose() * hull.vertices).maxCoeff() + direction.dot(pose.translation());
}

// The width of the slab between a's hull and b's across world axis n (unit): how far below the
// lowest vertex of b's hull the highest of a's lies. Positive: the hulls are apart by at least
// that much.
double slabGap(const Vector3& n, const Shape& a, const Transform& pose_a, const Shape& b,
               const Transform& pose_b) {
  return -support(b.hull, pose_b, -n) - support(a.hull, pose_a, n);
}

// How far any vertex of `geometry`'s hull can have moved between two poses of its body: the
// hull lies in the sphere of its box (centre c, radius r), whose centre moved by |to c - from c|
// and whose rim turned by at most ||R_to - R_from||_2 r = sqrt(3 - tr(R_from^T R_to)) r.
double displacement(const Shape& geometry, const Transform& from, const Transform& to) {
  const Vector3& c = geometry.boxCenter;
  const double trace = (from.linear().array() * to.linear().array()).sum();
  const double turn = std::sqrt(std::max(0.0, 3.0 - trace));
  return (to * c - from * c).norm() + turn * geometry.boxHalfSize.norm();
}

// A proof that two hulls were at least `gap` apart, placed as they were then, across `axis`
// (in a's body frame). It still holds for any placement whose two displacements from those
// poses add up to less than the gap; once they do not, its axis is the first to try again.
struct SeparationCertificate {
  Transform pose_a = Transform::Identity();
  Transform pose_b = Transform::Identity();
  Vector3 axis = Vector3::Zero();
  double gap = -1.0;  // negative: empty
};

// Rounding in the support and displacement arithmetic stays far below this, mm (FCL's triangle
// tests round alike).
constexpr double kCertificateMargin = 1e-6;

// What one thread remembers of a pair of meshes between queries (planners and autograsp ask
// about the same pairs in nearby poses again and again): a few separation certificates (a mesh
// shown by several links, as a hand's fingers, meets the other mesh at several poses), and how
// many queries to leave to FCL alone after certificates failed. Memory only chooses what to try or
// proves by geometry; stale memory costs time, never truth.
struct PairMemory {
  int failures = 0;
  int skip = 0;
  std::array<SeparationCertificate, 4> certificates;
  Vector3 nearestDifference = Vector3::UnitX();  // GJK's last answer, where the next one starts
};

bool certified(const PairMemory& memory, const Shape& a, const Transform& pose_a, const Shape& b,
               const Transform& pose_b, double by) {
  for (const SeparationCertificate& c : memory.certificates)
    if (c.gap > by && c.gap > displacement(a, c.pose_a, pose_a) +
                                  displacement(b, c.pose_b, pose_b) + by + kCertificateMargin)
      return true;
  return false;
}

// The certificate of the placement nearest this one; with `empty_first`, an empty slot before
// any. Each finger showing a shared mesh so keeps its own certificate and tries its own axis.
SeparationCertificate& nearestCertificate(PairMemory& memory, const Transform& pose_a,
                                          const Transform& pose_b, bool empty_first) {
  auto farness = [&](const SeparationCertificate& c) {
    if (c.gap < 0) return empty_first ? -1.0 : std::numeric_limits<double>::infinity();
    return (c.pose_a.translation() - pose_a.translation()).norm() +
           (c.pose_b.translation() - pose_b.translation()).norm();
  };
  return *std::min_element(memory.certificates.begin(), memory.certificates.end(),
                           [&](const auto& x, const auto& y) { return farness(x) < farness(y); });
}

// The certified gap across axis n (unit, world), less the margin; a positive one is remembered.
// Not positive: n proves nothing.
double separationAlong(PairMemory& memory, const Vector3& n, const Shape& a,
                       const Transform& pose_a, const Shape& b, const Transform& pose_b) {
  const double gap = slabGap(n, a, pose_a, b, pose_b) - kCertificateMargin;
  if (!(gap > 0)) return 0.0;
  nearestCertificate(memory, pose_a, pose_b, true) = {pose_a, pose_b,
                                                      pose_a.linear().transpose() * n, gap};
  return gap;
}

// The world axis from a's hull to b's through their nearest points, by GJK started from the
// pair's last answer (nearby placements need a few iterations, not a dozen); none when they
// overlap.
std::optional<Vector3> nearestAxis(PairMemory& memory, const Shape& a, const Transform& pose_a,
                                   const Shape& b, const Transform& pose_b) {
  const auto nearest = geometry::nearestDifference(a.hull, b.hull, pose_a.inverse() * pose_b,
                                                   memory.nearestDifference);
  if (!nearest) return std::nullopt;
  memory.nearestDifference = *nearest;
  return (pose_a.linear() * -*nearest).normalized();  // b lies along minus a - b
}

PairMemory& memoryOf(const Shape& a, const Shape& b) {
  using Key = std::pair<const geometry::ConvexHull*, const geometry::ConvexHull*>;
  struct KeyHash {
    std::size_t operator()(const Key& k) const {
      return std::hash<const void*>()(k.first) * 31 ^ std::hash<const void*>()(k.second);
    }
  };
  thread_local std::unordered_map<Key, PairMemory, KeyHash> memory;
  if (memory.size() > 4096) memory.clear();
  return memory[{&a.hull, &b.hull}];
}

}  // namespace

bool rootVolumesApart(const CollisionGeometry& a, const Transform& pose_a,
                      const CollisionGeometry& b, const Transform& pose_b) {
  const Transform b_in_a = pose_a.inverse(Eigen::Isometry) * pose_b;
  return !fcl::overlap(b_in_a.linear(), b_in_a.translation(), a.bvh->getBV(0).bv,
                       b.bvh->getBV(0).bv);
}

namespace {

// Whether two placed hulls are certainly more than `by` apart (hullsApart, for one pair of
// shapes).
bool shapesApart(const Shape& a, const Transform& pose_a, const Shape& b, const Transform& pose_b,
                 double by) {
  PairMemory& memory = memoryOf(a, b);
  // A certificate from a nearby placement proves it without looking at a vertex.
  if (certified(memory, a, pose_a, b, pose_b, by)) return true;
  // A cheap axis (world, unit) settles the question when it certifies a gap: one wider than `by`
  // proves it; a narrower one says apart, but maybe not by enough, and GJK would not say more.
  auto settledAlong = [&](const Vector3& n) -> std::optional<bool> {
    const double gap = separationAlong(memory, n, a, pose_a, b, pose_b);
    if (gap > by) return true;
    if (gap > 0 && by > 0) return false;
    return std::nullopt;
  };
  // The axis that separated them in the nearest placement, first: nearby poses are usually still
  // apart by it.
  if (const Vector3 axis = nearestCertificate(memory, pose_a, pose_b, false).axis; !axis.isZero())
    if (const auto settled = settledAlong(pose_a.linear() * axis)) return *settled;
  // The axis between the boxes' centres: two scans of hull vertices, a tenth of GJK's cost, and it
  // separates most pairs whose last axis no longer does (a link that turned past the other).
  if (const Vector3 between = pose_b * b.boxCenter - pose_a * a.boxCenter;
      between.squaredNorm() > 0)
    if (const auto settled = settledAlong(between.normalized())) return *settled;
  // Hulls that overlapped lately (a fingertip whose hull reaches into the mug's) most likely
  // still do: back off GJK for up to 16 queries, doubling with each failure.
  if (memory.skip > 0) {
    --memory.skip;
    return false;
  }
  const std::optional<Vector3> axis = nearestAxis(memory, a, pose_a, b, pose_b);
  const double gap = axis ? separationAlong(memory, *axis, a, pose_a, b, pose_b) : 0.0;
  if (gap > 0) {
    memory.failures = 0;
    return gap > by;
  }
  memory.failures = std::min(memory.failures + 1, 5);
  memory.skip = (1 << memory.failures) - 1;  // 1, 3, 7, 15, 31 queries... capped below
  memory.skip = std::min(memory.skip, 16);
  return false;
}

}  // namespace

bool hullsApart(const CollisionGeometry& a, const Transform& pose_a, const CollisionGeometry& b,
                const Transform& pose_b, double by) {
  if (!a.hull || !b.hull) return false;
  if (shapesApart(wholeOf(a), pose_a, wholeOf(b), pose_b, by)) return true;
  if (a.parts.empty() && b.parts.empty()) return false;
  // Every triangle lies in its part's hull: each part apart from each part of the other proves
  // the meshes apart. A mesh without parts stands as one.
  const auto shapeCount = [](const CollisionGeometry& g) {
    return g.parts.empty() ? std::size_t{1} : g.parts.size();
  };
  const auto shape = [](const CollisionGeometry& g, std::size_t i) {
    return g.parts.empty() ? wholeOf(g) : partOf(g.parts[i]);
  };
  for (std::size_t i = 0; i < shapeCount(a); ++i)
    for (std::size_t j = 0; j < shapeCount(b); ++j)
      if (!shapesApart(shape(a, i), pose_a, shape(b, j), pose_b, by)) return false;
  return true;
}

std::shared_ptr<const CollisionGeometry> collisionGeometry(
    const std::shared_ptr<const TriangleMesh>& mesh) {
  if (!mesh || mesh->empty()) return nullptr;
  return cache().get(mesh);
}

const CollisionGeometry* collisionGeometryOf(const std::shared_ptr<const TriangleMesh>& mesh) {
  if (!mesh) return nullptr;
  // Direct-mapped by address. An entry is this mesh's only if it shares the mesh's control block
  // (another mesh may since have been made at a dead one's address).
  struct Remembered {
    std::weak_ptr<const TriangleMesh> mesh;
    const CollisionGeometry* geometry = nullptr;
  };
  thread_local std::array<Remembered, 64> remembered;
  Remembered& slot =
      remembered[(reinterpret_cast<std::uintptr_t>(mesh.get()) >> 4) % remembered.size()];
  const bool same = !slot.mesh.owner_before(mesh) && !mesh.owner_before(slot.mesh);
  if (!same) slot = {mesh, collisionGeometry(mesh).get()};
  return slot.geometry;
}

}  // namespace graspkit
