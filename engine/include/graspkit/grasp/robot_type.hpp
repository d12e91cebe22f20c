#pragma once
// A robot type: what the `type` attribute of <robot> names (Hand, Barrett, Puma560, ...). The
// engine provides the generic "Robot" and "Hand"; every special type comes from a plugin, which
// overrides only what differs: extra collision exclusions, a closed-form inverse kinematics, a
// hand-specific autograsp. A RobotType is stateless and shared by every robot of its type.

#include "graspkit/grasp/autograsp.hpp"
#include "graspkit/model/inverse_kinematics.hpp"

namespace graspkit {

class Robot;
struct RobotModel;
class World;

// What a close moves. The looser the promise, the fewer closes a planner can rule out unrun.
enum class CloseMotion {
  // Each DOF from its value toward the end its default velocity points to (one with no velocity
  // stays), within its limits; the palm stays still. The engine's close.
  TowardClosingEnds,
  // The DOFs anywhere within their limits; the palm stays still.
  WithinDofLimits,
  // Anything, the palm too: no close is ruled out.
  Unknown,
};

class RobotType {
 public:
  virtual ~RobotType() = default;

  // Adjusts a freshly read model once, before it is shared: adds the type's collision
  // exclusions, checks the structure the type relies on (throw graspkit::Error naming
  // model.file when it is wrong). The default changes nothing.
  virtual void configure(RobotModel& model) const;

  // DOF values that put the end of chain `request.chain` at `target` (world frame). The default
  // is the engine's iterative solver (iterativeInverseKinematics).
  virtual IkResult inverseKinematics(const Robot& robot, const Transform& target,
                                     const IkRequest& request) const;

  // Closes the hand. The default is the engine's autoGrasp (genericAutoGrasp). A type that
  // overrides it says what its close moves in closeMotion().
  virtual AutoGraspResult autoGrasp(World& world, int robot, const AutoGraspOptions& options) const;

  // What autoGrasp() moves, for planners that skip closes which cannot reach the object
  // (planning/close_reach.hpp). The default is the engine's close: TowardClosingEnds.
  virtual CloseMotion closeMotion() const;
};

// Dispatches to the robot's type (closed form where it has one), else the iterative solver.
// Throws graspkit::Error for a bad chain index; an unreachable target is a failed result.
IkResult inverseKinematics(const Robot& robot, const Transform& target,
                           const IkRequest& request = {});

}  // namespace graspkit
