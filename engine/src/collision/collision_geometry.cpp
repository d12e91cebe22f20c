// The process-wide cache of collision geometry, one entry per live mesh. Meshes are immutable and
// shared by every world, clone and link that shows them, so their BVHs can be too: a planner's
// clones on several threads all read the same hierarchy.

#include "collision/collision_geometry.hpp"

#include <mutex>
#include <shared_mutex>
#include <unordered_map>
#include <vector>

#include <fmt/format.h>

#include "graspkit/error.hpp"

namespace graspkit {
namespace {

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
  bvh->beginModel(static_cast<int>(triangles.size()), static_cast<int>(vertex_count));
  bvh->addSubModel(mesh.vertices, triangles);
  bvh->endModel();

  Eigen::AlignedBox3d box;
  for (const fcl::Triangle& tri : triangles)
    for (int k = 0; k < 3; ++k) box.extend(mesh.vertices[tri[k]]);
  auto geometry = std::make_shared<CollisionGeometry>();
  geometry->bvh = std::move(bvh);
  geometry->boxCenter = box.center();
  geometry->boxHalfSize = 0.5 * box.sizes();
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

std::shared_ptr<const CollisionGeometry> collisionGeometry(
    const std::shared_ptr<const TriangleMesh>& mesh) {
  if (!mesh || mesh->empty()) return nullptr;
  return cache().get(mesh);
}

}  // namespace graspkit
