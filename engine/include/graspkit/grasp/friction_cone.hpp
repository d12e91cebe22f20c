#pragma once
// The linearised friction cone of a contact, as GraspIt! builds it, and the wrenches a contact
// can apply to the grasped object.
//
// GraspIt! samples a friction "ellipsoid" in (tangential force x, tangential force y, torque
// about the normal) with semi-axes (1, 1, e_tau): at each of a few latitudes phi it takes
// equally spaced longitudes theta = j * 2 pi / n_phi, starting at theta = 0 on the contact
// frame's x axis, and scales the direction (cos theta cos phi, sin theta cos phi, sin phi) onto
// the ellipsoid. Each sample plus a unit normal force is one edge of the cone:
//   point contact with friction  8 edges, phi = 0 (every 45 deg from x);
//   soft finger                  20 edges, phi = 90, 45, 0, -45, -90 deg with 1, 5, 8, 5, 1
//                                longitudes (the poles are the pure torsion edges);
//   frictionless                 1 edge, the normal force alone.
// (GraspIt! gives a mu = 0 point contact 8 coincident normal edges; one spans the same hull.)

#include <vector>

#include "graspkit/collision/contact.hpp"

namespace graspkit {

// One sampled latitude of the friction ellipsoid.
struct FrictionLatitude {
  double phi;  // latitude, radians: 0 = pure tangential friction, +-pi/2 = pure torsion
  int count;   // longitudes at this latitude, the first at theta = 0
};

// The latitudes GraspIt! samples for a contact model (empty for Frictionless).
std::vector<FrictionLatitude> frictionLatitudes(ContactModel model);

// The cone edges in the contact frame as wrenches per unit normal force, before friction is
// scaled by mu: (e_x, e_y, 1, 0, 0, e_tau) with (e_x, e_y, e_tau) on the ellipsoid
// e_x^2 + e_y^2 + (e_tau / eccentricity_tau)^2 = 1. Frictionless gives the single edge
// (0, 0, 1, 0, 0, 0). `torsion` is the soft-finger e_tau in mm (ignored by point contacts);
// throws graspkit::Error when it is negative or not finite.
std::vector<Vector6> frictionEdges(ContactModel model, double torsion = 0.0);

// The wrenches one contact can apply to the object, in world coordinates about the object's
// centre of gravity, one per cone edge, for a unit normal force:
//   f   = n e_z + mu (e_x t_x + e_y t_y)
//   tau = (r x f + mu e_tau n) / maxRadius,   r = contact point - CoG.
// `objectSideContact` is the contact seen from the object (body1 = the object: its position1
// lies on the object and its normal points into the object, along the force the hand applies).
// Dividing torque by the object's maxRadius makes it commensurate with force, as GraspIt! does.
// A contact with mu = 0 counts as frictionless, whatever its model (as in GraspIt!).
std::vector<Vector6> contactWrenches(const Contact& objectSideContact, const Vector3& cogWorld,
                                     double maxRadius);

// contactWrenches for each contact of a grasp: the input of graspWrenchSpace().
std::vector<std::vector<Vector6>> graspWrenches(const std::vector<Contact>& objectSideContacts,
                                                const Vector3& cogWorld, double maxRadius);

}  // namespace graspkit
