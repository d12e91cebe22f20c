#pragma once
// The statics of a settled grasp: can the contacts that hold the object at rest also carry its
// weight turned along an axis, with the hand's DOF forces as they are and friction to spare?
//
// The squeeze at rest is an equilibrium: the contact forces f0 on the object balance each
// other and, through the fingers' Jacobians, the DOF controllers' forces. Under a pull a (the
// object's weight m a, and the links' own), a new equilibrium needs contact forces f inside
// their friction cones with
//     sum_c G_c f_c = sum_c G_c f0_c - Q(a)
// in every generalized coordinate the contacts touch (dynamics/generalized_coordinates.hpp):
// the object's 6 rows (force and moment balance) and each DOF's row (the DOF's force does not
// change: a saturated controller pushes with maxEffort whatever the load, and a stiffer one
// would have to move to push harder). Each cone is a pyramid of edges, and f a nonnegative
// combination of them, so the question is one nonnegative least-squares problem
// (math/nonnegative_least_squares.hpp): it holds exactly when the residual is 0.
//
// The answer "holds" is meant to stand for a simulated pull that holds (grasp_validation.hpp):
// the pyramid uses only a share of each contact's friction, so that a transient at the pull's
// start or a contact the solver shares differently does not slide. Where statics cannot speak
// for the dynamics it says why instead: a finger touching another finger or the palm (forces
// between DOFs), a DOF at a joint limit (the limit's force is unknown), breakaway and compliant
// DOFs (their joints or forces change under load), or the object touching anything but a hand.

#include <string>
#include <vector>

#include "graspkit/math/transform.hpp"
#include "graspkit/model/world.hpp"

namespace graspkit {

// A contact on the object at rest: where, its normal into the object, its friction coefficient
// and the force it puts on the object (world frame, g*mm/s^2), and what the object touches.
struct HeldContact {
  BodyRef other;
  Vector3 point = Vector3::Zero();
  Vector3 normal = Vector3::UnitZ();
  double mu = 0.0;
  Vector3 force = Vector3::Zero();
};

// The object's contacts from the impulses of the last two steps of length dt (World::
// lastImpulses after each): each contact counted at half its impulse per step, so that a rest
// which alternates between a step that pushes contacts out and one that does not is seen at its
// mean. A contact between other bodies is not returned; it sets `betweenOthers`, so that the
// check can refuse the grasp (it would pass force from one DOF to another).
struct HeldContacts {
  std::vector<HeldContact> onObject;
  bool betweenOthers = false;  // some contact does not involve the object (a finger on a finger)
};
HeldContacts heldContacts(const World& world, int object,
                          const std::vector<ContactImpulse>& previousImpulses,
                          const std::vector<ContactImpulse>& lastImpulses, double dt);

// The margins that make "an equilibrium exists" stand for "a simulated pull holds": the pull
// scaled up, optionally a box of disturbing wrenches on top, the pyramid inside a share of the
// friction cone, and only the contacts the squeeze presses. The defaults agreed with the
// simulation on every one of 1,000 planned grasps (docs/dynamics.md); the disturbance agreed
// as well and decided a quarter fewer directions, so it is off. (A pinch between two points
// turns freely about the line between them: where the pull has a moment about that line there
// is no equilibrium anyway, and where it has none the simulation holds too.)
struct StaticHoldMargins {
  double loadFactor = 2.0;  // the pull, times this
  // Each of the object's wrench axes, both ways, in units of its weight under the pull (forces)
  // and of its weight times its radius (moments), added to the pull one at a time (0: none).
  double disturbance = 0.0;
  double frictionShare = 1.0;  // of each contact's mu, for the pyramid
  // A contact counts when its normal force at rest is at least this share of the largest: one
  // the squeeze barely presses may be a gap within the contact search's reach.
  double leastShare = 0.01;
  int coneEdges = 8;  // the pyramid's edges, at least 3 (inscribed in the cone)
};

struct StaticHoldRequest {
  Vector3 acceleration = Vector3::Zero();  // the pull on the object and the links, mm/s^2
  StaticHoldMargins margins;
};

struct StaticHoldResult {
  bool holds = false;
  std::string reason;     // when it does not: why statics cannot say it holds
  double residual = 0.0;  // the equilibrium's error, in units of the object's weight
};

// Whether the settled `world` (every body at rest, contacts as `contacts` has them) holds body
// `object` under request.acceleration in an equilibrium as the header describes. Throws
// graspkit::Error for a bad object index or a request out of range.
StaticHoldResult staticHold(const World& world, int object, const HeldContacts& contacts,
                            const StaticHoldRequest& request);

}  // namespace graspkit
