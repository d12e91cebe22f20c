#pragma once
// The generalized coordinates of a world's dynamics and the Jacobians that map their velocities
// to the motion of points of bodies. Each graspable body has 6 coordinates (velocity of its
// centre of mass, then angular velocity, world frame); each robot one per DOF, whose joints turn
// (or slide) by ratio * DOF velocity about the z axis of the frame before them, as in DH.
// Obstacles and robot bases that are not mounted on another robot have no coordinates.

#include <Eigen/Dense>
#include <map>
#include <vector>

#include "graspkit/math/transform.hpp"
#include "graspkit/model/body_ref.hpp"

namespace graspkit {

class World;

namespace dynamics {

using MatrixX = Eigen::MatrixXd;
using VectorX = Eigen::VectorXd;

// One joint seen from the bodies it carries: where it is, which way it moves, which coordinate
// drives it and how strongly.
struct JointAxis {
  int coordinate = 0;
  double ratio = 1.0;
  bool revolute = true;
  Vector3 axis = Vector3::UnitZ();   // world frame
  Vector3 origin = Vector3::Zero();  // a point on the axis, world frame
};

// How a body moves with the coordinates: a free body through its own 6, a robot part through
// the joints between it and the world.
struct BodyMotion {
  int freeCoordinate = -1;           // first of the 6 coordinates of a graspable body, else -1
  Vector3 centre = Vector3::Zero();  // the free body's centre of mass, world frame
  std::vector<JointAxis> joints;
  bool moves() const { return freeCoordinate >= 0 || !joints.empty(); }
};

class GeneralizedCoordinates {
 public:
  explicit GeneralizedCoordinates(const World& world);

  int size() const { return size_; }
  int robotOffset(int robot) const { return robot_offset_[robot]; }
  int bodyOffset(int body) const { return body_offset_[body]; }

  // Bodies with mass that move: every graspable body, and every robot part with joints above.
  const std::vector<BodyRef>& movingBodies() const { return moving_; }
  const BodyMotion& motion(const BodyRef& ref) const;

  // The 3 x size() Jacobians of a point `p` (world frame) rigidly attached to `ref`: its
  // linear velocity, and the body's angular velocity. Zero for bodies that do not move.
  MatrixX linearJacobian(const BodyRef& ref, const Vector3& p) const;
  MatrixX angularJacobian(const BodyRef& ref) const;

 private:
  std::vector<JointAxis> robotAncestors(const World& world, int robot) const;
  std::vector<JointAxis> chainAxes(const World& world, int robot, int chain, int last_joint) const;

  int size_ = 0;
  std::vector<int> robot_offset_;
  std::vector<int> body_offset_;
  std::vector<BodyRef> moving_;
  std::map<BodyRef, BodyMotion> motion_;
  BodyMotion still_;
};

}  // namespace dynamics
}  // namespace graspkit
