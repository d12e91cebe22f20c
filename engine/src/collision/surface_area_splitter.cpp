#include "collision/surface_area_splitter.hpp"

#include <algorithm>
#include <array>
#include <limits>

namespace graspkit::collision {
namespace {

constexpr int kBins = 16;

double surfaceArea(const Eigen::AlignedBox3d& box) {
  if (box.isEmpty()) return 0.0;
  const Vector3 e = box.sizes();
  return 2.0 * (e.x() * e.y() + e.y() * e.z() + e.z() * e.x());
}

}  // namespace

void SurfaceAreaSplitter::set(Vector3* vertices, fcl::Triangle* triangles, fcl::BVHModelType) {
  vertices_ = vertices;
  triangles_ = triangles;
  mesh_boxes_.clear();
  mesh_centres_.clear();
}

void SurfaceAreaSplitter::clear() {
  vertices_ = nullptr;
  triangles_ = nullptr;
  boxes_ = {};
  centres_ = {};
  mesh_boxes_ = {};
  mesh_centres_ = {};
}

template <class BoxOf, class CentreOf>
void SurfaceAreaSplitter::cheapestCut(const Eigen::Matrix3d& frame, int count, BoxOf box_of,
                                      CentreOf centre_of, double& best) {
  Eigen::AlignedBox3d centre_range;
  for (int i = 0; i < count; ++i) centre_range.extend(centre_of(i));
  for (int a = 0; a < 3; ++a) {
    const double lo = centre_range.min()[a], hi = centre_range.max()[a];
    if (!(hi > lo)) continue;
    std::array<Eigen::AlignedBox3d, kBins> bin_box;
    std::array<int, kBins> bin_count{};
    const double scale = kBins / (hi - lo);
    for (int i = 0; i < count; ++i) {
      const int b = std::min(kBins - 1, static_cast<int>((centre_of(i)[a] - lo) * scale));
      bin_box[b].extend(box_of(i));
      ++bin_count[b];
    }
    // Sweep from the right for each plane's second child, then from the left for its first.
    std::array<double, kBins> right_cost{};
    Eigen::AlignedBox3d right;
    int right_count = 0;
    for (int b = kBins - 1; b > 0; --b) {
      right.extend(bin_box[b]);
      right_count += bin_count[b];
      right_cost[b] = surfaceArea(right) * right_count;
    }
    Eigen::AlignedBox3d left;
    int left_count = 0;
    for (int b = 0; b + 1 < kBins; ++b) {
      left.extend(bin_box[b]);
      left_count += bin_count[b];
      if (left_count == 0 || left_count == count) continue;
      const double cost = surfaceArea(left) * left_count + right_cost[b + 1];
      if (cost < best) {
        best = cost;
        axis_ = frame.col(a);
        value_ = lo + (b + 1) / scale;  // a coordinate in `frame`: the dot with its axis
      }
    }
  }
}

void SurfaceAreaSplitter::computeRule(const BoundingVolume& bv, unsigned int* primitives,
                                      int count) {
  const Eigen::Matrix3d& axes = bv.obb.axis;  // columns: the node box's axes, longest first
  axis_ = axes.col(0);
  value_ = axis_.dot(bv.obb.To);
  if (count < 2 || !triangles_) return;

  // The first node is the root, over every triangle: their boxes and centres in the mesh's
  // frame are kept for every node below.
  if (mesh_boxes_.empty()) {
    const unsigned triangles = *std::max_element(primitives, primitives + count) + 1;
    mesh_boxes_.resize(triangles);
    mesh_centres_.resize(triangles);
    for (unsigned t = 0; t < triangles; ++t) {
      const Vector3& p0 = vertices_[triangles_[t][0]];
      const Vector3& p1 = vertices_[triangles_[t][1]];
      const Vector3& p2 = vertices_[triangles_[t][2]];
      mesh_boxes_[t] = {p0.cwiseMin(p1).cwiseMin(p2), p0.cwiseMax(p1).cwiseMax(p2)};
      mesh_centres_[t] = (p0 + p1 + p2) / 3.0;
    }
  }

  // The node's triangles in its box's frame (buffers kept between nodes).
  boxes_.resize(count);
  centres_.resize(count);
  const Eigen::Matrix3d to_box = axes.transpose();
  for (int i = 0; i < count; ++i) {
    const fcl::Triangle& t = triangles_[primitives[i]];
    const Vector3 p0 = to_box * vertices_[t[0]];
    const Vector3 p1 = to_box * vertices_[t[1]];
    const Vector3 p2 = to_box * vertices_[t[2]];
    boxes_[i] = {p0.cwiseMin(p1).cwiseMin(p2), p0.cwiseMax(p1).cwiseMax(p2)};
    centres_[i] = (p0 + p1 + p2) / 3.0;
  }

  // Planes across the box's axes, with child boxes in its frame, and across the mesh frame's
  // axes, with child boxes in that frame: a box's axes follow the spread of its triangles, which
  // for two far clusters (a finger's pad and its knuckle) runs across the gap between them.
  double best = std::numeric_limits<double>::infinity();
  cheapestCut(
      axes, count, [&](int i) -> const Eigen::AlignedBox3d& { return boxes_[i]; },
      [&](int i) -> const Vector3& { return centres_[i]; }, best);
  cheapestCut(
      Eigen::Matrix3d::Identity(), count,
      [&](int i) -> const Eigen::AlignedBox3d& { return mesh_boxes_[primitives[i]]; },
      [&](int i) -> const Vector3& { return mesh_centres_[primitives[i]]; }, best);
}

}  // namespace graspkit::collision
