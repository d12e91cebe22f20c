#pragma once
// Grasp quality measures over the grasp wrench space, registered by name so that a plugin can
// add its own. The built-ins are GraspIt!'s:
//   "epsilon"  the radius of the largest ball about the origin inside the wrench space: the
//              smallest distance from the origin to a facet hyperplane (Ferrari & Canny); -1
//              when the grasp is not force closure or the hull could not be built;
//   "volume"   the volume of the wrench space; 0 when the hull could not be built (no force
//              closure check); NaN when HullMethod::SkipNonForceClosure skipped the hull.
// and one of graspkit's own:
//   "weight"   the largest pure force through the object's centre of mass (no torque) that the
//              grasp resists in every direction: what it can do against the object's weight,
//              however the object is turned, in units of the contacts' normal force
//              (weightQuality()).
// Names are case-sensitive.

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "graspkit/grasp/wrench_space.hpp"

namespace graspkit {

class QualityMeasure {
 public:
  virtual ~QualityMeasure() = default;
  virtual std::string name() const = 0;
  // Larger is better. A measure must not throw for a wrench space that was not built.
  virtual double evaluate(const GraspWrenchSpace& gws) const = 0;
};

using QualityMeasureFactory = std::function<std::unique_ptr<QualityMeasure>()>;

// The engine's own measures, "epsilon" and "volume", with their factories: the Registry
// (plugin/registry.hpp) starts with them, and plugins add more there.
std::vector<std::pair<std::string, QualityMeasureFactory>> builtinQualityMeasures();

// The smallest epsilon (GraspIt!'s units: the distance from the origin to the nearest facet of
// the grasp wrench space, forces in units of the contact's normal force, torques divided by the
// object's max radius) that counts as force closure. A grasp is force closure when the origin
// lies inside the wrench space by at least this much, not merely inside: qhull decides each
// facet's offset to within its precision (about 1e-12 to 1e-9 for these hulls, more after the
// exact pre-merges of a retried hull), so an epsilon of 6.9e-11 says "the origin sits on the
// hull", and rounding alone would decide whether such a grasp resists every wrench. Real
// force-closure grasps have epsilons of 1e-3 to 0.5 (plannerMug's best: 0.2), so 1e-6 lies three
// orders of magnitude above qhull's noise and three below the weakest grasp worth keeping; a
// grasp below it resists some wrench only with forces a million times its contact forces.
inline constexpr double kForceClosureEpsilon = 1e-6;

// The one decision every output makes (grasps, plans, datasets, the C ABI, Lua, Python): an
// epsilon (epsilonQuality(), -1 when the origin is outside) is force closure when it is at
// least kForceClosureEpsilon. NaN is not.
bool isForceClosure(double epsilon);

// isForceClosure(epsilonQuality(gws)): the origin lies inside the built wrench space, every facet
// at least kForceClosureEpsilon from it. GraspIt! only looks for offsets > 0, so a grasp whose
// origin sits on the hull within rounding (epsilon 0 or 6.9e-11) is force closure to it, or not,
// as rounding falls; here it is not (its epsilon is still reported as computed).
bool isForceClosure(const GraspWrenchSpace& gws);

// The built-in measures as plain functions.
double epsilonQuality(const GraspWrenchSpace& gws);
double volumeQuality(const GraspWrenchSpace& gws);

// The radius of the largest ball about the origin inside the wrench space's slice of zero torque:
// the largest force through the centre of mass (GraspIt!'s torque origin) that the grasp resists
// whatever its direction, with the wrench space's bounded contact forces. The slice keeps the
// facets' inequalities n.w + offset <= 0 with w = (f, 0), so the radius is the smallest
// -offset / |n_force| over the facets; facets of torque alone do not bound it. Epsilon is the
// same radius over every wrench, so weight >= epsilon always. A grasp wins a pull of the object's
// weight m g when its contacts can press with a total normal force of about m g / weight (L1
// space; each contact m g / weight for LInfinity) or more. -1 when the origin is outside the
// hull or the hull was not built (not force closure); NaN for HullMethod::NearestFacet's one
// facet, which does not bound the slice (its volume is NaN too), and for a space built without
// the force coordinates.
double weightQuality(const GraspWrenchSpace& gws);

}  // namespace graspkit
