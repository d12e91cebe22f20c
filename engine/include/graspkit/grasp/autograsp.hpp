#pragma once
// Hand motions that stop at contact, with GraspIt!'s static semantics: autoGrasp closes every
// DOF along its default velocity until nothing moves; openUntilFree backs the DOFs off until the
// hand collides with nothing; approachToContact moves the hand along its approach direction
// until it touches. The contact instant is found by bisection, so a hand that stops touches
// (closer than the contact threshold) and never interpenetrates.

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "graspkit/base/enum_names.hpp"
#include "graspkit/collision/contact.hpp"

namespace graspkit {

class World;

struct AutoGraspOptions {
  // Scales every DOF's default velocity; a negative factor opens instead of closing.
  double speedFactor = 1.0;
  bool stopAtContact = false;  // end at the first contact, as GraspIt!'s stopAtContact
  int maxIterations = 500;     // GraspIt!'s failsafe
  // Asked before each step; false ends the close where it is (MotionEnd::Stopped). A planner's
  // time budget runs out inside a close this way: a close of a hand with small DOF steps (the
  // RobotIQ's linkage) takes long enough to overrun a budget checked only between closes.
  std::function<bool()> keepGoing;
};

enum class MotionEnd {
  Settled,             // nothing moves any more
  Contact,             // stopAtContact and a contact appeared (or approach touched)
  IterationLimit,      // the failsafe ended it
  InterpolationError,  // the contact instant could not be bracketed (GraspIt!'s "Robot joint
                       // interpolation error")
  NoContact,           // approachToContact went its whole distance without touching
  Stopped,             // keepGoing said stop: the motion is unfinished
};

// "settled", "contact", "iteration_limit", "interpolation_error", "no_contact" or "stopped": how
// reports
// and scripts name a motion's end (base/enum_names.hpp: nameOf, valueNamed, parseNamed).
std::span<const EnumName<MotionEnd>> enumNames(std::type_identity<MotionEnd>);

struct AutoGraspResult {
  std::vector<double> dofValues;
  std::vector<Contact> contacts;  // seen from the hand's links, after the motion
  int iterations = 0;
  MotionEnd end = MotionEnd::Settled;
};

// Closes robot `robot`'s DOFs in `world` (the world is changed) the way its robot type closes
// (RobotType::autoGrasp; genericAutoGrasp unless a plugin overrides it). Throws graspkit::Error
// for a bad robot index or a robot that is not a hand (no chains, or a "Robot" type without
// fingers).
AutoGraspResult autoGrasp(World& world, int robot, const AutoGraspOptions& options = {});

// GraspIt!'s Hand::autoGrasp: every DOF closes along its default velocity at once.
AutoGraspResult genericAutoGrasp(World& world, int robot, const AutoGraspOptions& options = {});

// One static DOF motion, GraspIt!'s moveDOFToContacts: the building block of hand-specific
// autograsps. Each DOF d moves from its value toward targets[d] by |steps[d]| per step (the
// sign comes from the target; a zero step holds the DOF where it is). A colliding step is
// bisected back to the contact instant, and the joints behind each touching link stop (a link
// already touching at the start stops them if the motion would push it further in).
struct DofMotion {
  std::vector<double> targets;      // one per DOF, clamped into the DOF's range
  std::vector<double> steps;        // one per DOF; magnitudes
  bool stopAtContact = false;       // end after the first step that brought a contact
  int maxIterations = 500;          // GraspIt!'s failsafe
  std::function<bool()> keepGoing;  // as AutoGraspOptions::keepGoing
  // Called after every change of the DOF values (each step and each bisection point), before
  // collisions are checked: lets a caller move the base with the fingers (a compliant close).
  std::function<void(World&, int robot)> afterDofChange;
};

// Runs `motion` on robot `robot` (the world is changed). Returns the final DOFs and contacts;
// `iterations` is the number of steps taken, 0 when nothing could move. Throws
// graspkit::Error for a bad robot index, a robot that is not a hand, or vectors whose size is
// not the robot's DOF count.
AutoGraspResult moveDofsToContacts(World& world, int robot, const DofMotion& motion);

// Opens the DOFs (against their default velocity) in chunks until the hand collides with
// nothing or every DOF is at its open limit. Returns whether the hand ends collision-free.
bool openUntilFree(World& world, int robot);

struct ApproachOptions {
  double maxDistance = 500.0;              // mm
  double step = 50.0 * kContactThreshold;  // mm, GraspIt!'s 10 mm
  // The way to move, in the world frame (any length but zero); unset: the hand's approach
  // direction (the palm's approach frame z), as GraspIt! moves.
  std::optional<Vector3> direction;
};

// Moves the hand in a straight line (its approach direction unless `options.direction` says
// otherwise) until it touches something. Throws graspkit::Error when the robot is in collision
// before it moves, or for a zero or non-finite direction.
AutoGraspResult approachToContact(World& world, int robot, const ApproachOptions& options = {});

// The contacts between robot `robot`'s links and every other body the collision filter pairs
// them with, seen from the links. With `object`, only contacts with that body.
std::vector<Contact> robotContacts(const World& world, int robot, const BodyRef* object = nullptr);

// Of `contacts` (seen from the links, as robotContacts() gives them), those with `object`, in
// order: what robotContacts(world, robot, &object) gives where `contacts` are the robot's. A close
// returns its final contacts (AutoGraspResult::contacts), so measuring the grasp it left needs
// no second contact search.
std::vector<Contact> contactsWith(const std::vector<Contact>& contacts, const BodyRef& object);

}  // namespace graspkit
