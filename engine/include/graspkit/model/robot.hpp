#pragma once
// A robot: a base link (the palm for hands), DOFs, and kinematic chains of joints and links.
// RobotModel is what a Robot file describes; it is immutable and shared. Robot is one instance
// of it in a world: base pose, DOF and joint values, and the link poses they give.

#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "graspkit/model/dof.hpp"
#include "graspkit/model/eigengrasp.hpp"
#include "graspkit/model/kinematic_chain.hpp"
#include "graspkit/model/tendon.hpp"
#include "graspkit/model/virtual_contact.hpp"

namespace graspkit {

// Bounds on one robot, which every robot reader enforces. GraspIt!'s hands have at most a few dozen
// DOFs and links; the bounds keep a hostile file from costing memory out of proportion to its size
// (a robot's eigengrasp matrix, identity by default, holds DOFs x DOFs numbers) while leaving room
// for whole humanoids.
inline constexpr int kMaxRobotDofs = 1024;
inline constexpr int kMaxRobotJoints = 4096;  // over all chains, and as many links

class RobotType;

// The frame a hand approaches along: z is the approach direction, in the palm frame.
struct ApproachDirection {
  Vector3 referenceLocation = Vector3::Zero();
  Vector3 direction = Vector3::UnitZ();
  Transform frame() const;  // GraspIt!'s construction of x and y around z
};

struct FlockOfBirds {
  int number = 0;
  Transform offset = Transform::Identity();
};

struct CollisionPair {
  LinkRef first;
  LinkRef second;
  // Why the pair is never checked: empty for a robot file's own <disableCollision> (and a robot
  // type's), else the reader's reason ("MJCF <contact><exclude>", "SRDF <disable_collisions>",
  // "always in collision (64 of 64 postures)", ...). info --json lists them.
  std::string reason;
};

struct RobotModel {
  std::string name;    // the file stem
  std::string type;    // the <robot type> attribute (Robot, Hand, Barrett, ...)
  std::string dbName;  // defaults to type
  // The type's behaviour (from the registry) and who provided it ("barrett 1.0.0", "built in").
  // Null for a model built in code: it behaves as a generic robot.
  std::shared_ptr<const RobotType> robotType;
  std::string typeProvider;
  bool isHand = true;  // false only for type "Robot"
  std::filesystem::path file;

  std::shared_ptr<const BodyModel> palm;
  std::string palmFile;  // as written
  std::string palmSensorType;
  std::vector<std::string> palmFilters;

  std::vector<Dof> dofs;
  std::vector<KinematicChain> chains;
  std::vector<CollisionPair> disabledCollisions;
  std::optional<ApproachDirection> approach;

  std::string eigengraspFile;  // as written, relative to the robot folder
  EigengraspSet eigengrasps;   // identity eigengrasps when the file names none
  std::string virtualContactFile;
  std::vector<VirtualContact> virtualContacts;
  std::string cyberGloveFile;
  std::optional<FlockOfBirds> flockOfBirds;
  std::vector<Tendon> tendons;
  std::vector<TendonWrapper> tendonWrappers;

  // Excludes the pair (a, b) from collision detection, as a robot type's configure() does.
  // Throws graspkit::Error naming the file when a or b is not a link of this model.
  void disableCollision(const LinkRef& a, const LinkRef& b);
  bool hasLink(const LinkRef& ref) const;  // the base, or an existing chain link

  int jointCount() const;
  int linkCount() const;  // chain links, the base excluded
  const Joint& joint(int robot_joint_index) const;
  std::size_t triangleCount() const;  // base and every link
  Transform approachFrame() const { return approach ? approach->frame() : Transform::Identity(); }
};

// How setDofValues treats values outside a DOF's range.
enum class LimitPolicy {
  Clamp,   // clamp each value into its DOF's range (interactive use)
  Ignore,  // apply as given (GraspIt! does this when it loads a world)
};

// Per joint of a breakaway DOF: whether the joint has broken away, and the DOF value at which
// it stopped following the DOF (what world files save as `1 <value>`).
struct BreakawayState {
  bool engaged = false;
  double value = 0.0;
};

// How far a DOF must have gone on past the value a joint stopped at for the joint to be in
// breakaway (GraspIt!'s test): nearer, the joint still follows its DOF.
constexpr double kBreakawayLag = 1e-5;

class Robot {
 public:
  explicit Robot(std::shared_ptr<const RobotModel> model);

  const RobotModel& model() const { return *model_; }
  const std::shared_ptr<const RobotModel>& modelPtr() const { return model_; }
  const std::string& name() const { return model_->name; }
  int dofCount() const { return static_cast<int>(dof_values_.size()); }

  // The base (palm) frame in the world.
  const Transform& pose() const { return pose_; }
  void setPose(const Transform& pose);

  std::span<const double> dofValues() const { return dof_values_; }
  // Sets every DOF, moves the joints through the coupling and updates the link poses.
  // Throws graspkit::Error for a wrong count or a non-finite value.
  void setDofValues(std::span<const double> values, LimitPolicy policy = LimitPolicy::Clamp);
  void setDofValue(int dof, double value, LimitPolicy policy = LimitPolicy::Clamp);
  // setPose and setDofValues at once, the links placed once (a planner's every step). Nothing
  // changes when it throws.
  void setPoseAndDofValues(const Transform& pose, std::span<const double> values,
                           LimitPolicy policy = LimitPolicy::Clamp);

  // Joint values, robot-wide order, DH offsets excluded.
  std::span<const double> jointValues() const { return joint_values_; }

  // Dynamics: DOF velocities (rad/s, mm/s for prismatic DOFs) and the set-points of the DOF
  // PD controllers. Without set-points a robot holds the posture its first step finds.
  std::span<const double> dofVelocities() const { return dof_velocities_; }
  void setDofVelocities(std::span<const double> velocities);
  std::span<const double> dofTargets() const { return dof_targets_; }
  void setDofTargets(std::span<const double> targets);  // an empty span clears them
  // The controllers' moving set-points: each steps towards its target at the DOF's speed
  // (|defaultVelocity|, 1 where that is 0) once per step, as GraspIt!'s do. Empty before the
  // first step, which starts them at the DOF values.
  std::span<const double> dofReferences() const { return dof_references_; }
  void setDofReferences(std::span<const double> references);  // an empty span clears them

  std::span<const BreakawayState> breakaway() const { return breakaway_; }
  void setBreakaway(int joint, BreakawayState state);
  // Re-engages each joint marked broken away whose DOF has not gone on past it by more than
  // kBreakawayLag: the joint a DOF stopped with (a Barrett's distal) is still driven by it.
  // A joint moves by at most kBreakawayLag times its ratio.
  void releaseBreakawayNotLagging();

  // World poses: the base, and link l of chain c.
  const Transform& linkPose(int chain, int link) const { return link_poses_[chain][link]; }
  const Transform& linkPose(const LinkRef& ref) const;
  const std::vector<std::vector<Transform>>& linkPoses() const { return link_poses_; }
  // The pose at the end of chain c (its last link), where a child robot is mounted.
  const Transform& chainEndPose(int chain) const { return link_poses_[chain].back(); }

 private:
  // Checks and takes (clamped or not) every DOF value; the joints and links are not moved.
  void takeDofValues(std::span<const double> values, LimitPolicy policy);
  void updateJoints();
  void updateLinkPoses();

  std::shared_ptr<const RobotModel> model_;
  Transform pose_ = Transform::Identity();
  std::vector<double> dof_values_;
  std::vector<double> joint_values_;
  std::vector<BreakawayState> breakaway_;
  std::vector<std::vector<Transform>> link_poses_;
  std::vector<double> dof_velocities_;
  std::vector<double> dof_targets_;
  std::vector<double> dof_references_;
};

}  // namespace graspkit
