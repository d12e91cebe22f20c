#pragma once
// Internal: a mesh's Embree geometry, built once per TriangleMesh and shared by every world,
// clone and thread (Embree scenes are read-only after commit). Contact search uses its
// bounded point queries to find triangle pairs; the ray scene instances it.

#include <embree3/rtcore.h>

#include <limits>
#include <memory>
#include <optional>
#include <vector>

#include "graspkit/geometry/mesh.hpp"

namespace graspkit::raycast {

// Embree works in float. A double past float range becomes an infinity of its sign here (a plain
// cast would be undefined behaviour), which Embree treats as no bound or an invalid primitive.
inline float toEmbreeFloat(double value) {
  constexpr double kMax = std::numeric_limits<float>::max();
  if (value > kMax) return std::numeric_limits<float>::infinity();
  if (value < -kMax) return -std::numeric_limits<float>::infinity();
  return static_cast<float>(value);
}

// The process-wide Embree device.
RTCDevice device();

class EmbreeMesh {
 public:
  explicit EmbreeMesh(std::shared_ptr<const TriangleMesh> mesh);
  ~EmbreeMesh();
  EmbreeMesh(const EmbreeMesh&) = delete;
  EmbreeMesh& operator=(const EmbreeMesh&) = delete;

  RTCScene scene() const { return scene_; }
  const TriangleMesh& mesh() const { return *mesh_; }
  const Eigen::AlignedBox3d& bounds() const { return bounds_; }
  // Triangle t's bounding box (mesh frame, mm), kept so that searches test it with one load.
  const Eigen::AlignedBox3d& triangleBox(unsigned t) const { return triangle_boxes_[t]; }
  // The mean of the triangles' box diagonals, mm: how large a search around one of them is.
  double meanTriangleSize() const { return mean_triangle_size_; }

  // Calls visit(triangle index) for every triangle whose bounding box may come within `radius`
  // of `center` (mesh frame, mm). It may also visit a few farther ones (Embree works in float);
  // callers test exactly. Thread-safe.
  template <class Visit>
  void forEachTriangleNear(const Vector3& center, double radius, Visit&& visit) const {
    forEachNear(center, radius, &invoke<Visit>, &visit);
  }

  // The nearest point of the mesh to `center` (mesh frame, mm) no farther than `maxDistance`
  // (may be infinite), measured in double on the mesh's own vertices; nullopt when nothing is
  // that close. Embree only prunes, with its radius shrunk as closer triangles turn up.
  // Thread-safe.
  struct Nearest {
    unsigned triangle = 0;
    Vector3 point = Vector3::Zero();  // mesh frame, mm
    double distance = 0.0;            // mm
  };
  std::optional<Nearest> nearest(const Vector3& center, double maxDistance) const;

  // How far float rounding of the stored vertices and of a query point `center` (mesh frame)
  // can move what Embree compares; search radii are widened by this so nothing is pruned that
  // double arithmetic would keep.
  double floatPad(const Vector3& center) const {
    return 1e-6 * (center.cwiseAbs().maxCoeff() + bounds_.sizes().maxCoeff()) + 1e-6;
  }

 private:
  using Callback = void (*)(void* user, unsigned triangle);
  template <class Visit>
  static void invoke(void* user, unsigned triangle) {
    (*static_cast<Visit*>(user))(triangle);
  }
  void forEachNear(const Vector3& center, double radius, Callback callback, void* user) const;

  std::shared_ptr<const TriangleMesh> mesh_;
  RTCScene scene_ = nullptr;
  Eigen::AlignedBox3d bounds_;
  std::vector<Eigen::AlignedBox3d> triangle_boxes_;
  double mean_triangle_size_ = 0.0;
};

// The shared Embree geometry of `mesh`, built on first use. Thread-safe.
std::shared_ptr<const EmbreeMesh> embreeMesh(const std::shared_ptr<const TriangleMesh>& mesh);

}  // namespace graspkit::raycast
