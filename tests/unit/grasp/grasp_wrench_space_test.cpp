// The grasp wrench space and the quality measures against closed-form truths: polytopes whose
// volume and inradius are known, grasps whose force closure follows from mechanics (what two
// antipodal point contacts cannot resist, what frictionless contacts on a sphere cannot), and
// the quality-measure registry.

#include <gtest/gtest.h>

#include <cmath>
#include <thread>

#include "graspkit/base/error.hpp"
#include "graspkit/grasp/friction_cone.hpp"
#include "graspkit/grasp/quality.hpp"
#include "graspkit/grasp/wrench_space.hpp"
#include "graspkit/plugin/registry.hpp"

namespace graspkit {
namespace {

Vector6 unit(int i, double sign = 1.0) {
  Vector6 e = Vector6::Zero();
  e[i] = sign;
  return e;
}

// The 12 points +-e_i: the 6-D cross-polytope, volume 2^6 / 6!, inradius 1 / sqrt(6).
std::vector<std::vector<Vector6>> crossPolytope() {
  std::vector<std::vector<Vector6>> sets;
  for (int i = 0; i < 6; ++i) sets.push_back({unit(i), unit(i, -1.0)});
  return sets;
}

TEST(WrenchSpace, CrossPolytopeVolumeAndEpsilon) {
  const GraspWrenchSpace gws = graspWrenchSpace(crossPolytope());
  ASSERT_TRUE(gws.built) << gws.failure;
  EXPECT_EQ(gws.pointCount, 12u);
  EXPECT_EQ(gws.hyperplanes.size(), 64u);  // one facet per orthant
  EXPECT_NEAR(gws.volume, 64.0 / 720.0, 1e-9);
  EXPECT_NEAR(epsilonQuality(gws), 1.0 / std::sqrt(6.0), 1e-9);
  EXPECT_TRUE(isForceClosure(gws));
  for (const WrenchHyperplane& h : gws.hyperplanes) {
    EXPECT_NEAR(h.normal.norm(), 1.0, 1e-12);
    EXPECT_NEAR(h.normal.cwiseAbs().minCoeff(), 1.0 / std::sqrt(6.0), 1e-9);
  }
}

// The force-closure decision is a stated tolerance, not a sign: an epsilon under
// kForceClosureEpsilon (a grasp whose origin lies on its hull within qhull's rounding) is not
// force closure, whatever its sign came out as.
TEST(ForceClosure, DecidedByTheStatedTolerance) {
  EXPECT_EQ(kForceClosureEpsilon, 1e-6);
  EXPECT_FALSE(isForceClosure(6.9e-11));  // the dataset grasp of issue 39
  EXPECT_FALSE(isForceClosure(0.0));
  EXPECT_FALSE(isForceClosure(-1.0));
  EXPECT_FALSE(isForceClosure(9.99e-7));
  EXPECT_FALSE(isForceClosure(std::nan("")));
  EXPECT_TRUE(isForceClosure(1e-6));
  EXPECT_TRUE(isForceClosure(0.2));
}

// The cross-polytope moved along the normal of one facet until that facet passes `gap` from
// the origin: a wrench space that barely contains the origin. Its epsilon is `gap` (every other
// facet is farther: their normals make an angle with the moved one's).
std::vector<std::vector<Vector6>> crossPolytopeWithin(double gap) {
  const Vector6 normal = Vector6::Constant(1.0 / std::sqrt(6.0));
  const Vector6 shift = -(1.0 / std::sqrt(6.0) - gap) * normal;
  auto sets = crossPolytope();
  for (auto& set : sets)
    for (Vector6& w : set) w += shift;
  return sets;
}

TEST(ForceClosure, AHullThatBarelyHoldsTheOriginIsNotForceClosure) {
  const GraspWrenchSpace barely = graspWrenchSpace(crossPolytopeWithin(1e-10));
  ASSERT_TRUE(barely.built) << barely.failure;
  // Inside by rounding only: epsilon positive (or 0) and tiny, and not force closure.
  EXPECT_GE(epsilonQuality(barely), 0.0);
  EXPECT_LT(epsilonQuality(barely), 1e-8);
  EXPECT_FALSE(isForceClosure(barely));
  // The same hull with the origin 1e-4 inside is force closure, with that epsilon.
  const GraspWrenchSpace inside = graspWrenchSpace(crossPolytopeWithin(1e-4));
  ASSERT_TRUE(inside.built) << inside.failure;
  EXPECT_NEAR(epsilonQuality(inside), 1e-4, 1e-9);
  EXPECT_TRUE(isForceClosure(inside));
}

TEST(WrenchSpace, LInfinityOfAxisPairsIsTheCube) {
  // Minkowski sum over 6 contacts of {0, e_i, -e_i} = {-1, 0, 1}^6: the cube [-1, 1]^6.
  WrenchSpaceOptions options;
  options.type = WrenchSpaceType::LInfinity;
  const GraspWrenchSpace gws = graspWrenchSpace(crossPolytope(), options);
  ASSERT_TRUE(gws.built) << gws.failure;
  EXPECT_EQ(gws.pointCount, 729u);
  EXPECT_NEAR(gws.volume, 64.0, 1e-6);
  EXPECT_NEAR(epsilonQuality(gws), 1.0, 1e-9);
  EXPECT_TRUE(isForceClosure(gws));
}

TEST(WrenchSpace, CubeCornersAsL1) {
  std::vector<Vector6> corners;
  for (int mask = 0; mask < 64; ++mask) {
    Vector6 c;
    for (int i = 0; i < 6; ++i) c[i] = (mask >> i) & 1 ? 1.0 : -1.0;
    corners.push_back(c);
  }
  const GraspWrenchSpace gws = graspWrenchSpace({corners});
  ASSERT_TRUE(gws.built) << gws.failure;
  EXPECT_NEAR(gws.volume, 64.0, 1e-6);
  EXPECT_NEAR(epsilonQuality(gws), 1.0, 1e-9);
}

TEST(WrenchSpace, MinkowskiSumPoints) {
  const std::vector<Vector6> points =
      wrenchSpacePoints({{unit(0), unit(1)}, {unit(2)}}, WrenchSpaceType::LInfinity);
  // ({0} U {e0, e1}) + ({0} U {e2}) = 0, e0, e1, e2, e0+e2, e1+e2.
  ASSERT_EQ(points.size(), 6u);
  std::vector<Vector6> expected = {Vector6::Zero(), unit(0),           unit(1),
                                   unit(2),         unit(0) + unit(2), unit(1) + unit(2)};
  for (const Vector6& e : expected) {
    EXPECT_TRUE(std::any_of(points.begin(), points.end(), [&](const Vector6& p) {
      return (p - e).norm() == 0.0;
    })) << e.transpose();
  }
}

TEST(WrenchSpace, SelectedDimensions) {
  // fx, fy, tz of the cross-polytope: the octahedron, volume 4/3, inradius 1/sqrt(3).
  WrenchSpaceOptions options;
  options.dimensions = {true, true, false, false, false, true};
  const GraspWrenchSpace gws = graspWrenchSpace(
      {{unit(0), unit(0, -1), unit(1), unit(1, -1), unit(5), unit(5, -1)}}, options);
  ASSERT_TRUE(gws.built) << gws.failure;
  EXPECT_NEAR(gws.volume, 4.0 / 3.0, 1e-9);
  EXPECT_NEAR(epsilonQuality(gws), 1.0 / std::sqrt(3.0), 1e-9);
  for (const WrenchHyperplane& h : gws.hyperplanes) {
    EXPECT_EQ(h.normal[2], 0.0);
    EXPECT_EQ(h.normal[3], 0.0);
    EXPECT_EQ(h.normal[4], 0.0);
  }
}

TEST(WrenchSpace, OriginOutsideIsNotForceClosure) {
  // The cross-polytope shifted by 2 along fx: a full hull that misses the origin.
  std::vector<std::vector<Vector6>> sets = crossPolytope();
  for (auto& set : sets)
    for (Vector6& w : set) w[0] += 2.0;
  for (HullMethod method : {HullMethod::GraspIt, HullMethod::SkipNonForceClosure}) {
    WrenchSpaceOptions options;
    options.method = method;
    const GraspWrenchSpace gws = graspWrenchSpace(sets, options);
    EXPECT_FALSE(isForceClosure(gws));
    EXPECT_EQ(epsilonQuality(gws), -1.0);
    if (method == HullMethod::GraspIt) {
      ASSERT_TRUE(gws.built) << gws.failure;
      EXPECT_NEAR(gws.volume, 64.0 / 720.0, 1e-9);  // volume does not check force closure
      EXPECT_NEAR(volumeQuality(gws), 64.0 / 720.0, 1e-9);
    } else {
      EXPECT_TRUE(gws.originOutside);
      EXPECT_TRUE(std::isnan(volumeQuality(gws)));
    }
  }
}

TEST(WrenchSpace, SkipNonForceClosureBuildsTheHullWhenTheOriginIsInside) {
  WrenchSpaceOptions options;
  options.method = HullMethod::SkipNonForceClosure;
  const GraspWrenchSpace gws = graspWrenchSpace(crossPolytope(), options);
  ASSERT_TRUE(gws.built) << gws.failure;
  EXPECT_FALSE(gws.originOutside);
  EXPECT_NEAR(epsilonQuality(gws), 1.0 / std::sqrt(6.0), 1e-9);
}

// qhull must fail quietly: a result, nothing on stdout or stderr.
GraspWrenchSpace buildSilently(const std::vector<std::vector<Vector6>>& sets,
                               const WrenchSpaceOptions& options = {}) {
  testing::internal::CaptureStdout();
  testing::internal::CaptureStderr();
  GraspWrenchSpace gws = graspWrenchSpace(sets, options);
  const std::string out = testing::internal::GetCapturedStdout();
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_EQ(out, "");
  EXPECT_EQ(err, "");
  return gws;
}

void expectFailed(const GraspWrenchSpace& gws) {
  EXPECT_FALSE(gws.built);
  EXPECT_FALSE(gws.failure.empty());
  EXPECT_TRUE(gws.hyperplanes.empty());
  EXPECT_EQ(epsilonQuality(gws), -1.0);
  EXPECT_EQ(volumeQuality(gws), 0.0);
  EXPECT_FALSE(isForceClosure(gws));
}

TEST(WrenchSpace, FlatWrenchSetFailsQuietly) {
  // The cross-polytope of the first five coordinates: everything has tz = 0.
  std::vector<std::vector<Vector6>> sets = crossPolytope();
  sets.pop_back();
  sets.push_back({Vector6(Vector6::Constant(0.1).eval())});
  sets.back()[0][5] = 0.0;
  const GraspWrenchSpace gws = buildSilently(sets);
  expectFailed(gws);
  EXPECT_NE(gws.failure.find("qhull"), std::string::npos) << gws.failure;
}

TEST(WrenchSpace, TooFewPointsFailQuietly) {
  expectFailed(buildSilently({{unit(0), unit(1), unit(2)}}));
}

TEST(WrenchSpace, NoContactsOrTooFewDimensionsFail) {
  expectFailed(buildSilently({}));
  WrenchSpaceOptions options;
  options.dimensions = {true, false, false, false, false, false};
  expectFailed(buildSilently(crossPolytope(), options));
}

TEST(WrenchSpace, RefusesTooManyPoints) {
  // 8 contacts of 8 wrenches: 9^8 = 43 million L-infinity points.
  const std::vector<std::vector<Vector6>> sets(8, std::vector<Vector6>(8, unit(0)));
  WrenchSpaceOptions options;
  options.type = WrenchSpaceType::LInfinity;
  try {
    graspWrenchSpace(sets, options);
    FAIL() << "expected graspkit::Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("43046721"), std::string::npos) << e.what();
  }
  options.type = WrenchSpaceType::L1;
  options.maxPoints = 10;
  EXPECT_THROW(graspWrenchSpace(sets, options), Error);
}

TEST(WrenchSpace, ThreadsBuildIndependently) {
  // No global lock: each build owns its qhull state.
  std::vector<std::thread> threads;
  std::vector<int> good(4, 0);
  for (int t = 0; t < 4; ++t) {
    threads.emplace_back([t, &good] {
      for (int i = 0; i < 10; ++i) {
        const GraspWrenchSpace gws = graspWrenchSpace(crossPolytope());
        if (gws.built && std::abs(gws.volume - 64.0 / 720.0) < 1e-9) ++good[t];
      }
    });
  }
  for (std::thread& thread : threads) thread.join();
  for (int t = 0; t < 4; ++t) EXPECT_EQ(good[t], 10);
}

// --- Grasps -----------------------------------------------------------------------------------

// An object-side contact at `point` whose normal points into the object.
Contact objectContact(const Vector3& point, const Vector3& inward, double mu) {
  Contact c;
  c.position1 = point;
  c.normal = inward.normalized();
  c.frame = contactFrame(c.normal);
  c.mu = mu;
  c.model = mu > 0 ? ContactModel::PointWithFriction : ContactModel::Frictionless;
  return c;
}

GraspWrenchSpace graspSpace(const std::vector<Contact>& contacts, double max_radius,
                            WrenchSpaceType type = WrenchSpaceType::L1) {
  WrenchSpaceOptions options;
  options.type = type;
  return graspWrenchSpace(graspWrenches(contacts, Vector3::Zero(), max_radius), options);
}

// A 40 mm cube centred on its CoG, held on the faces x = +-20.
constexpr double kCubeRadius = 20.0 * 1.7320508075688772;

TEST(GraspQuality, TwoAntipodalPointContactsCannotResistTorqueAboutTheirAxis) {
  // Every force passes through the x axis, so no wrench has a torque about it: the wrench set
  // is flat in tx and the grasp is not force closure, whatever the friction.
  const std::vector<Contact> contacts = {objectContact({20, 0, 0}, {-1, 0, 0}, 0.5),
                                         objectContact({-20, 0, 0}, {1, 0, 0}, 0.5)};
  for (const auto& set : graspWrenches(contacts, Vector3::Zero(), kCubeRadius))
    for (const Vector6& w : set) EXPECT_NEAR(w[3], 0.0, 1e-15);
  const GraspWrenchSpace gws = buildSilently(graspWrenches(contacts, Vector3::Zero(), kCubeRadius));
  EXPECT_FALSE(isForceClosure(gws));
  EXPECT_EQ(epsilonQuality(gws), -1.0);
}

std::vector<Contact> fourFaceContacts(double mu) {
  return {objectContact({20, 0, 8}, {-1, 0, 0}, mu), objectContact({20, 0, -8}, {-1, 0, 0}, mu),
          objectContact({-20, 0, 8}, {1, 0, 0}, mu), objectContact({-20, 0, -8}, {1, 0, 0}, mu)};
}

TEST(GraspQuality, FourFrictionalContactsOnTwoOppositeFacesAreForceClosure) {
  // Friction along y at two heights gives torque about x, normal forces at two heights torque
  // about y, friction along y on opposite faces torque about z; friction bears fy and fz.
  const GraspWrenchSpace gws = graspSpace(fourFaceContacts(0.5), kCubeRadius);
  ASSERT_TRUE(gws.built) << gws.failure;
  EXPECT_TRUE(isForceClosure(gws));
  EXPECT_GT(epsilonQuality(gws), 0.0);
  EXPECT_GT(volumeQuality(gws), 0.0);
}

TEST(GraspQuality, FrictionlessOpposingContactsAreNeverForceClosure) {
  // Without friction no contact can push along y or z.
  const std::vector<Contact> two = {objectContact({20, 0, 0}, {-1, 0, 0}, 0.0),
                                    objectContact({-20, 0, 0}, {1, 0, 0}, 0.0)};
  for (const auto& contacts : {two, fourFaceContacts(0.0)}) {
    const GraspWrenchSpace gws =
        buildSilently(graspWrenches(contacts, Vector3::Zero(), kCubeRadius));
    EXPECT_FALSE(isForceClosure(gws));
    EXPECT_EQ(epsilonQuality(gws), -1.0);
  }
}

// Contacts on a sphere of radius 30 at the vertices of a regular tetrahedron.
std::vector<Contact> tetrahedralContacts(double mu) {
  const double s = 30.0 / std::sqrt(3.0);
  std::vector<Contact> contacts;
  for (const Vector3& v :
       {Vector3(s, s, s), Vector3(s, -s, -s), Vector3(-s, s, -s), Vector3(-s, -s, s)})
    contacts.push_back(objectContact(v, -v, mu));
  return contacts;
}

TEST(GraspQuality, FourTetrahedralFrictionalContactsOnASphereAreForceClosure) {
  // The normals positively span force space; friction in four tangent planes spans torque.
  const GraspWrenchSpace gws = graspSpace(tetrahedralContacts(0.5), 30.0);
  ASSERT_TRUE(gws.built) << gws.failure;
  EXPECT_TRUE(isForceClosure(gws));
  EXPECT_GT(epsilonQuality(gws), 0.0);
}

TEST(GraspQuality, FrictionlessContactsOnASphereCannotResistTorque) {
  // Every normal passes through the centre: no torque at all.
  const GraspWrenchSpace gws =
      buildSilently(graspWrenches(tetrahedralContacts(0.0), Vector3::Zero(), 30.0));
  EXPECT_FALSE(isForceClosure(gws));
  EXPECT_EQ(epsilonQuality(gws), -1.0);
}

TEST(GraspQuality, EpsilonGrowsWithFriction) {
  // A wider cone contains the narrower one's wrenches (same contacts, same normals), and the
  // larger hull is at least as far from the origin everywhere.
  const double narrow = epsilonQuality(graspSpace(tetrahedralContacts(0.3), 30.0));
  const double wide = epsilonQuality(graspSpace(tetrahedralContacts(0.8), 30.0));
  EXPECT_GT(narrow, 0.0);
  EXPECT_GE(wide, narrow);
}

// Three contacts 120 degrees apart on the equator of a sphere of radius 30.
std::vector<Contact> equatorialContacts(double mu) {
  std::vector<Contact> contacts;
  for (int k = 0; k < 3; ++k) {
    const double a = k * 2.0 * M_PI / 3.0;
    const Vector3 p = 30.0 * Vector3(std::cos(a), std::sin(a), 0.0);
    contacts.push_back(objectContact(p, -p, mu));
  }
  return contacts;
}

TEST(GraspQuality, LInfinityContainsL1) {
  // Each L1 wrench is a point of the Minkowski sum (the other contacts contributing 0), so the
  // L-infinity hull contains the L1 hull: larger epsilon and volume. (Three contacts: 9^3 = 729
  // points; four would take seconds.)
  const std::vector<Contact> contacts = equatorialContacts(0.5);
  const GraspWrenchSpace l1 = graspSpace(contacts, 30.0, WrenchSpaceType::L1);
  const GraspWrenchSpace linf = buildSilently(graspWrenches(contacts, Vector3::Zero(), 30.0),
                                              {.type = WrenchSpaceType::LInfinity});
  ASSERT_TRUE(l1.built) << l1.failure;
  ASSERT_TRUE(linf.built) << linf.failure;
  EXPECT_TRUE(isForceClosure(l1));
  EXPECT_GE(epsilonQuality(linf), epsilonQuality(l1));
  EXPECT_GT(linf.volume, l1.volume);
}

// The weight measure is the inradius of the hull's slice of zero torque. For the cross-polytope
// with its force axes stretched by `a`, that slice is the octahedron with vertices +-a e_i
// (i < 3), whose inradius is a / sqrt(3); the torque axes do not change it.
TEST(WeightQuality, IsTheInradiusOfTheZeroTorqueSlice) {
  for (const double a : {1.0, 0.25, 3.0}) {
    auto sets = crossPolytope();
    for (int i = 0; i < 3; ++i)
      for (Vector6& w : sets[static_cast<std::size_t>(i)]) w *= a;
    const GraspWrenchSpace gws = graspWrenchSpace(sets);
    ASSERT_TRUE(gws.built) << gws.failure;
    EXPECT_NEAR(weightQuality(gws), a / std::sqrt(3.0), 1e-9) << "a = " << a;
    EXPECT_GE(weightQuality(gws), epsilonQuality(gws));
  }
}

TEST(WeightQuality, IsMinusOneWithoutForceClosureAndNaNForOneFacet) {
  const GraspWrenchSpace outside = graspWrenchSpace(crossPolytopeWithin(-0.1));
  ASSERT_TRUE(outside.built) << outside.failure;
  EXPECT_EQ(weightQuality(outside), -1.0);
  EXPECT_EQ(weightQuality(GraspWrenchSpace{}), -1.0);  // not built
  // NearestFacet keeps only the facet nearest the origin, which does not bound the slice.
  const GraspWrenchSpace nearest =
      graspWrenchSpace(crossPolytope(), {.method = HullMethod::NearestFacet});
  EXPECT_TRUE(std::isnan(weightQuality(nearest)));
  // Torques alone: no facet bounds a force.
  const GraspWrenchSpace torques =
      graspWrenchSpace(crossPolytope(), {.dimensions = {false, false, false, true, true, true}});
  ASSERT_TRUE(torques.built) << torques.failure;
  EXPECT_TRUE(std::isnan(weightQuality(torques)));
}

// Two frictional contacts pressing a sphere from opposite sides along x: they resist any force
// (friction across, the other contact along x) but no torque about x, so they are not force
// closure and the weight measure says so.
TEST(WeightQuality, TwoAntipodalContactsAreNotCounted) {
  const std::vector<Contact> contacts = {objectContact(Vector3(30, 0, 0), Vector3(-1, 0, 0), 0.5),
                                         objectContact(Vector3(-30, 0, 0), Vector3(1, 0, 0), 0.5)};
  EXPECT_EQ(weightQuality(graspSpace(contacts, 30.0)), -1.0);
}

// --- Registry ---------------------------------------------------------------------------------

TEST(QualityRegistry, BuiltInsArePresent) {
  const std::vector<std::string> names = qualityMeasureNames();
  EXPECT_NE(std::find(names.begin(), names.end(), "epsilon"), names.end());
  EXPECT_NE(std::find(names.begin(), names.end(), "volume"), names.end());
  EXPECT_NE(std::find(names.begin(), names.end(), "weight"), names.end());
  EXPECT_TRUE(std::is_sorted(names.begin(), names.end()));

  const GraspWrenchSpace gws = graspWrenchSpace(crossPolytope());
  EXPECT_EQ(makeQualityMeasure("epsilon")->name(), "epsilon");
  EXPECT_NEAR(makeQualityMeasure("epsilon")->evaluate(gws), 1.0 / std::sqrt(6.0), 1e-9);
  EXPECT_NEAR(makeQualityMeasure("volume")->evaluate(gws), 64.0 / 720.0, 1e-9);
  EXPECT_NEAR(makeQualityMeasure("weight")->evaluate(gws), 1.0 / std::sqrt(3.0), 1e-9);
}

class FacetCount final : public QualityMeasure {
 public:
  std::string name() const override { return "test.facet_count"; }
  double evaluate(const GraspWrenchSpace& gws) const override {
    return static_cast<double>(gws.hyperplanes.size());
  }
};

TEST(QualityRegistry, ACustomMeasureIsFoundByName) {
  registerQualityMeasure("test.facet_count", [] { return std::make_unique<FacetCount>(); });
  const std::vector<std::string> names = qualityMeasureNames();
  EXPECT_NE(std::find(names.begin(), names.end(), "test.facet_count"), names.end());
  const auto measure = makeQualityMeasure("test.facet_count");
  EXPECT_EQ(measure->name(), "test.facet_count");
  EXPECT_EQ(measure->evaluate(graspWrenchSpace(crossPolytope())), 64.0);
  // A name is registered once.
  EXPECT_THROW(
      registerQualityMeasure("test.facet_count", [] { return std::make_unique<FacetCount>(); }),
      Error);
  EXPECT_THROW(registerQualityMeasure("", [] { return std::make_unique<FacetCount>(); }), Error);
  EXPECT_THROW(registerQualityMeasure("test.empty", nullptr), Error);
}

TEST(QualityRegistry, AnUnknownNameIsAnErrorNamingIt) {
  try {
    makeQualityMeasure("no-such-measure");
    FAIL() << "expected graspkit::Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("no-such-measure"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("epsilon"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace graspkit
