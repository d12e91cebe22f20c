#include "graspkit/grasp/wrench_space.hpp"

#include <algorithm>
#include <limits>

#include <fmt/format.h>

extern "C" {
#include <libqhull_r/qhull_ra.h>
}

#include "graspkit/base/error.hpp"
#include "graspkit/grasp/nearest_facet.hpp"
#include "math/qhull_run.hpp"

namespace graspkit {

namespace {

// The hull of the packed wrenches into `gws`: its facets (normals expanded to six coordinates by
// gws.dimensions), volume and area, or gws.built = false with qhull's reason.
void hullOfWrenches(std::vector<double>& coords, int dim, const char* options,
                    GraspWrenchSpace& gws) {
  gws.pointCount = coords.size() / static_cast<std::size_t>(dim);
  gws.built = false;
  gws.hyperplanes.clear();
  gws.volume = gws.area = 0.0;
  std::optional<std::string> failure = detail::runQhull(coords, dim, options, [&](qhT* qh) {
    qh_getarea(qh, qh->facet_list);
    gws.volume = qh->totvol;
    gws.area = qh->totarea;
    gws.hyperplanes.reserve(static_cast<std::size_t>(qh->num_facets));
    facetT* facet;
    FORALLfacets {
      WrenchHyperplane plane;
      int k = 0;
      for (int d = 0; d < 6; ++d)
        if (gws.dimensions[d]) plane.normal[d] = facet->normal[k++];
      plane.offset = facet->offset;
      gws.hyperplanes.push_back(plane);
    }
  });
  gws.built = !failure;
  if (failure) gws.failure = *failure;
}

}  // namespace

namespace {

// GraspIt!'s qhull options without the output ones ("Pp n"): Qx exact pre-merges, QJ joggled
// input, C-0.0001 a centrum radius for merging.
constexpr const char* kGraspItOptions = "Qx QJ C-0.0001";
constexpr const char* kLInfinityFallbackOptions = "Qx";
// The exact hull: no joggle, no centrum radius; qhull's merges of coplanar facets triangulated.
constexpr const char* kExactOptions = "Qt";

// The number of points, as a double so that a huge Minkowski sum cannot overflow.
double pointCount(const std::vector<std::vector<Vector6>>& sets, WrenchSpaceType type) {
  double count = type == WrenchSpaceType::L1 ? 0.0 : 1.0;
  for (const auto& set : sets) {
    const double k = static_cast<double>(set.size());
    count = type == WrenchSpaceType::L1 ? count + k : count * (k + 1.0);
  }
  return count;
}

// True when some plane through the origin has every point at least `margin` beyond it, i.e.
// the origin is outside conv(points) by at least `margin`. Gilbert's algorithm: x walks
// through conv(points) towards the point nearest the origin; the point s minimising x . s
// bounds that distance from below by x . s / |x|. Gives up (false) when x comes within
// `margin` of the origin or after a fixed number of steps, leaving the answer to qhull.
bool originClearlyOutside(const std::vector<double>& coords, int dim, double margin) {
  using Vec = Eigen::VectorXd;
  const Eigen::Index n = static_cast<Eigen::Index>(coords.size()) / dim;
  const Eigen::Map<const Eigen::MatrixXd> points(coords.data(), dim, n);
  Vec x = points.rowwise().mean();
  for (int step = 0; step < 1000; ++step) {
    const double norm = x.norm();
    if (norm < margin) return false;
    Eigen::Index nearest = 0;
    const double support = (x.transpose() * points).minCoeff(&nearest);
    if (support >= margin * norm) return true;
    const Vec d = x - points.col(nearest);
    const double dd = d.squaredNorm();
    if (dd == 0.0) return false;
    x -= std::clamp(x.dot(d) / dd, 0.0, 1.0) * d;
  }
  return false;
}

// The largest wrench norm, at least 1: the scale of SkipNonForceClosure's margin.
double wrenchScale(const std::vector<Vector6>& points) {
  double scale = 1.0;
  for (const Vector6& p : points) scale = std::max(scale, p.norm());
  return scale;
}

void markOriginOutside(GraspWrenchSpace& gws, std::size_t pointCount, const char* how) {
  gws.pointCount = pointCount;
  gws.originOutside = true;
  gws.volume = gws.area = std::numeric_limits<double>::quiet_NaN();
  gws.failure = fmt::format("not force closure: the origin is outside the wrenches ({})", how);
}

// HullMethod::NearestFacet: the one facet of the exact hull that decides epsilon. Should
// rounding defeat the search (never in nearest_facet_test's 11,000 random wrench sets; 5 of
// some 640 UMI gripper closes on seed 11's objects, whose pad contacts share planes), qhull's
// exact hull ("Qt") answers instead.
void nearestFacetOfWrenches(std::vector<double>& coords, int dim, GraspWrenchSpace& gws) {
  const Eigen::Index n = static_cast<Eigen::Index>(coords.size()) / dim;
  const NearestFacet nearest =
      nearestHullFacet(Eigen::Map<const Eigen::MatrixXd>(coords.data(), dim, n));
  switch (nearest.origin) {
    case OriginPlacement::Outside:
      markOriginOutside(gws, static_cast<std::size_t>(n), "a supporting facet separates them");
      return;
    case OriginPlacement::Flat:
      gws.pointCount = static_cast<std::size_t>(n);
      gws.failure = fmt::format("the wrenches span fewer than {} dimensions (flat)", dim);
      return;
    case OriginPlacement::Unresolved:
      hullOfWrenches(coords, dim, kExactOptions, gws);
      break;
    case OriginPlacement::Inside: {
      gws.pointCount = static_cast<std::size_t>(n);
      WrenchHyperplane plane;
      int k = 0;
      for (int d = 0; d < 6; ++d)
        if (gws.dimensions[d]) plane.normal[d] = nearest.normal[k++];
      plane.offset = nearest.offset;
      gws.hyperplanes = {plane};
      gws.built = true;
      break;
    }
  }
  gws.volume = gws.area = std::numeric_limits<double>::quiet_NaN();
}

}  // namespace

std::string_view epsilonMethodName(HullMethod method) {
  switch (method) {
    case HullMethod::NearestFacet:
      return "nearest facet (exact)";
    case HullMethod::ExactHull:
      return "qhull Qt (exact)";
    default:
      return "qhull Qx QJ C-0.0001 (GraspIt!)";
  }
}

std::span<const EnumName<WrenchSpaceType>> enumNames(std::type_identity<WrenchSpaceType>) {
  static constexpr EnumName<WrenchSpaceType> kNames[] = {{WrenchSpaceType::L1, "L1"},
                                                         {WrenchSpaceType::LInfinity, "Linf"},
                                                         {WrenchSpaceType::LInfinity, "LInfinity"}};
  return kNames;
}

std::vector<Vector6> wrenchSpacePoints(const std::vector<std::vector<Vector6>>& contactWrenches,
                                       WrenchSpaceType type, std::size_t maxPoints) {
  const double count = pointCount(contactWrenches, type);
  if (count > static_cast<double>(maxPoints))
    throw Error(
        fmt::format("the {} wrench space of {} contacts would have {:.0f} points, more "
                    "than the limit of {}",
                    type == WrenchSpaceType::L1 ? "L1" : "L-infinity", contactWrenches.size(),
                    count, maxPoints));

  std::vector<Vector6> points;
  points.reserve(static_cast<std::size_t>(count));
  if (type == WrenchSpaceType::L1) {
    for (const auto& set : contactWrenches) points.insert(points.end(), set.begin(), set.end());
    return points;
  }
  // Minkowski sum of ({0} U set) over the sets, one set at a time.
  points.push_back(Vector6::Zero());
  for (const auto& set : contactWrenches) {
    const std::size_t previous = points.size();
    for (const Vector6& w : set)
      for (std::size_t i = 0; i < previous; ++i) points.push_back(points[i] + w);
  }
  return points;
}

GraspWrenchSpace graspWrenchSpace(const std::vector<std::vector<Vector6>>& contactWrenches,
                                  const WrenchSpaceOptions& options) {
  GraspWrenchSpace gws;
  gws.type = options.type;
  gws.dimensions = options.dimensions;
  int dim = 0;
  for (bool used : options.dimensions) dim += used ? 1 : 0;
  if (dim < 2) {
    gws.failure = fmt::format("a wrench space needs at least 2 dimensions, {} selected", dim);
    return gws;
  }
  const std::vector<Vector6> points =
      wrenchSpacePoints(contactWrenches, options.type, options.maxPoints);
  if (contactWrenches.empty() || points.empty()) {
    gws.failure = "no contact wrenches";
    return gws;
  }

  std::vector<double> coords;
  coords.reserve(points.size() * static_cast<std::size_t>(dim));
  for (const Vector6& p : points)
    for (int d = 0; d < 6; ++d)
      if (options.dimensions[d]) coords.push_back(p[d]);
  // Gilbert's iteration proves most non-force-closure grasps in a few microseconds. Before the
  // nearest-facet search it pays in 5 and 6 dimensions only (random 6-D grasps: 22 us against
  // the search's 99 us when the origin is outside, 55 us wasted when inside); in 3-D the search
  // alone is as fast as the iteration (10 us).
  const bool gilbertFirst = options.method == HullMethod::SkipNonForceClosure ||
                            (options.method == HullMethod::NearestFacet && dim >= 5);
  if (gilbertFirst &&
      originClearlyOutside(coords, dim, kForceClosureMargin * wrenchScale(points))) {
    markOriginOutside(gws, points.size(), "hull skipped");
    return gws;
  }
  if (options.method == HullMethod::NearestFacet) {
    nearestFacetOfWrenches(coords, dim, gws);
    return gws;
  }
  if (options.method == HullMethod::ExactHull) {
    hullOfWrenches(coords, dim, kExactOptions, gws);
    return gws;
  }
  // qhull may joggle a copy, but keep the input intact for a second attempt.
  std::vector<double> input =
      options.type == WrenchSpaceType::LInfinity ? coords : std::vector<double>{};
  hullOfWrenches(coords, dim, kGraspItOptions, gws);
  if (!gws.built && options.type == WrenchSpaceType::LInfinity) {
    // The Minkowski sum is full of coplanar points, where joggling plus merging often ends in
    // a "wide merge" error (GraspIt! then reports epsilon -1 for a force-closure grasp). Exact
    // pre-merges alone ("Qx") build the true hull.
    const std::string first_failure = gws.failure;
    hullOfWrenches(input, dim, kLInfinityFallbackOptions, gws);
    if (!gws.built) gws.failure = first_failure + "; with Qx alone: " + gws.failure;
  }
  return gws;
}

}  // namespace graspkit
