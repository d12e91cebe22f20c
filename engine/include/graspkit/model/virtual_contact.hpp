#pragma once
// Virtual contacts: points on the hand's surface that the planner's energies use as if they
// touched the object.

#include <vector>

#include "graspkit/math/transform.hpp"

namespace graspkit {

struct VirtualContact {
  int finger = -1;  // chain index, -1 for the palm
  int link = 0;
  std::vector<Eigen::Matrix<double, 6, 1>> frictionEdges;
  Vector3 location = Vector3::Zero();            // mm, link frame
  Quaternion rotation = Quaternion::Identity();  // contact frame in link frame
  Vector3 translation = Vector3::Zero();
  Vector3 normal = Vector3::UnitZ();
  double sCof = 0.0;
};

class Robot;

// Virtual contacts for a hand whose file gives none (28 of GraspIt!'s 55 robot files, every URDF
// hand), derived from its geometry and its closing motion. The rule:
//   - a finger link gets one contact if it moves when the hand closes: each DOF is moved a small
//     step along its default velocity from the robot's current values, and a triangle of the
//     link's mesh belongs to the link's pad when its outward normal lies within 45 degrees of
//     the way its centroid moves;
//   - the palm gets one, its pad facing within 45 degrees of the approach direction;
//   - the contact sits on the pad's surface at the point nearest the pad's area-weighted centroid,
//     with the pad's area-weighted mean normal (pointing out of the link), GraspIt!'s contact
//     frame around it, 8 friction edges (a point contact with friction) and sCof 0.5.
// A link with no such triangles gets none. Locations and frames are in the link frame, as in a
// virtual-contact file.
std::vector<VirtualContact> deriveVirtualContacts(const Robot& robot);

// The virtual contacts a URDF or MJCF hand's setup keeps (docs/hands.md): of the derived ones,
// the palm's and each finger's last link's, where a finger is a chain whose tip reaches, with
// the DOFs at mid-range, at least 90 % as far from the palm as the farthest tip of every DOF that
// drives it. So a linkage's inner bars (a Robotiq's drivers, moved by the same DOF as its
// fingertips but ending nearer the palm) draw no contact, and the planner's energy pulls the
// object to the pads.
std::vector<VirtualContact> deriveFingertipContacts(const Robot& robot);

}  // namespace graspkit
