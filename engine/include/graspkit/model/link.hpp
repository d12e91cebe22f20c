#pragma once
// A link of a kinematic chain: a body, how it hangs on the chain's joints, and its collision
// rule. GraspIt! puts a link's frame at the end of the DH transform of its last joint.

#include <memory>
#include <optional>
#include <string>

#include "graspkit/model/body.hpp"

namespace graspkit {

// How a link connects to the previous one; it also says how many joints the link consumes.
enum class DynamicJointType { Revolute, Prismatic, Universal, Ball, Fixed };

int jointsConsumed(DynamicJointType type);  // 1, 1, 2, 3, 0

// A link of a robot: chain -1 (and link -1) means the base (palm).
struct LinkRef {
  int chain = -1;
  int link = -1;
  bool isBase() const { return chain < 0; }
  friend bool operator==(const LinkRef&, const LinkRef&) = default;
};

enum class CollisionRule {
  Default,          // collides with all but its own chain (see collision_filter.hpp)
  Off,              // removed from collision detection
  OverlappingPair,  // does not collide with `overlapTarget`
};

struct Link {
  std::shared_ptr<const BodyModel> body;
  std::string file;  // as written in the robot file
  std::string name;  // <robot>_chain<c>_link<l>
  DynamicJointType jointType = DynamicJointType::Revolute;
  int lastJoint = -1;  // chain-local index of the joint whose DH frame carries this link
  // The link's own frame in that DH frame: identity for GraspIt!'s robots; a URDF link keeps
  // its URDF frame, which DH frames cannot always be (URDF frames sit on the joint axis).
  Transform frame = Transform::Identity();
  CollisionRule collisionRule = CollisionRule::Default;
  std::optional<LinkRef> overlapTarget;
  std::string sensorType;
};

}  // namespace graspkit
