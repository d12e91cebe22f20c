#pragma once
// The soft-finger contact patch, as GraspIt! builds it (its SoftContact, after Johnson, Contact
// Mechanics, ch. 4). Where an elastic body touches another, each body's surface near the contact
// is fitted with a paraboloid; the two fits give the relative radii of curvature of the pair;
// a "mattress" (an elastic layer of fixed depth on a rigid core) pressed by a normal force then
// gives the contact ellipse, and the ellipse the largest torque about the normal per unit of
// mu times the normal force: the soft finger's e_tau (Contact::torsion).
//
// Lengths are mm, Young's moduli Pa, forces N.

#include <span>

#include "graspkit/math/transform.hpp"

namespace graspkit {

inline constexpr double kMattressDepth = 3.0;        // mm, GraspIt!'s hard-wired layer depth
inline constexpr double kFlatRelativeRadius = 20.0;  // mm, stands in for a degenerate radius
inline constexpr double kStaticNormalForce = 5.0;    // N, GraspIt!'s normal force in statics

// z = a x^2 + b y^2 + c x y in a contact frame: origin at the contact, z along the normal into
// the body, so a convex surface has a, b > 0.
struct Paraboloid {
  double a = 0.0;  // 1/mm
  double b = 0.0;
  double c = 0.0;
};

// The least-squares paraboloid through `points` (contact frame, mm). Coefficients smaller than
// 1e-6 /mm become 0 (GraspIt!'s "almost planar"); too few points to pin the three down give the
// flat paraboloid.
Paraboloid fitParaboloid(std::span<const Vector3> points);

// A paraboloid's principal radii of curvature, mm, with -1 marking a flat direction (curvature
// within 1e-6 /mm of 0, as GraspIt! decides it); a concave direction has a negative radius.
// `direction` is the unit tangent (contact frame, z = 0) along which r1 is measured.
struct PrincipalRadii {
  double r1 = -1.0;
  double r2 = -1.0;
  Vector3 direction = Vector3::UnitX();
};
PrincipalRadii principalRadii(const Paraboloid& surface);

// The relative radii of two surfaces pressed together (Johnson 4.2), from each surface's
// principal radii and the angle between their first principal directions: r1 = 1/(A+B + A-B)
// <= r2 = 1/(A+B - (A-B)). Negative radii count as flat. A relative radius is -1 where the
// relative curvature vanishes (two planes; a cylinder on a plane along its axis).
struct RelativeRadii {
  double r1 = -1.0;
  double r2 = -1.0;
};
RelativeRadii relativeRadii(const PrincipalRadii& surface1, const PrincipalRadii& surface2,
                            double angle);

// The mattress model: a layer of depth kMattressDepth and modulus `youngs` pressed by
// `normal_force` sinks by delta = sqrt(N h / (E pi sqrt(R1' R2'))); the contact ellipse has
// semi-axes sqrt(2 delta R1') and sqrt(2 delta R2'), and the largest torque about the normal is
// mu N times 8 sqrt(ab) / 15. Degenerate radii become kFlatRelativeRadius.
struct ContactEllipse {
  double semiMajor = 0.0;  // mm
  double semiMinor = 0.0;  // mm
  double torsion = 0.0;    // mm: the largest torque / (mu N), the friction ellipsoid's e_tau
};
ContactEllipse mattressEllipse(RelativeRadii radii, double youngs, double normal_force);

// How far around a contact the surface is fitted: 0.4 * 1000 * (1/E)^0.333 mm (GraspIt!'s
// exponent and fudge factor), about 3.5 mm for rubber at 1.5e6 Pa.
double patchNeighbourhoodRadius(double youngs);

}  // namespace graspkit
