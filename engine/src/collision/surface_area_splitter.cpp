#include "collision/surface_area_splitter.hpp"

#include <array>
#include <limits>

#include <Eigen/Geometry>

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
}

void SurfaceAreaSplitter::clear() {
  vertices_ = nullptr;
  triangles_ = nullptr;
  boxes_ = {};
  centres_ = {};
}

void SurfaceAreaSplitter::computeRule(const BoundingVolume& bv, unsigned int* primitives,
                                      int count) {
  const Eigen::Matrix3d& axes = bv.obb.axis;  // columns: the node box's axes, longest first
  axis_ = axes.col(0);
  value_ = axis_.dot(bv.obb.To);
  if (count < 2 || !triangles_) return;

  // Each triangle in the node box's frame: its box and its centre (buffers kept between nodes).
  boxes_.resize(count);
  centres_.resize(count);
  Eigen::AlignedBox3d centre_range;
  const Eigen::Matrix3d to_box = axes.transpose();
  for (int i = 0; i < count; ++i) {
    const fcl::Triangle& t = triangles_[primitives[i]];
    const Vector3 p0 = to_box * vertices_[t[0]];
    const Vector3 p1 = to_box * vertices_[t[1]];
    const Vector3 p2 = to_box * vertices_[t[2]];
    boxes_[i] = Eigen::AlignedBox3d(p0.cwiseMin(p1).cwiseMin(p2), p0.cwiseMax(p1).cwiseMax(p2));
    centres_[i] = (p0 + p1 + p2) / 3.0;
    centre_range.extend(centres_[i]);
  }
  const std::vector<Eigen::AlignedBox3d>& boxes = boxes_;
  const std::vector<Vector3>& centres = centres_;

  double best = std::numeric_limits<double>::infinity();
  for (int a = 0; a < 3; ++a) {
    const double lo = centre_range.min()[a], hi = centre_range.max()[a];
    if (!(hi > lo)) continue;
    std::array<Eigen::AlignedBox3d, kBins> bin_box;
    std::array<int, kBins> bin_count{};
    const double scale = kBins / (hi - lo);
    for (int i = 0; i < count; ++i) {
      const int b = std::min(kBins - 1, static_cast<int>((centres[i][a] - lo) * scale));
      bin_box[b].extend(boxes[i]);
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
        axis_ = axes.col(a);
        value_ = lo + (b + 1) / scale;  // in the box frame, along a world axis: the same dot
      }
    }
  }
}

}  // namespace graspkit::collision
