#pragma once
// A world: bodies (obstacles and graspable bodies), robots, connections between robots, and a
// camera. Everything heavy (meshes, robot definitions) is shared and immutable, so clone() only
// copies poses and DOF values; a planner runs one clone per thread.

#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "graspkit/model/body.hpp"
#include "graspkit/model/collision_filter.hpp"
#include "graspkit/model/robot.hpp"

namespace graspkit {

// A child robot mounted at the end of a parent robot's chain: the child's base sits at the
// parent chain's last link times `offset`. An optional mount piece is a body fixed to the
// child's base.
struct Connection {
  int parentRobot = 0;
  int parentChain = 0;
  int childRobot = 0;
  Transform offset = Transform::Identity();
  std::string mountFilename;  // as written in the world file, empty when none
  std::shared_ptr<const BodyModel> mount;
};

struct Camera {
  Vector3 position = Vector3::Zero();
  Quaternion orientation = Quaternion::Identity();
  double focalDistance = 0.0;
};

// A robot placed in a world, with the file name it was loaded from (for saving).
struct WorldRobot {
  Robot robot;
  std::filesystem::path filename;  // as written in the world file
};

// A contact impulse of the last time step, kept so that the next step's solver starts from it
// (a warm start): the pair, the contact point in body1's frame, and the impulse on body1 in the
// world frame (g*mm/s). The contact's normal (world frame, from body2 towards body1: the way a
// push moves body1) and the friction coefficient the step used let a statics check
// (dynamics/static_hold.hpp) ask what else these contacts could carry.
struct ContactImpulse {
  BodyRef body1;
  BodyRef body2;
  Vector3 localPoint = Vector3::Zero();
  Vector3 impulse = Vector3::Zero();
  Vector3 normal = Vector3::UnitZ();
  double mu = 0.0;
};

class World {
 public:
  std::vector<Body>& bodies() { return bodies_; }
  const std::vector<Body>& bodies() const { return bodies_; }
  const Body* findBody(const std::string& name) const;

  int robotCount() const { return static_cast<int>(robots_.size()); }
  const Robot& robot(int index) const;
  const WorldRobot& worldRobot(int index) const;
  std::optional<int> findRobot(const std::string& name) const;
  // The first robot that is a hand: what GraspIt! makes the current hand when a world loads, and
  // "the hand" wherever none is named. nullopt when no robot is a hand (an arm alone).
  std::optional<int> firstHand() const;
  // The first graspable (dynamic) body: "the object" wherever none is named. nullopt when none.
  std::optional<int> firstGraspable() const;

  const std::vector<Connection>& connections() const { return connections_; }
  const std::optional<Camera>& camera() const { return camera_; }
  void setCamera(std::optional<Camera> camera) { camera_ = std::move(camera); }

  // Adds a body; its name is made unique within the world. Returns its index.
  int addBody(Body body);
  // Removes free body `index` (an obstacle or graspable body; robots' links are not bodies here).
  // The bodies after it move down one index, and BodyRefs to them held elsewhere must follow;
  // the collision filter's switches do. Throws graspkit::Error for a bad index.
  void removeBody(int index);
  int addRobot(Robot robot, std::filesystem::path filename = {});
  // Mounts `child_robot` on the end of `parent_chain` of `parent_robot`. Throws graspkit::Error
  // for bad indices, a robot mounted twice, or a cycle.
  void connect(Connection connection);

  // Moving a robot moves every robot mounted on it.
  void setRobotPose(int robot, const Transform& pose);
  void setDofValues(int robot, std::span<const double> values,
                    LimitPolicy policy = LimitPolicy::Clamp);
  void setRobotPoseAndDofValues(int robot, const Transform& pose, std::span<const double> values,
                                LimitPolicy policy = LimitPolicy::Clamp);
  // Breaks joint `joint` of `robot` away (or re-engages it); mounted robots follow.
  void setBreakaway(int robot, int joint, BreakawayState state);
  // Robot::releaseBreakawayNotLagging on `robot`; mounted robots follow.
  void releaseBreakawayNotLagging(int robot);
  // The world pose of a connection's mount piece (the child's base).
  Transform mountPose(const Connection& connection) const;

  // Which pairs of bodies collision detection checks; a clone gets its own copy.
  CollisionFilter& collisionFilter() { return collision_filter_; }
  const CollisionFilter& collisionFilter() const { return collision_filter_; }

  // Dynamics (dynamics.hpp): gravity in mm/s^2, on by default (GraspIt! has none: set it to
  // zero to reproduce it), and the simulated time in seconds.
  const Vector3& gravity() const { return gravity_; }
  void setGravity(const Vector3& gravity) { gravity_ = gravity; }
  double time() const { return time_; }
  void setTime(double time) { time_ = time; }
  const std::vector<ContactImpulse>& lastImpulses() const { return last_impulses_; }
  void setLastImpulses(std::vector<ContactImpulse> impulses) {
    last_impulses_ = std::move(impulses);
  }
  // A robot's DOF velocities and PD set-points (see Robot). Throw graspkit::Error for a bad
  // index, a wrong count or a value that is not finite.
  void setDofVelocities(int robot, std::span<const double> velocities);
  void setDofTargets(int robot, std::span<const double> targets);
  void setDofReferences(int robot, std::span<const double> references);

  World clone() const { return *this; }

 private:
  Robot& mutableRobot(int index);
  void updateChildren(int parent);

  std::vector<Body> bodies_;
  // Per base name, the next numbered suffix to try: N copies of one file get their names in
  // O(N) each rather than O(N^2).
  std::map<std::string, int> next_suffix_;
  std::vector<WorldRobot> robots_;
  std::vector<Connection> connections_;
  std::optional<Camera> camera_;
  CollisionFilter collision_filter_;
  Vector3 gravity_ = Vector3(0.0, 0.0, -9810.0);
  double time_ = 0.0;
  std::vector<ContactImpulse> last_impulses_;
};

}  // namespace graspkit
