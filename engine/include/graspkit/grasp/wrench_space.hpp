#pragma once
// The grasp wrench space (GWS): the convex hull of the wrenches a grasp can apply to the object
// with bounded contact forces, as GraspIt! builds it (Ferrari & Canny).
//
//   L1         the hull of the union of every contact's wrenches (the sum of the normal forces
//              is at most 1);
//   LInfinity  the hull of the Minkowski sum over contacts of ({0} U the contact's wrenches)
//              (each normal force is at most 1). It has prod(k_i + 1) points for contacts with
//              k_i wrenches, so it grows fast: 4 point contacts give 9^4 = 6561 points.
//              Its many coplanar points often make qhull fail with GraspIt!'s options (a "wide
//              merge"); GraspIt! then reports epsilon -1 even for force-closure grasps.
//              graspkit retries with exact pre-merges alone ("Qx"), which builds the true
//              hull, but slowly (seconds for 6561 points).
//
// The hull is computed by qhull's reentrant library: every build uses its own qhT, so builds
// on different threads need no lock (GraspIt! serialises all qhull calls behind one global
// mutex). qhull's messages go to a memory buffer, never to stdout or stderr; a qhull failure
// (too few points, a flat or degenerate wrench set) is reported in the result, never thrown.

#include <array>
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>
#include "graspkit/base/enum_names.hpp"

#include "graspkit/collision/contact.hpp"  // Vector6

namespace graspkit {

enum class WrenchSpaceType { L1, LInfinity };
// "L1" or "Linf" ("LInfinity" accepted too) (base/enum_names.hpp).
std::span<const EnumName<WrenchSpaceType>> enumNames(std::type_identity<WrenchSpaceType>);

// How the wrench space is computed. qhull's merging ("C-0.0001") decides GraspIt!'s facets and
// volume: without it the volume comes out about 1e-4 larger and, on near-degenerate grasps,
// epsilon can differ by orders of magnitude; with exact options ("Qx", "Qt") it is no faster.
// So GraspIt and SkipNonForceClosure run qhull with GraspIt!'s options whenever they build a
// hull; they differ in when they skip it. NearestFacet builds no hull at all and gives the exact
// epsilon only; ExactHull is qhull's exact hull (timings of all four in
// bench/wrench_space_bench.cpp).
enum class HullMethod {
  // qhull on every wrench point with GraspIt!'s options "Qx QJ C-0.0001" (its output options
  // "Pp n" only affect printing): exact pre-merges, joggled input, centrum radius 1e-4.
  // qhull's joggle is seeded with a fixed seed, so results are reproducible.
  GraspIt,
  // For epsilon and force closure only. First looks for a plane through the origin that has
  // every wrench at least kForceClosureMargin beyond it (Gilbert's minimum-norm iteration, a
  // few microseconds). If there is one, the origin is outside the hull by more than qhull's
  // merges can move a facet, so GraspIt! reports epsilon -1 too: no hull is built and
  // GraspWrenchSpace::originOutside is set (volume and area are then unknown, NaN).
  // Otherwise it builds the hull exactly as GraspIt does.
  SkipNonForceClosure,
  // For epsilon and force closure only, where nothing is compared with GraspIt!'s figures (the
  // planner's potential-quality energies): the facet of the exact hull nearest the origin,
  // found without building the whole hull (nearestHullFacet(), grasp/nearest_facet.hpp).
  // `hyperplanes` holds that one facet when the origin is inside (so epsilonQuality() is the
  // exact epsilon); when the origin is outside, no facet and originOutside is set, as for
  // SkipNonForceClosure. Volume and area are NaN (unknown). It agrees with qhull's exact hull
  // ("Qt") to rounding, not with GraspIt!'s merged one, which can differ on near-degenerate
  // grasps. In 5 and 6 dimensions Gilbert's iteration runs first, as for SkipNonForceClosure.
  NearestFacet,
  // qhull on every wrench point with the exact options "Qt" (no joggle, no centrum radius, the
  // merged facets triangulated): the exact hull with its volume, which NearestFacet is checked
  // against (tests/unit/grasp/nearest_facet_test.cpp, bench/wrench_space_bench.cpp).
  ExactHull,
};

// How a method computes epsilon, for outputs that print it beside the epsilon:
// "qhull Qx QJ C-0.0001 (GraspIt!)" for GraspIt and SkipNonForceClosure, "nearest facet
// (exact)" for NearestFacet, "qhull Qt (exact)" for ExactHull.
std::string_view epsilonMethodName(HullMethod method);

// The margin, in wrench units (times the largest wrench norm when that exceeds 1), by which
// SkipNonForceClosure must find the origin outside the wrenches: ten times qhull's centrum
// radius 1e-4, so the merged hull GraspIt! builds cannot reach the origin.
inline constexpr double kForceClosureMargin = 1e-3;

// The most points a wrench space may be built from. Above it graspWrenchSpace() throws
// graspkit::Error rather than run out of memory or time: qhull in 6-D needs roughly
// 1 ms per 100 points and a few kB per facet. GraspIt! stops at INT_MAX / 6 (about 3.6e8).
inline constexpr std::size_t kMaxWrenchSpacePoints = 200000;

struct WrenchSpaceOptions {
  WrenchSpaceType type = WrenchSpaceType::L1;
  HullMethod method = HullMethod::GraspIt;
  // The wrench coordinates (fx, fy, fz, tx, ty, tz) the hull is built in; at least 2. The
  // hyperplanes keep six coordinates, with zeros in the unused ones (GraspIt!'s mask).
  std::array<bool, 6> dimensions = {true, true, true, true, true, true};
  std::size_t maxPoints = kMaxWrenchSpacePoints;
};

// A facet of the hull: the points w inside satisfy normal . w + offset <= 0 (qhull's
// convention). `normal` is a unit outward normal, so -offset is the signed distance of the
// origin from the facet plane: positive when the origin is on the inner side.
struct WrenchHyperplane {
  Vector6 normal = Vector6::Zero();
  double offset = 0.0;
};

struct GraspWrenchSpace {
  WrenchSpaceType type = WrenchSpaceType::L1;
  std::array<bool, 6> dimensions = {true, true, true, true, true, true};
  // True when the hull was built. When false, `failure` says why (no contacts, too few
  // dimensions, or qhull's own first error line, e.g. a flat wrench set) and the hull is empty.
  bool built = false;
  std::string failure;
  // HullMethod::SkipNonForceClosure or NearestFacet found the origin outside the wrenches and
  // built no hull: not force closure, epsilon -1, volume and area NaN (unknown).
  bool originOutside = false;
  std::vector<WrenchHyperplane> hyperplanes;
  double volume = 0.0;         // in the used dimensions, in (unit force)^d
  double area = 0.0;           // surface area of the hull
  std::size_t pointCount = 0;  // wrench points handed to qhull
};

// The points a wrench space is the hull of: the union of the sets (L1) or the Minkowski sum of
// ({0} U set) over the sets (LInfinity), in the full six coordinates. Throws graspkit::Error
// when there would be more than `maxPoints`.
std::vector<Vector6> wrenchSpacePoints(const std::vector<std::vector<Vector6>>& contactWrenches,
                                       WrenchSpaceType type,
                                       std::size_t maxPoints = kMaxWrenchSpacePoints);

// Builds the wrench space of a grasp from one wrench set per contact (see graspWrenches() in
// friction_cone.hpp). Throws graspkit::Error only for a request it refuses (too many points);
// everything qhull cannot build is a result with built = false.
GraspWrenchSpace graspWrenchSpace(const std::vector<std::vector<Vector6>>& contactWrenches,
                                  const WrenchSpaceOptions& options = {});

}  // namespace graspkit
