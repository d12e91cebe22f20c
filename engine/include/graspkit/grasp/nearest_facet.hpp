#pragma once
// The facet of a point set's convex hull nearest the origin, found without building the whole
// hull: Ferrari and Canny's epsilon is the origin's distance from that facet.
//
// An expanding-polytope search (EPA, as in collision detection, here in 2 to 6 dimensions):
// the polytope Q is the hull of a growing subset of the points, kept as simplicial facets in a
// priority queue by the signed distance of the origin beyond each facet's plane. The facet in
// front of the origin the most (the nearest one once the origin is inside) is taken; the point
// farthest beyond it (the support point in its normal's direction, a scan over the points) is
// added when it lies beyond by more than a tolerance, replacing the facets it sees with a cone
// from their horizon (where rounding leaves that horizon open, as coplanar contacts can, the
// facets the point lies below by up to 100 tolerances join the cone). Otherwise that facet's plane
// supports the whole set, and since Q lies inside the set's hull, the facet is one of the hull's
// and the nearest: its distance is epsilon (when the origin is beyond it, the origin is outside the
// hull). Each point is added at most once, and the search stays near the origin, so only a fraction
// of the hull's facets is ever built.

#include <Eigen/Core>

namespace graspkit {

enum class OriginPlacement {
  Inside,      // within the hull (or on its boundary): the facet is the nearest, epsilon >= 0
  Outside,     // beyond the facet's plane, which supports the whole set: epsilon -1
  Flat,        // the points span fewer dimensions than they have (to 1000 tolerances): epsilon -1
  Unresolved,  // rounding broke the polytope's bookkeeping: ask an exact hull (qhull "Qt")
};

struct NearestFacet {
  OriginPlacement origin = OriginPlacement::Unresolved;
  // A unit outward normal and offset in the points' coordinates, qhull's convention: the points
  // satisfy normal . x + offset <= 0, so -offset is the origin's distance inside the facet.
  Eigen::VectorXd normal;
  double offset = 0.0;
  int pointsAdded = 0;    // vertices of the final polytope Q
  int facetsCreated = 0;  // every simplicial facet Q ever had, initial simplex included
};

// The points are the columns (2 to 6 rows). A point counts as beyond a facet when it is more
// than `tolerance` beyond its plane; the default, 1e-12 times the largest point norm, lies
// above the rounding of the planes (about 1e-15 of it) and bounds the error in epsilon.
NearestFacet nearestHullFacet(const Eigen::Ref<const Eigen::MatrixXd>& points,
                              double tolerance = -1.0);

}  // namespace graspkit
