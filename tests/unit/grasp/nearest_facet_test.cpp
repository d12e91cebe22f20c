// HullMethod::NearestFacet (grasp/nearest_facet.hpp) against qhull's exact hull (ExactHull,
// "Qt") on over 10,000 grasps: random contact sets on spheres and boxes in six and fewer wrench
// dimensions, the force-only three dimensions of the planner's potential-quality energy,
// near-degenerate sets (origin near the boundary, coplanar contacts, flat wrench sets),
// L-infinity Minkowski sums, and GraspIt!'s planned plannerMug grasps with perturbed variants.
// Epsilon must agree to 1e-9 relative wherever it is force closure, and the force-closure
// decision everywhere. Most sets are 3-D, where qhull is quick: its 6-D hulls take the time.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iostream>
#include <random>
#include <sstream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "graspkit/grasp/friction_cone.hpp"
#include "graspkit/grasp/nearest_facet.hpp"
#include "graspkit/grasp/quality.hpp"
#include "graspkit/grasp/wrench_space.hpp"
#include "graspkit/math/transform.hpp"
#include "test_paths.hpp"

namespace graspkit {
namespace {

using Sets = std::vector<std::vector<Vector6>>;
using Mask = std::array<bool, 6>;

constexpr Mask kAll = {true, true, true, true, true, true};
constexpr Mask kForces = {true, true, true, false, false, false};
constexpr double kRelativeTolerance = 1e-9;

// One comparison's tally: how many sets, how many force closure, the worst relative error.
struct Tally {
  int grasps = 0;
  int forceClosure = 0;
  int disagreements = 0;
  double worstRelative = 0.0;
  double worstAbsoluteBelowClosure = 0.0;  // where both are >= 0 but not force closure

  void print(const std::string& what) const {
    std::cout << fmt::format(
        "[ nearest  ] {:<28} {:>5} grasps, {:>5} force closure, worst relative error {:.2e}, "
        "worst absolute below closure {:.2e}, {} force-closure disagreements\n",
        what, grasps, forceClosure, worstRelative, worstAbsoluteBelowClosure, disagreements);
  }
};

double epsilonBy(const Sets& sets, const Mask& mask, HullMethod method,
                 WrenchSpaceType type = WrenchSpaceType::L1) {
  WrenchSpaceOptions options;
  options.type = type;
  options.dimensions = mask;
  options.method = method;
  return epsilonQuality(graspWrenchSpace(sets, options));
}

// The search alone, without the Gilbert shortcut graspWrenchSpace() takes first, so that the
// search itself meets every origin outside too.
double searchEpsilon(const Sets& sets, const Mask& mask, WrenchSpaceType type) {
  const std::vector<Vector6> points = wrenchSpacePoints(sets, type);
  const int dim = static_cast<int>(std::count(mask.begin(), mask.end(), true));
  Eigen::MatrixXd packed(dim, static_cast<Eigen::Index>(points.size()));
  for (std::size_t i = 0; i < points.size(); ++i) {
    int k = 0;
    for (int d = 0; d < 6; ++d)
      if (mask[d]) packed(k++, static_cast<Eigen::Index>(i)) = points[i][d];
  }
  const NearestFacet nearest = nearestHullFacet(packed);
  EXPECT_NE(nearest.origin, OriginPlacement::Unresolved);
  if (nearest.origin != OriginPlacement::Inside) return -1.0;
  return -nearest.offset;
}

// `counted`: the first of a set's comparisons counts the set.
void compare(double ours, double exact, Tally& tally, const std::string& what, bool counted) {
  const bool closure = isForceClosure(exact);
  if (counted) {
    ++tally.grasps;
    tally.forceClosure += closure ? 1 : 0;
  }
  if (closure != isForceClosure(ours)) {
    ++tally.disagreements;
    ADD_FAILURE() << what << ": force closure differs, nearest facet " << ours << ", qhull Qt "
                  << exact;
    return;
  }
  if (closure) {
    const double relative = std::abs(ours - exact) / exact;
    tally.worstRelative = std::max(tally.worstRelative, relative);
    EXPECT_LE(relative, kRelativeTolerance)
        << what << ": nearest facet " << fmt::format("{:.17g}", ours) << ", qhull Qt "
        << fmt::format("{:.17g}", exact);
  } else if (ours >= 0.0 && exact >= 0.0) {
    tally.worstAbsoluteBelowClosure =
        std::max(tally.worstAbsoluteBelowClosure, std::abs(ours - exact));
  }
}

void check(const Sets& sets, const Mask& mask, Tally& tally, const std::string& what,
           WrenchSpaceType type = WrenchSpaceType::L1) {
  const double exact = epsilonBy(sets, mask, HullMethod::ExactHull, type);
  compare(epsilonBy(sets, mask, HullMethod::NearestFacet, type), exact, tally, what, true);
  compare(searchEpsilon(sets, mask, type), exact, tally, what + " (search alone)", false);
}

// ---- random grasps ----

class GraspSampler {
 public:
  explicit GraspSampler(std::uint64_t seed) : rng_(seed) {}

  double uniform(double lo, double hi) { return std::uniform_real_distribution<>(lo, hi)(rng_); }
  int integer(int lo, int hi) { return std::uniform_int_distribution<>(lo, hi)(rng_); }

  Vector3 direction() {
    std::normal_distribution<> n;
    return Vector3(n(rng_), n(rng_), n(rng_)).normalized();
  }

  // A contact on the object seen from the object: the normal points into it.
  Contact contact(const Vector3& point, const Vector3& inward, double mu,
                  ContactModel model = ContactModel::PointWithFriction) {
    Contact c;
    c.position1 = point;
    c.normal = inward.normalized();
    c.frame = contactFrame(c.normal);
    c.mu = mu;
    c.model = model;
    if (model == ContactModel::SoftFinger) c.torsion = uniform(0.5, 5.0);
    return c;
  }

  // A point on a sphere of radius 50 mm, or on a 100 x 60 x 40 mm box, normal tilted a little.
  Contact onObject(bool box, double mu) {
    if (!box) {
      const Vector3 u = direction();
      return contact(50.0 * u, -(u + 0.1 * direction()), mu, model());
    }
    const Vector3 half(50.0, 30.0, 20.0);
    const int axis = integer(0, 2);
    const double side = integer(0, 1) ? 1.0 : -1.0;
    Vector3 p(uniform(-half.x(), half.x()), uniform(-half.y(), half.y()),
              uniform(-half.z(), half.z()));
    p[axis] = side * half[axis];
    Vector3 inward = Vector3::Zero();
    inward[axis] = -side;
    return contact(p, inward, mu, model());
  }

  Sets grasp(int contacts, bool box, const Vector3& cog = Vector3::Zero()) {
    std::vector<Contact> list;
    for (int i = 0; i < contacts; ++i) list.push_back(onObject(box, uniform(0.1, 1.0)));
    return graspWrenches(list, cog, box ? 62.0 : 50.0);
  }

  // What the potential-quality energy builds: each contact's cone edges scaled by its
  // distance weight in (0, 2], forces only.
  Sets energyGrasp(int contacts, bool box) {
    Sets sets = grasp(contacts, box);
    for (auto& set : sets) {
      const double scale = uniform(0.01, 2.0);
      for (Vector6& w : set) w = scale * w;
    }
    return sets;
  }

  std::mt19937_64& rng() { return rng_; }

 private:
  // Mostly point contacts, some soft fingers (20 edges, torsion) and frictionless ones.
  ContactModel model() {
    const int k = integer(0, 9);
    return k == 0   ? ContactModel::SoftFinger
           : k == 1 ? ContactModel::Frictionless
                    : ContactModel::PointWithFriction;
  }

  std::mt19937_64 rng_;
};

Mask randomMask(GraspSampler& s) {
  for (;;) {
    Mask mask;
    for (bool& used : mask) used = s.integer(0, 2) != 0;
    if (std::count(mask.begin(), mask.end(), true) >= 2) return mask;
  }
}

TEST(NearestFacet, RandomGraspsInSixDimensions) {
  GraspSampler s(40);
  Tally tally;
  for (int i = 0; i < 300; ++i)
    check(s.grasp(s.integer(2, 4), i % 2 == 1), kAll, tally, fmt::format("6-D grasp {}", i));
  tally.print("random, 6-D");
}

TEST(NearestFacet, RandomGraspsInSelectedDimensions) {
  GraspSampler s(41);
  Tally tally;
  for (int i = 0; i < 1000; ++i) {
    const Mask mask = randomMask(s);
    check(s.grasp(s.integer(2, 6), i % 2 == 1), mask, tally, fmt::format("masked grasp {}", i));
  }
  tally.print("random, 2- to 6-D masks");
}

// The planner's hot path: forces only, cone edges scaled per contact.
TEST(NearestFacet, PotentialQualityForceSpaces) {
  GraspSampler s(42);
  Tally tally;
  for (int i = 0; i < 7500; ++i)
    check(s.energyGrasp(s.integer(3, 6), i % 2 == 1), kForces, tally,
          fmt::format("force space {}", i));
  tally.print("potential-quality, 3-D");
}

// The wrench points shifted so that the origin lies near, on or just outside the nearest
// facet: epsilon from 1e-3 of its value down to 0 and below.
TEST(NearestFacet, OriginNearTheBoundary) {
  GraspSampler s(43);
  Tally tally;
  const double fractions[] = {1e-2, 1e-3, 1e-6, 1e-9, 0.0, -1e-9, -1e-6};
  int tried = 0;
  while (tally.grasps < 1100) {
    const bool sixD = tried++ % 4 == 0;
    const Mask mask = sixD ? kAll : kForces;
    const Sets sets = sixD ? s.grasp(s.integer(3, 4), true) : s.energyGrasp(4, false);
    WrenchSpaceOptions options;
    options.dimensions = mask;
    options.method = HullMethod::ExactHull;
    const GraspWrenchSpace gws = graspWrenchSpace(sets, options);
    const double epsilon = epsilonQuality(gws);
    if (!isForceClosure(epsilon)) continue;
    const auto nearest = std::min_element(
        gws.hyperplanes.begin(), gws.hyperplanes.end(),
        [](const WrenchHyperplane& a, const WrenchHyperplane& b) { return a.offset > b.offset; });
    for (double fraction : fractions) {
      // Moving every point by -(1 - fraction) epsilon n brings that facet to fraction epsilon.
      const Vector6 shift = -(1.0 - fraction) * epsilon * nearest->normal;
      Sets moved = sets;
      for (auto& set : moved)
        for (Vector6& w : set) w += shift;
      check(moved, mask, tally, fmt::format("boundary grasp {} at {}", tried, fraction));
    }
  }
  tally.print("origin near the boundary");
}

// Contacts in one plane through the centre (coplanar points of contact), contacts sharing one
// point, frictionless contacts whose forces span a plane only (a flat force space), and
// antipodal pairs.
TEST(NearestFacet, DegenerateContactSets) {
  GraspSampler s(44);
  Tally tally;
  for (int i = 0; i < 200; ++i) {
    std::vector<Contact> equator, shared, flat;
    const int n = s.integer(3, 5);
    for (int k = 0; k < n; ++k) {
      const double a = s.uniform(0.0, 2.0 * M_PI);
      const Vector3 u(std::cos(a), std::sin(a), 0.0);
      equator.push_back(s.contact(40.0 * u, -u, s.uniform(0.1, 1.0)));
      flat.push_back(s.contact(40.0 * u, -u + Vector3(0, 0, 0), 0.0));
      shared.push_back(s.contact(Vector3(40.0, 0.0, 0.0), -Vector3::UnitX() + 0.3 * s.direction(),
                                 s.uniform(0.1, 1.0)));
    }
    const Vector3 cog = Vector3::Zero();
    check(graspWrenches(equator, cog, 40.0), kAll, tally, fmt::format("equator {}", i));
    check(graspWrenches(equator, cog, 40.0), kForces, tally, fmt::format("equator f {}", i));
    check(graspWrenches(shared, cog, 40.0), kAll, tally, fmt::format("shared point {}", i));
    check(graspWrenches(flat, cog, 40.0), kForces, tally, fmt::format("flat {}", i));
    const Vector3 u = s.direction();
    const std::vector<Contact> antipodal = {s.contact(40.0 * u, -u, s.uniform(0.1, 1.0)),
                                            s.contact(-40.0 * u, u, s.uniform(0.1, 1.0))};
    check(graspWrenches(antipodal, cog, 40.0), kAll, tally, fmt::format("antipodal {}", i));
  }
  tally.print("degenerate contact sets");
}

// Wrench sets of UMI gripper grasps whose pad contacts lie in common planes: a point added to
// the polytope lay within rounding of several facets' hyperplanes, its horizon did not close,
// and the search gave up to qhull (pad_wrench_sets.txt). The first three must now be resolved by
// the search itself; every one must give qhull's exact epsilon through graspWrenchSpace(),
// where the last still falls back to qhull.
TEST(NearestFacet, CoplanarPadContactsOfAParallelGripper) {
  std::ifstream in(test::sourceDir() / "tests/unit/grasp/pad_wrench_sets.txt");
  ASSERT_TRUE(in) << "tests/unit/grasp/pad_wrench_sets.txt is missing";
  std::vector<Sets> sets;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream header(line);
    int dim = 0, count = 0;
    header >> dim >> count;
    ASSERT_EQ(dim, 6);
    Sets points;
    for (int i = 0; i < count; ++i) {
      Vector6 w;
      for (int d = 0; d < 6; ++d) in >> w[d];
      points.push_back({w});  // L1: the hull of every wrench, each its own contact
    }
    ASSERT_TRUE(in) << "set " << sets.size() << " is short";
    sets.push_back(std::move(points));
  }
  ASSERT_EQ(sets.size(), 4u);
  Tally tally;
  for (std::size_t i = 0; i < sets.size(); ++i) {
    const double exact = epsilonBy(sets[i], kAll, HullMethod::ExactHull);
    ASSERT_TRUE(isForceClosure(exact)) << "set " << i;
    compare(epsilonBy(sets[i], kAll, HullMethod::NearestFacet), exact, tally,
            fmt::format("pad set {}", i), true);
    if (i < 3)
      compare(searchEpsilon(sets[i], kAll, WrenchSpaceType::L1), exact, tally,
              fmt::format("pad set {} (search alone)", i), false);
  }
  tally.print("coplanar pad contacts");
}

// L-infinity wrench spaces: Minkowski sums, full of coplanar points (9^k for k point contacts).
TEST(NearestFacet, LInfinityMinkowskiSums) {
  GraspSampler s(46);
  Tally tally;
  for (int i = 0; i < 100; ++i)
    check(s.energyGrasp(s.integer(3, 4), i % 2 == 1), kForces, tally,
          fmt::format("L-infinity forces {}", i), WrenchSpaceType::LInfinity);
  for (int i = 0; i < 20; ++i)
    check(s.grasp(2, i % 2 == 1), kAll, tally, fmt::format("L-infinity 6-D {}", i),
          WrenchSpaceType::LInfinity);
  tally.print("L-infinity");
}

// GraspIt!'s plannerMug grasps (contacts as GraspIt! recorded them), then variants: a subset
// of their contacts, each moved up to 2 mm, normal tilted up to about 6 degrees, mu scaled.
TEST(NearestFacet, PlannedGraspsAndVariants) {
  GRASPKIT_REQUIRE_SHARED();
  std::ifstream in(*test::referenceFigures());
  const nlohmann::json figures = nlohmann::json::parse(in);
  GraspSampler s(45);
  Tally tally;
  auto vec = [](const nlohmann::json& v) {
    return Vector3(v.at(0).get<double>(), v.at(1).get<double>(), v.at(2).get<double>());
  };
  for (const char* key : {"plannerMug_as_loaded", "plannerMug_force_closure_1"}) {
    const nlohmann::json& j = figures.at("grasps").at(key);
    std::vector<Contact> contacts;
    for (const nlohmann::json& c : j.at("autograsp").at("contacts"))
      contacts.push_back(s.contact(vec(c.at("mate_pos_world_mm")), vec(c.at("mate_normal_world")),
                                   c.at("cof_static")));
    const Vector3 cog = vec(j.at("object_pose").at("t_mm"));
    const double radius = j.at("object_max_radius_mm").get<double>();
    check(graspWrenches(contacts, cog, radius), kAll, tally, key);
    for (int i = 0; i < 80; ++i) {
      std::vector<Contact> variant;
      for (const Contact& c : contacts) {
        if (s.integer(0, 4) == 0) continue;
        variant.push_back(s.contact(c.position1 + s.uniform(0.0, 2.0) * s.direction(),
                                    c.normal + 0.1 * s.direction(), c.mu * s.uniform(0.5, 1.5)));
      }
      if (variant.size() < 2) continue;
      const Sets sets = graspWrenches(variant, cog, radius);
      check(sets, kAll, tally, fmt::format("{} variant {}", key, i));
      check(sets, kForces, tally, fmt::format("{} variant {} forces", key, i));
    }
  }
  tally.print("planned plannerMug grasps");
}

// What HullMethod::NearestFacet leaves in the wrench space: one facet, volume unknown.
TEST(NearestFacet, WrenchSpaceHoldsTheNearestFacetOnly) {
  Sets cross;
  for (int i = 0; i < 6; ++i) {
    Vector6 e = Vector6::Zero();
    e[i] = 1.0;
    cross.push_back({e, -e});
  }
  WrenchSpaceOptions options;
  options.method = HullMethod::NearestFacet;
  const GraspWrenchSpace gws = graspWrenchSpace(cross, options);
  ASSERT_TRUE(gws.built) << gws.failure;
  ASSERT_EQ(gws.hyperplanes.size(), 1u);
  EXPECT_NEAR(epsilonQuality(gws), 1.0 / std::sqrt(6.0), 1e-14);
  EXPECT_TRUE(std::isnan(volumeQuality(gws)));
  EXPECT_EQ(epsilonMethodName(HullMethod::NearestFacet), "nearest facet (exact)");
  EXPECT_EQ(epsilonMethodName(HullMethod::GraspIt), "qhull Qx QJ C-0.0001 (GraspIt!)");

  // The origin outside (every point moved 2 along the first axis): no facet, as
  // SkipNonForceClosure reports it.
  for (auto& set : cross)
    for (Vector6& w : set) w[0] += 2.0;
  const GraspWrenchSpace outside = graspWrenchSpace(cross, options);
  EXPECT_TRUE(outside.originOutside);
  EXPECT_EQ(epsilonQuality(outside), -1.0);
}

}  // namespace
}  // namespace graspkit
