#pragma once
// A split rule for FCL's top-down hierarchy builder chosen by the surface-area heuristic
// (Goldsmith and Salmon 1987; MacDonald and Booth 1990): of the planes across the node's three
// oriented-box axes and the mesh frame's three axes, at a few evenly spaced places each, the one
// that minimises the expected cost of a query reaching the node, each child's box surface area
// times its triangle count. FCL's own rules cut the longest axis at the mean or the median of the
// triangles' centres, which leaves long thin children where a mesh's triangles are uneven (a
// mug's handle beside its fine rim).

#include <vector>

#include <fcl/geometry/bvh/detail/BV_splitter_base.h>
#include <Eigen/Geometry>

#include "collision/collision_geometry.hpp"

namespace graspkit::collision {

class SurfaceAreaSplitter final : public fcl::detail::BVSplitterBase<BoundingVolume> {
 public:
  void set(Vector3* vertices, fcl::Triangle* triangles, fcl::BVHModelType type) override;
  void computeRule(const BoundingVolume& bv, unsigned int* primitives, int count) override;
  // FCL puts a triangle whose centre `q` this returns true for in the second child.
  bool apply(const Vector3& q) const override { return q.dot(axis_) > value_; }
  void clear() override;

 private:
  // Of the planes across `frame`'s axes (columns) at kBins places, the one cheapest by the
  // heuristic, with each triangle's box and centre in that frame; taken (into axis_, value_)
  // where it beats `best`, which it then lowers.
  template <class BoxOf, class CentreOf>
  void cheapestCut(const Eigen::Matrix3d& frame, int count, BoxOf box_of, CentreOf centre_of,
                   double& best);

  const Vector3* vertices_ = nullptr;
  const fcl::Triangle* triangles_ = nullptr;
  Vector3 axis_ = Vector3::UnitX();
  double value_ = 0.0;
  std::vector<Eigen::AlignedBox3d> boxes_;  // per triangle of the node, in its box's frame
  std::vector<Vector3> centres_;
  std::vector<Eigen::AlignedBox3d> mesh_boxes_;  // per triangle of the mesh, in the mesh's frame
  std::vector<Vector3> mesh_centres_;
};

}  // namespace graspkit::collision
