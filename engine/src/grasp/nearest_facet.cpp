#include "graspkit/grasp/nearest_facet.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <queue>
#include <utility>
#include <vector>

namespace graspkit {
namespace {

constexpr int kMaxDim = 6;
// A set thinner than this many tolerances is flat: its epsilon could be no more than half its
// thickness (1e-9 of its size by default, far below kForceClosureEpsilon for wrenches of unit
// size), and a thinner first simplex could not orient the facets reliably.
constexpr double kFlatFactor = 1e3;
// How far below a facet's plane, in tolerances, a point may lie and still take the facet into
// its cone when the facets it strictly sees leave a horizon that does not close (addPoint).
constexpr double kCoplanarFactor = 100.0;
using Points = Eigen::Ref<const Eigen::MatrixXd>;

// A simplicial facet: D vertices, and across the ridge opposite vertex[i] the facet neighbor[i].
template <int D>
struct Facet {
  std::array<int, D> vertex{};
  std::array<int, D> neighbor{};
  Eigen::Matrix<double, D, 1> normal = Eigen::Matrix<double, D, 1>::Zero();
  double offset = 0.0;
  bool alive = true;
  int visited = -1;  // the step whose visible set last took this facet
};

// A ridge of the horizon's cone seen from one new facet: the facet, the position of the vertex
// opposite the ridge, and the ridge's vertices other than the apex, sorted (the key that the
// neighbouring new facet shares).
struct ConeRidge {
  std::array<int, kMaxDim> key{};
  int facet = 0;
  int position = 0;
};

// The search in D dimensions: fixed-size vectors make a facet's plane a few hundred flops.
template <int D>
class ExpandingPolytope {
  using Vec = Eigen::Matrix<double, D, 1>;
  using Mat = Eigen::Matrix<double, D, D>;
  using Facet = graspkit::Facet<D>;
  static constexpr int dim_ = D;

 public:
  ExpandingPolytope(const Points& points, double tolerance)
      : tolerance_(tolerance), added_(static_cast<std::size_t>(points.cols()), false) {
    points_.reserve(static_cast<std::size_t>(points.cols()));
    for (Eigen::Index i = 0; i < points.cols(); ++i) points_.push_back(points.col(i));
  }

  NearestFacet run() {
    NearestFacet result;
    if (!initialSimplex()) {
      result.origin = OriginPlacement::Flat;
      return result;
    }
    for (;;) {
      const int f = nearestLiveFacet();
      if (f < 0) return result;  // Unresolved: the queue ran dry
      const auto [beyond, distance] = supportPoint(facets_[static_cast<std::size_t>(f)]);
      if (beyond < 0 || distance <= tolerance_) return finish(f, result);
      if (!addPoint(beyond, f)) return result;  // Unresolved
    }
  }

 private:
  // Greedy: each next vertex is the point farthest from the affine hull of those chosen, so the
  // simplex is far from flat whenever the set is; its centroid then orients every later facet.
  bool initialSimplex() {
    const int n = static_cast<int>(points_.size());
    if (n <= dim_) return false;
    Vec mean = Vec::Zero();
    for (const Vec& p : points_) mean += p;
    mean /= n;
    std::vector<int> chosen = {0};
    for (int i = 1; i < n; ++i)
      if ((point(i) - mean).squaredNorm() > (point(chosen[0]) - mean).squaredNorm()) chosen[0] = i;
    Mat basis = Mat::Zero();
    for (int k = 0; k < dim_; ++k) {
      const Vec& origin = point(chosen.front());
      double farthest = -1.0;
      Vec farthestOffset = Vec::Zero();
      int pick = -1;
      for (int i = 0; i < n; ++i) {
        Vec r = point(i) - origin;
        orthogonalise(r, basis, k);
        const double d2 = r.squaredNorm();
        if (d2 > farthest) farthest = d2, pick = i, farthestOffset = r;
      }
      if (pick < 0 || std::sqrt(farthest) <= kFlatFactor * tolerance_) return false;
      chosen.push_back(pick);
      basis.col(k) = farthestOffset.normalized();
    }
    interior_ = Vec::Zero();
    for (int v : chosen) interior_ += point(v);
    interior_ /= static_cast<double>(dim_ + 1);
    // Facet i is the simplex's face opposite chosen[i]; its ridge opposite chosen[j] is shared
    // with facet j.
    for (int i = 0; i <= dim_; ++i) {
      Facet facet;
      int slot = 0;
      for (int j = 0; j <= dim_; ++j) {
        if (j == i) continue;
        facet.vertex[static_cast<std::size_t>(slot)] = chosen[static_cast<std::size_t>(j)];
        facet.neighbor[static_cast<std::size_t>(slot)] = j;
        ++slot;
      }
      push(std::move(facet));
    }
    for (int v : chosen) added_[static_cast<std::size_t>(v)] = true;
    return true;
  }

  // The plane through the facet's vertices: its normal is what remains of the direction from
  // the interior point to the facet after projecting out the facet's edges (modified
  // Gram-Schmidt, each step twice, which keeps the basis orthogonal to rounding). That
  // direction has a component along the normal of at least the interior point's distance from
  // the facet, so nothing cancels, and the normal comes out oriented outward.
  void computePlane(Facet& facet) const {
    const Vec& base = point(facet.vertex[0]);
    Mat basis;
    for (int k = 1; k < dim_; ++k) {
      Vec e = point(facet.vertex[static_cast<std::size_t>(k)]) - base;
      orthogonalise(e, basis, k - 1);
      basis.col(k - 1) = e.normalized();
    }
    Vec normal = base - interior_;
    orthogonalise(normal, basis, dim_ - 1);
    facet.normal = normal.normalized();
    double sum = 0.0;
    for (int k = 0; k < dim_; ++k)
      sum += facet.normal.dot(point(facet.vertex[static_cast<std::size_t>(k)]));
    facet.offset = -sum / dim_;
  }

  const Vec& point(int i) const { return points_[static_cast<std::size_t>(i)]; }

  static void orthogonalise(Vec& v, const Mat& basis, int columns) {
    for (int pass = 0; pass < 2; ++pass)
      for (int j = 0; j < columns; ++j) v -= basis.col(j).dot(v) * basis.col(j);
  }

  int push(Facet facet) {
    computePlane(facet);
    const int id = static_cast<int>(facets_.size());
    queue_.emplace(facet.offset, id);
    facets_.push_back(std::move(facet));
    return id;
  }

  // The live facet with the origin farthest in front of it (largest offset); dead ones, left in
  // the queue when a point replaced them, are skipped.
  int nearestLiveFacet() {
    while (!queue_.empty()) {
      const int f = queue_.top().second;
      queue_.pop();
      if (facets_[static_cast<std::size_t>(f)].alive) return f;
    }
    return -1;
  }

  // The point not yet a vertex of Q that is farthest beyond the facet's plane, and how far.
  std::pair<int, double> supportPoint(const Facet& facet) const {
    int best = -1;
    double farthest = -std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < points_.size(); ++i) {
      if (added_[i]) continue;
      const double d = facet.normal.dot(points_[i]) + facet.offset;
      if (d > farthest) farthest = d, best = static_cast<int>(i);
    }
    return {best, farthest};
  }

  NearestFacet finish(int f, NearestFacet& result) const {
    const Facet& facet = facets_[static_cast<std::size_t>(f)];
    result.origin = facet.offset > 0.0 ? OriginPlacement::Outside : OriginPlacement::Inside;
    result.normal = facet.normal;
    result.offset = facet.offset;
    result.pointsAdded = static_cast<int>(std::count(added_.begin(), added_.end(), true));
    result.facetsCreated = static_cast<int>(facets_.size());
    return result;
  }

  bool sees(const Facet& facet, int point, double threshold) const {
    return facet.normal.dot(this->point(point)) + facet.offset > threshold;
  }

  // The facets the point sees, connected to `start` (which it sees), marked `step`.
  std::vector<int> visibleFrom(int point, int start, int step, double threshold) {
    std::vector<int> visible = {start};
    facets_[static_cast<std::size_t>(start)].visited = step;
    for (std::size_t k = 0; k < visible.size(); ++k) {
      const Facet& facet = facets_[static_cast<std::size_t>(visible[k])];
      for (int i = 0; i < dim_; ++i) {
        const int g = facet.neighbor[static_cast<std::size_t>(i)];
        Facet& other = facets_[static_cast<std::size_t>(g)];
        if (other.visited == step || !sees(other, point, threshold)) continue;
        other.visited = step;
        visible.push_back(g);
      }
    }
    return visible;
  }

  // A ridge of the horizon: visible facet `seen` meets facet `outside`, which the point does not
  // see, across the ridge opposite the seen facet's vertex `position`.
  struct HorizonRidge {
    int seen = 0;
    int position = 0;
    int outside = 0;
  };

  // Replaces the facets the point sees by the cone from the point to their horizon. Facets that
  // lie within rounding of the point's own hyperplane (coplanar contacts on one finger pad give
  // many) can be seen from some sides and not from others, and the horizon then does not close.
  // The point then also takes the facets it lies below by up to 1 and then 100 tolerances: the
  // cone cuts from Q a sliver no thicker than that, 1e-10 of the points' size, which bounds what
  // it can change in epsilon. False, with Q unchanged, when no horizon closes.
  bool addPoint(int point, int start) {
    for (double threshold : {tolerance_, -tolerance_, -kCoplanarFactor * tolerance_})
      if (addPoint(point, start, threshold)) return true;
    return false;
  }

  // addPoint() with the facets whose plane the point lies more than `threshold` beyond.
  bool addPoint(int point, int start, double threshold) {
    const int step = ++visits_;
    const std::vector<int> visible = visibleFrom(point, start, step, threshold);
    std::vector<HorizonRidge> horizon;
    for (int f : visible) {
      const Facet& seen = facets_[static_cast<std::size_t>(f)];
      for (int i = 0; i < dim_; ++i) {
        const int outside = seen.neighbor[static_cast<std::size_t>(i)];
        const Facet& other = facets_[static_cast<std::size_t>(outside)];
        if (other.visited == step) continue;
        if (std::find(other.neighbor.begin(), other.neighbor.begin() + dim_, f) ==
            other.neighbor.begin() + dim_)
          return false;
        horizon.push_back({f, i, outside});
      }
    }
    // The cone's facets, checked to pair up across their ridges before Q changes.
    std::vector<Facet> cone;
    std::vector<ConeRidge> ridges;
    for (const HorizonRidge& ridge : horizon) {
      Facet facet;
      facet.vertex = facets_[static_cast<std::size_t>(ridge.seen)].vertex;
      facet.vertex[static_cast<std::size_t>(ridge.position)] = point;
      facet.neighbor[static_cast<std::size_t>(ridge.position)] = ridge.outside;
      addConeRidges(facet, static_cast<int>(facets_.size() + cone.size()), ridge.position, ridges);
      cone.push_back(std::move(facet));
    }
    if (!pairRidges(ridges)) return false;
    // The horizon is closed: the cone replaces the visible facets.
    for (std::size_t k = 0; k < cone.size(); ++k) {
      const HorizonRidge& ridge = horizon[k];
      const int id = push(std::move(cone[k]));
      Facet& kept = facets_[static_cast<std::size_t>(ridge.outside)];
      *std::find(kept.neighbor.begin(), kept.neighbor.begin() + dim_, ridge.seen) = id;
    }
    for (int f : visible) facets_[static_cast<std::size_t>(f)].alive = false;
    added_[static_cast<std::size_t>(point)] = true;
    linkCone(ridges);
    return true;
  }

  // The ridges of new facet `facet` (to be `id`) that contain the apex (at `apex`): one per
  // other vertex.
  static void addConeRidges(const Facet& facet, int id, int apex, std::vector<ConeRidge>& ridges) {
    for (int m = 0; m < dim_; ++m) {
      if (m == apex) continue;
      ConeRidge ridge;
      ridge.key.fill(-1);
      int slot = 0;
      for (int k = 0; k < dim_; ++k)
        if (k != m && k != apex) ridge.key[static_cast<std::size_t>(slot++)] = facet.vertex[k];
      std::sort(ridge.key.begin(), ridge.key.end());  // the unused -1s first, alike in all
      ridge.facet = id;
      ridge.position = m;
      ridges.push_back(ridge);
    }
  }

  // Sorts the cone's ridges by key; true when each key occurs exactly twice (the facets pair up).
  static bool pairRidges(std::vector<ConeRidge>& ridges) {
    std::sort(ridges.begin(), ridges.end(),
              [](const ConeRidge& a, const ConeRidge& b) { return a.key < b.key; });
    for (std::size_t k = 0; k < ridges.size(); k += 2) {
      if (k + 1 >= ridges.size() || ridges[k].key != ridges[k + 1].key) return false;
      if (k + 2 < ridges.size() && ridges[k + 2].key == ridges[k].key) return false;
    }
    return true;
  }

  // Links the cone's facets across their shared ridges, sorted and paired by pairRidges().
  void linkCone(const std::vector<ConeRidge>& ridges) {
    for (std::size_t k = 0; k < ridges.size(); k += 2) {
      const ConeRidge& a = ridges[k];
      const ConeRidge& b = ridges[k + 1];
      facets_[static_cast<std::size_t>(a.facet)].neighbor[static_cast<std::size_t>(a.position)] =
          b.facet;
      facets_[static_cast<std::size_t>(b.facet)].neighbor[static_cast<std::size_t>(b.position)] =
          a.facet;
    }
  }

  std::vector<Vec> points_;
  double tolerance_;
  std::vector<bool> added_;
  Vec interior_;
  std::vector<Facet> facets_;
  std::priority_queue<std::pair<double, int>> queue_;
  int visits_ = -1;  // the last visible-set search's mark
};

}  // namespace

NearestFacet nearestHullFacet(const Points& points, double tolerance) {
  const auto dim = points.rows();
  if (dim < 2 || dim > kMaxDim) return {};
  if (tolerance < 0.0) {
    const double scale = points.cols() > 0 ? points.colwise().norm().maxCoeff() : 0.0;
    tolerance = 1e-12 * scale;
  }
  if (points.cols() == 0 || !(tolerance > 0.0)) {
    NearestFacet flat;
    flat.origin = OriginPlacement::Flat;
    return flat;
  }
  switch (dim) {
    case 2:
      return ExpandingPolytope<2>(points, tolerance).run();
    case 3:
      return ExpandingPolytope<3>(points, tolerance).run();
    case 4:
      return ExpandingPolytope<4>(points, tolerance).run();
    case 5:
      return ExpandingPolytope<5>(points, tolerance).run();
    default:
      return ExpandingPolytope<6>(points, tolerance).run();
  }
}

}  // namespace graspkit
