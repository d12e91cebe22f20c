#pragma once
// Internal: breakaway clutches in a simulation (GraspIt!'s `b` DOFs, the Barrett hand's
// TorqueSwitch). A breakaway DOF drives its joints through a clutch each; when the contacts
// on the links a joint carries push back on that joint harder than the DOF's breakAwayTorque,
// the clutch slips: the joint stays where it is (its worm gear holds it) and the DOF goes on
// driving the joints beyond it, as the static autograsp does when a proximal link touches.
// The clutch takes hold again when the DOF comes back to where the joint broke away.

#include <vector>

#include "graspkit/model/world.hpp"

namespace graspkit::dynamics {

// GraspIt!'s breakAwayTorque is N*mm once read (the files give N*m); the simulation's torques
// are g*mm^2/s^2.
constexpr double kNewtonMillimetre = 1.0e6;

// Updates the clutches of every robot in `next` (the world after a step of h) from the contact
// impulses the step applied (`impulses`, as World::lastImpulses, points in body1's frame at
// `before`'s poses).
void updateBreakawayClutches(const World& before, World& next,
                             const std::vector<ContactImpulse>& impulses, double h);

}  // namespace graspkit::dynamics
