#pragma once
// A contact between two bodies, as GraspIt! defines it: two surfaces closer than the contact
// threshold and not interpenetrating. A contact is seen from one of its bodies (body1); mate()
// gives the same contact seen from the other. Everything is in world coordinates.

#include <vector>

#include "graspkit/base/enum_names.hpp"
#include "graspkit/math/transform.hpp"
#include "graspkit/model/body_ref.hpp"

namespace graspkit {

inline constexpr double kContactThreshold = 0.2;   // mm, GraspIt!'s Contact::THRESHOLD
inline constexpr double kDuplicateDistance = 3.0;  // mm, contacts closer on both bodies merge
inline constexpr double kKineticSpeed = 1.0;       // mm/s: above it, kinetic friction applies

enum class ContactModel {
  Frictionless,       // normal force only (mu = 0)
  PointWithFriction,  // Coulomb cone linearised by 8 edges
  SoftFinger,         // cone plus torsional friction, 20 edges (either body elastic)
};

using Vector6 = Eigen::Matrix<double, 6, 1>;

struct Contact {
  BodyRef body1;
  BodyRef body2;
  Vector3 position1 = Vector3::Zero();  // the contact point on body1, world, mm
  Vector3 position2 = Vector3::Zero();  // the contact point on body2, world, mm
  // Unit normal pointing into body1: the direction of the force body2 can push body1 with.
  Vector3 normal = Vector3::UnitZ();
  // Contact frame in the world: columns x, y, z with z = normal, x = normalise(n x X) (or
  // n x Z when n is nearly parallel to X), y = z x x.
  Matrix3 frame = Matrix3::Identity();
  double distance = 0.0;  // separation of the two points, mm (below the threshold)
  double mu = 0.0;        // friction coefficient from the two materials
  ContactModel model = ContactModel::PointWithFriction;
  // Soft fingers (see contact_patch.hpp): the largest torque about the normal per unit normal
  // force divided by mu, in mm (GraspIt!'s e_tau), and the relative radii of curvature of the
  // two surfaces that it came from (mm, kFlatRelativeRadius where the pair is flat). They
  // belong to the pair, so mate() keeps them. All 0 for other contacts.
  double torsion = 0.0;
  double patchRadius1 = 0.0;
  double patchRadius2 = 0.0;

  // The same contact seen from body2: bodies and points swapped, normal negated.
  Contact mate() const;
};

// "frictionless", "point" or "soft_finger": how reports and scripts name a contact model
// (base/enum_names.hpp: nameOf, valueNamed, parseNamed).
std::span<const EnumName<ContactModel>> enumNames(std::type_identity<ContactModel>);

}  // namespace graspkit
