#pragma once
// A serial chain of joints hanging from the robot's base, carrying links.

#include <span>
#include <vector>

#include "graspkit/model/joint.hpp"
#include "graspkit/model/link.hpp"

namespace graspkit {

struct KinematicChain {
  Transform base = Transform::Identity();  // palm frame -> frame of the first joint
  std::vector<Joint> joints;
  std::vector<Link> links;
  int firstJoint = 0;                                       // robot-wide index of joints[0]
  std::vector<std::pair<int, std::string>> tactileFilters;  // (link index, params)
};

// Forward kinematics of one chain: the world pose of every joint frame (after each joint's DH
// transform) given the chain's world base pose and its joint values (offsets excluded).
std::vector<Transform> jointFrames(const KinematicChain& chain,
                                   const Transform& chain_base_in_world,
                                   std::span<const double> joint_values);

// World poses of the chain's links: link l sits at the frame of its last joint (or at the
// chain base when it consumes no joint before it), times its own Link::frame.
std::vector<Transform> linkPoses(const KinematicChain& chain, const Transform& chain_base_in_world,
                                 std::span<const double> joint_values);
// The same into `poses`, whose storage is kept (a planner places the hand at every step).
void linkPoses(const KinematicChain& chain, const Transform& chain_base_in_world,
               std::span<const double> joint_values, std::vector<Transform>& poses);

}  // namespace graspkit
