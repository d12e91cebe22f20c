// Contact search between two bodies against hand-derived truth: two 20 mm cubes, one resting
// 0.1 mm above the other, touch along their facing squares; the contacts lie on the faces,
// point +z into the upper cube, are 0.1 mm long, carry GraspIt!'s friction for the two
// materials, and compact to the corners of the touching patch.

#include "graspkit/collision/contact_search.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "collision/contact_search_stages.hpp"
#include "graspkit/base/error.hpp"
#include "graspkit/collision/collision.hpp"
#include "graspkit/collision/contact.hpp"
#include "graspkit/io/graspit/world_file.hpp"
#include "graspkit/model/body.hpp"
#include "graspkit/model/material.hpp"
#include "graspkit/model/world.hpp"
#include "random_hand.hpp"
#include "test_paths.hpp"

namespace graspkit {
namespace {

constexpr double kSearchTolerance = 1e-9;

// A cube of side 20 mm centred on its origin, triangles counter-clockwise seen from outside.
std::shared_ptr<const TriangleMesh> unitCubeMesh() {
  auto mesh = std::make_shared<TriangleMesh>();
  for (int i = 0; i < 8; ++i) {
    const double x = (i == 1 || i == 2 || i == 5 || i == 6) ? 10 : -10;
    const double y = (i == 2 || i == 3 || i == 6 || i == 7) ? 10 : -10;
    const double z = i < 4 ? -10 : 10;
    mesh->vertices.emplace_back(x, y, z);
  }
  mesh->triangles = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
                     {1, 2, 6}, {1, 6, 5}, {2, 3, 7}, {2, 7, 6}, {3, 0, 4}, {3, 4, 7}};
  return mesh;
}

Body cube(const std::string& name, Material material, const Vector3& position,
          bool elastic = false) {
  auto model = std::make_shared<BodyModel>();
  model->name = name;
  model->mesh = unitCubeMesh();
  model->material = material;
  if (elastic) model->youngs = 1e9;
  Body body;
  body.model = model;
  body.kind = BodyKind::Graspable;
  body.name = name;
  Transform pose = Transform::Identity();
  pose.translation() = position;
  body.setPose(pose);
  return body;
}

// Lower cube at the origin (top face z = 10), upper cube above it with its bottom face at
// z = 10 + gap, shifted by (dx, dy).
struct TwoCubes {
  World world;
  BodyRef lower, upper;
};

TwoCubes twoCubes(double gap, double dx = 0, double dy = 0,
                  Material upper_material = Material::Rubber,
                  Material lower_material = Material::Wood, bool upper_elastic = false,
                  bool upper_first = false) {
  TwoCubes out;
  Body lower = cube("lower", lower_material, Vector3::Zero());
  Body upper = cube("upper", upper_material, Vector3(dx, dy, 20 + gap), upper_elastic);
  if (upper_first) {
    out.upper = BodyRef::body(out.world.addBody(upper));
    out.lower = BodyRef::body(out.world.addBody(lower));
  } else {
    out.lower = BodyRef::body(out.world.addBody(lower));
    out.upper = BodyRef::body(out.world.addBody(upper));
  }
  return out;
}

// Two cubes at a random gap and shift, the upper one tilted about x and y by random angles.
TwoCubes tiltedCubes(std::mt19937& random, std::uniform_real_distribution<double>& gap,
                     std::uniform_real_distribution<double>& shift,
                     std::uniform_real_distribution<double>& tilt) {
  TwoCubes s = twoCubes(gap(random), shift(random), shift(random));
  Transform pose = s.world.bodies()[1].pose;
  pose.rotate(Eigen::AngleAxisd(tilt(random), Vector3::UnitX()));
  pose.rotate(Eigen::AngleAxisd(tilt(random), Vector3::UnitY()));
  s.world.bodies()[1].setPose(pose);
  return s;
}

// Each expected point matched by exactly one contact's position1.
void expectPositions(const std::vector<Contact>& contacts, std::vector<Vector3> expected) {
  ASSERT_EQ(contacts.size(), expected.size());
  for (const Contact& c : contacts) {
    auto hit = std::find_if(expected.begin(), expected.end(), [&](const Vector3& e) {
      return (c.position1 - e).norm() < kSearchTolerance;
    });
    ASSERT_NE(hit, expected.end()) << "unexpected contact at " << c.position1.transpose();
    expected.erase(hit);
  }
}

// A sheet of n x n squares over 20 x 20 mm, each split in two, its heights drawn up to `bumps`
// mm; facing up (+z), or down.
Body denseSheet(const std::string& name, int n, double bumps, bool facing_up,
                std::mt19937& random) {
  auto mesh = std::make_shared<TriangleMesh>();
  std::uniform_real_distribution<double> height(0.0, bumps);
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j)
      mesh->vertices.emplace_back(-10.0 + 20.0 * i / n, -10.0 + 20.0 * j / n, height(random));
  const auto at = [n](int i, int j) { return static_cast<std::uint32_t>(i * (n + 1) + j); };
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      std::array<std::uint32_t, 3> a = {at(i, j), at(i + 1, j), at(i + 1, j + 1)};
      std::array<std::uint32_t, 3> b = {at(i, j), at(i + 1, j + 1), at(i, j + 1)};
      if (!facing_up) {
        std::swap(a[1], a[2]);
        std::swap(b[1], b[2]);
      }
      mesh->triangles.push_back(a);
      mesh->triangles.push_back(b);
    }
  }
  auto model = std::make_shared<BodyModel>();
  model->name = name;
  model->mesh = mesh;
  model->material = Material::Rubber;
  Body body;
  body.model = model;
  body.kind = BodyKind::Graspable;
  body.name = name;
  return body;
}

// Two dense sheets face to face (a gripper's pads closed on each other): the search in two
// stages gives the contacts of one search over the whole threshold, bit for bit and in the same
// order, whether the sheets are bumpy or flat (ties between equally near pairs), touching,
// apart or crossing, and whichever is walked.
TEST(FindContacts, TwoStagesGiveTheContactsOfOneSearch) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int compared = 0, with_contacts = 0, crossing = 0;
  for (int trial = 0; trial < 16; ++trial) {
    SCOPED_TRACE(trial);
    const double bumps = trial % 4 == 0 ? 0.0 : 0.06;
    World world;
    Body lower = denseSheet("lower", trial % 2 ? 30 : 20, bumps, true, random);
    Body upper = denseSheet("upper", trial % 3 ? 24 : 34, bumps, false, random);
    Transform pose = Transform::Identity();
    pose.translation() =
        Vector3(3.0 * unit(random), 3.0 * unit(random), bumps + 0.1 + 0.15 * unit(random));
    if (trial % 4 != 0) {
      pose.rotate(Eigen::AngleAxisd(0.03 * unit(random), Vector3::UnitX()));
      pose.rotate(Eigen::AngleAxisd(0.03 * unit(random), Vector3::UnitY()));
      pose.rotate(Eigen::AngleAxisd(0.5 * unit(random), Vector3::UnitZ()));
    }
    upper.setPose(pose);
    const BodyRef a = BodyRef::body(world.addBody(lower));
    const BodyRef b = BodyRef::body(world.addBody(upper));
    // One threshold a trial, drawn so that each threshold meets flat and bumpy sheets, either
    // size and either compaction (the whole product cost 5 minutes under the sanitizers).
    const double threshold = std::array{0.45, 1.3, 2.0}[(trial + trial / 4) % 3];
    for (const bool touching : {false, true}) {
      ContactRequest two_stages;
      two_stages.threshold = threshold;
      two_stages.graspitDuplicates = false;
      two_stages.softContacts = false;
      two_stages.compact = trial % 2 == 0;
      two_stages.touchingIsContact = touching;
      const ContactResult one =
          collision::findContactsInStages(world, a, b, two_stages, /*two_stages=*/false);
      const ContactResult two =
          collision::findContactsInStages(world, a, b, two_stages, /*two_stages=*/true);
      EXPECT_EQ(one.interpenetrating, two.interpenetrating);
      ASSERT_EQ(one.contacts.size(), two.contacts.size()) << threshold;
      for (std::size_t i = 0; i < one.contacts.size(); ++i) {
        EXPECT_EQ(one.contacts[i].position1, two.contacts[i].position1) << i;
        EXPECT_EQ(one.contacts[i].position2, two.contacts[i].position2) << i;
        EXPECT_EQ(one.contacts[i].normal, two.contacts[i].normal) << i;
      }
      ++compared;
      if (!one.contacts.empty()) ++with_contacts;
      if (one.interpenetrating) ++crossing;
    }
  }
  EXPECT_EQ(compared, 16 * 2);
  EXPECT_GT(with_contacts, compared / 2);  // the trials touch, mostly
  EXPECT_GT(crossing, 0);                  // and some cross
}

// Sets where the search finds each query triangle's candidate target triangles, for as long as
// it lives.
class CandidatesFrom {
 public:
  explicit CandidatesFrom(bool target) { collision::setCandidatesFromTarget(target); }
  ~CandidatesFrom() { collision::setCandidatesFromTarget(std::nullopt); }
};

// The contacts of `a` and `b` with each query triangle's candidates found from the target's
// triangles and from the query triangle's own ball: the same, bit for bit and in order.
// Returns whether there were any.
bool sameContactsFromEitherSide(const World& world, const BodyRef& a, const BodyRef& b,
                                const ContactRequest& request) {
  ContactResult from_target, from_query;
  {
    CandidatesFrom chosen(true);
    from_target = findContacts(world, a, b, request);
  }
  {
    CandidatesFrom chosen(false);
    from_query = findContacts(world, a, b, request);
  }
  EXPECT_EQ(from_target.interpenetrating, from_query.interpenetrating);
  EXPECT_EQ(from_target.contacts.size(), from_query.contacts.size());
  for (std::size_t i = 0; i < std::min(from_target.contacts.size(), from_query.contacts.size());
       ++i) {
    EXPECT_EQ(from_target.contacts[i].position1, from_query.contacts[i].position1) << i;
    EXPECT_EQ(from_target.contacts[i].position2, from_query.contacts[i].position2) << i;
    EXPECT_EQ(from_target.contacts[i].normal, from_query.contacts[i].normal) << i;
  }
  return !from_query.contacts.empty();
}

// GraspIt!'s Barrett around its mug: the links' triangles are 2.4-3.5 times the mug's, so the
// search finds their candidates from the mug's triangles; from the links' own balls, it finds
// the same contacts, with GraspIt!'s duplicates, with touching counted and with a wider
// threshold.
TEST(FindContacts, CandidatesFromEitherSideAroundGraspItsMug) {
  GRASPKIT_REQUIRE_SHARED();
  World world = loadWorldFile(*test::graspitDataDir() / "worlds" / "plannerMug.xml");
  const Transform mug_pose = bodyPose(world, BodyRef::body(0));
  ContactRequest graspit, touching, wide;
  touching.touchingIsContact = true;
  wide.threshold = 2.0;
  wide.graspitDuplicates = false;
  std::mt19937 random(17);
  int with_contacts = 0;
  for (int trial = 0; trial < 50; ++trial) {
    SCOPED_TRACE(trial);
    test::placeHandRandomlyNear(world, mug_pose.translation(), random);
    for (const BodyRef& link : worldBodies(world)) {
      if (!link.isLink()) continue;
      for (const ContactRequest* request : {&graspit, &touching, &wide})
        with_contacts += sameContactsFromEitherSide(world, link, BodyRef::body(0), *request);
    }
  }
  EXPECT_GT(with_contacts, 200);  // of 1,350 searches
}

// A coarse bumpy sheet on a dense one, each searched from either side.
TEST(FindContacts, CandidatesFromEitherSideCoarseOnDense) {
  std::mt19937 random(5);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int with_contacts = 0;
  for (int trial = 0; trial < 12; ++trial) {
    SCOPED_TRACE(trial);
    World world;
    Body lower = denseSheet("lower", 24, 0.06, true, random);
    Body upper = denseSheet("upper", 3 + trial % 3, 0.3, false, random);
    Transform pose = Transform::Identity();
    pose.translation() = Vector3(3.0 * unit(random), 3.0 * unit(random), 0.4 + 0.3 * unit(random));
    pose.rotate(Eigen::AngleAxisd(0.05 * unit(random), Vector3::UnitX()));
    pose.rotate(Eigen::AngleAxisd(0.5 * unit(random), Vector3::UnitZ()));
    upper.setPose(pose);
    const BodyRef a = BodyRef::body(world.addBody(lower));
    const BodyRef b = BodyRef::body(world.addBody(upper));
    ContactRequest request;
    request.threshold = 1.0;
    request.touchingIsContact = trial % 2 == 0;
    with_contacts += sameContactsFromEitherSide(world, a, b, request);
    with_contacts += sameContactsFromEitherSide(world, b, a, request);
  }
  EXPECT_GT(with_contacts, 16);  // of 24
}

TEST(FindContacts, FacingSquaresAPointOneApart) {
  TwoCubes s = twoCubes(0.1);
  const ContactResult result = findContacts(s.world, s.upper, s.lower);
  EXPECT_FALSE(result.interpenetrating);
  // Equal aligned squares: compaction leaves the perimeter, the four corners, seen from the
  // upper cube (its bottom face at z = 10.1).
  expectPositions(result.contacts, {Vector3(-10, -10, 10.1), Vector3(10, -10, 10.1),
                                    Vector3(10, 10, 10.1), Vector3(-10, 10, 10.1)});
  for (const Contact& c : result.contacts) {
    EXPECT_EQ(c.body1, s.upper);
    EXPECT_EQ(c.body2, s.lower);
    EXPECT_LT((c.position2 - (c.position1 - Vector3(0, 0, 0.1))).norm(), kSearchTolerance);
    EXPECT_LT((c.normal - Vector3::UnitZ()).norm(), kSearchTolerance) << c.normal.transpose();
    EXPECT_NEAR(c.distance, 0.1, kSearchTolerance);
    // GraspIt!'s static friction table: wood on rubber is 1.0.
    EXPECT_DOUBLE_EQ(c.mu, 1.0);
    EXPECT_EQ(c.model, ContactModel::PointWithFriction);
    // The documented frame for n = +z: x = n x X = +y, y = n x x = -x.
    EXPECT_LT((c.frame.col(2) - Vector3::UnitZ()).norm(), kSearchTolerance);
    EXPECT_LT((c.frame.col(0) - Vector3::UnitY()).norm(), kSearchTolerance);
    EXPECT_LT((c.frame.col(1) + Vector3::UnitX()).norm(), kSearchTolerance);
  }
}

TEST(FindContacts, WithoutCompactionEveryContactLiesOnTheFaces) {
  TwoCubes s = twoCubes(0.1);
  ContactRequest request;
  request.compact = false;
  request.duplicateDistance = 1e-3;
  const ContactResult result = findContacts(s.world, s.upper, s.lower, request);
  ASSERT_GE(result.contacts.size(), 4u);
  for (const Contact& c : result.contacts) {
    EXPECT_NEAR(c.position1.z(), 10.1, kSearchTolerance);
    EXPECT_NEAR(c.position2.z(), 10.0, kSearchTolerance);
    EXPECT_LE(c.position1.head<2>().cwiseAbs().maxCoeff(), 10 + kSearchTolerance);
    EXPECT_NEAR(c.distance, 0.1, kSearchTolerance);
  }
}

TEST(FindContacts, ShiftedSquaresCompactToTheirOverlap) {
  // Upper square [-5, 15]^2 over the lower [-10, 10]^2: the overlap [-5, 10]^2 has one corner
  // from each square and two where their edges cross.
  TwoCubes s = twoCubes(0.1, 5, 5);
  const ContactResult result = findContacts(s.world, s.upper, s.lower);
  EXPECT_FALSE(result.interpenetrating);
  expectPositions(result.contacts, {Vector3(-5, -5, 10.1), Vector3(10, -5, 10.1),
                                    Vector3(10, 10, 10.1), Vector3(-5, 10, 10.1)});
  for (const Contact& c : result.contacts) {
    EXPECT_LT((c.normal - Vector3::UnitZ()).norm(), kSearchTolerance);
    EXPECT_NEAR(c.distance, 0.1, kSearchTolerance);
  }
}

TEST(FindContacts, BeyondTheThresholdNone) {
  TwoCubes s = twoCubes(0.3);
  const ContactResult result = findContacts(s.world, s.upper, s.lower);
  EXPECT_TRUE(result.contacts.empty());
  EXPECT_FALSE(result.interpenetrating);
  // A wider threshold finds them again, 0.3 long.
  ContactRequest wide;
  wide.threshold = 0.5;
  const ContactResult found = findContacts(s.world, s.upper, s.lower, wide);
  ASSERT_EQ(found.contacts.size(), 4u);
  for (const Contact& c : found.contacts) EXPECT_NEAR(c.distance, 0.3, kSearchTolerance);
}

// inContact is findContacts' "found any": hand cases, then random tilted poses about the
// threshold, some crossing, either body first.
TEST(InContact, AnswersWhetherFindContactsFindsAny) {
  EXPECT_TRUE(inContact(twoCubes(0.05).world, BodyRef::body(1), BodyRef::body(0)));
  EXPECT_FALSE(inContact(twoCubes(0.3).world, BodyRef::body(1), BodyRef::body(0)));
  ContactRequest wide;
  wide.threshold = 0.5;
  EXPECT_TRUE(inContact(twoCubes(0.3).world, BodyRef::body(1), BodyRef::body(0), wide));
  std::mt19937 random(11);
  std::uniform_real_distribution<double> gap(-0.2, 0.3), shift(-25, 25), tilt(-0.02, 0.02);
  int with = 0, without = 0;
  for (int trial = 0; trial < 600; ++trial) {
    TwoCubes s = tiltedCubes(random, gap, shift, tilt);
    for (const auto& [a, b] : {std::pair{s.upper, s.lower}, std::pair{s.lower, s.upper}}) {
      const bool found = !findContacts(s.world, a, b).contacts.empty();
      ASSERT_EQ(inContact(s.world, a, b), found) << "trial " << trial;
      (found ? with : without) += 1;
    }
  }
  EXPECT_GT(with, 100);
  EXPECT_GT(without, 100);
}

// surfacesWithin asks withinDistance's question through the contact search: the cubes' gap
// against the distance by hand (crossing and touching count as within), then, as a second
// method, FCL's own answer on tilted cubes and on GraspIt!'s Barrett around its mug, each
// asked just below and just above FCL's distance for the pair.
TEST(SurfacesWithin, TheGapByHand) {
  EXPECT_TRUE(surfacesWithin(twoCubes(0.05).world, BodyRef::body(1), BodyRef::body(0), 0.1));
  EXPECT_FALSE(surfacesWithin(twoCubes(0.15).world, BodyRef::body(1), BodyRef::body(0), 0.1));
  EXPECT_TRUE(surfacesWithin(twoCubes(0.15).world, BodyRef::body(1), BodyRef::body(0), 0.2));
  EXPECT_TRUE(surfacesWithin(twoCubes(0.0).world, BodyRef::body(1), BodyRef::body(0), 0.1));
  EXPECT_TRUE(surfacesWithin(twoCubes(-3.0).world, BodyRef::body(0), BodyRef::body(1), 0.1));
  // Side by side, 2 mm apart across x: the distance is the gap between the x faces.
  EXPECT_FALSE(
      surfacesWithin(twoCubes(-20.0, 22.0).world, BodyRef::body(0), BodyRef::body(1), 1.9));
  EXPECT_TRUE(surfacesWithin(twoCubes(-20.0, 22.0).world, BodyRef::body(0), BodyRef::body(1), 2.1));
}

// Asks surfacesWithin just inside and just outside FCL's distance between a and b; returns
// whether the pair was near enough to count.
bool agreesWithFclAbout(const World& world, const BodyRef& a, const BodyRef& b,
                        const std::string& what) {
  const double d = distance(world, a, b).distance;
  if (d > 5.0) return false;
  EXPECT_EQ(surfacesWithin(world, a, b, 0.1), withinDistance(world, a, b, 0.1)) << what;
  if (d < 1e-3) {
    EXPECT_TRUE(surfacesWithin(world, a, b, 0.01)) << what << ": distance " << d;
  } else {
    EXPECT_FALSE(surfacesWithin(world, a, b, d * (1 - 1e-6))) << what << ": distance " << d;
    EXPECT_TRUE(surfacesWithin(world, a, b, d * (1 + 1e-6))) << what << ": distance " << d;
  }
  return true;
}

TEST(SurfacesWithin, AgreesWithFclOnTiltedCubes) {
  std::mt19937 random(3);
  std::uniform_real_distribution<double> gap(-0.5, 3.0), shift(-25, 25), tilt(-0.3, 0.3);
  int near = 0;
  for (int trial = 0; trial < 300; ++trial) {
    TwoCubes s = tiltedCubes(random, gap, shift, tilt);
    near += agreesWithFclAbout(s.world, s.upper, s.lower, "trial " + std::to_string(trial));
  }
  EXPECT_GT(near, 200);
}

TEST(SurfacesWithin, AgreesWithFclAroundGraspItsMug) {
  GRASPKIT_REQUIRE_SHARED();
  World world = loadWorldFile(*test::graspitDataDir() / "worlds" / "plannerMug.xml");
  const Transform mug_pose = bodyPose(world, BodyRef::body(0));
  std::mt19937 random(9);
  int near = 0;
  for (int trial = 0; trial < 150; ++trial) {  // random hand poses and postures by the mug
    test::placeHandRandomlyNear(world, mug_pose.translation(), random);
    for (const BodyRef& link : worldBodies(world))
      if (link.isLink())
        near += agreesWithFclAbout(world, link, BodyRef::body(0), "trial " + std::to_string(trial));
  }
  EXPECT_GT(near, 100);
}

TEST(FindContacts, OverlappingCubesInterpenetrate) {
  TwoCubes s = twoCubes(-5.0);
  EXPECT_TRUE(findContacts(s.world, s.upper, s.lower).interpenetrating);
  EXPECT_TRUE(findContacts(s.world, s.lower, s.upper).interpenetrating);
}

TEST(FindContacts, SeenFromTheOtherBodyIsTheMate) {
  TwoCubes s = twoCubes(0.1, 5, 5);
  const ContactResult from_upper = findContacts(s.world, s.upper, s.lower);
  const ContactResult from_lower = findContacts(s.world, s.lower, s.upper);
  ASSERT_EQ(from_upper.contacts.size(), from_lower.contacts.size());
  ASSERT_FALSE(from_upper.contacts.empty());
  for (const Contact& c : from_upper.contacts) {
    // mate(): bodies and points swapped, normal negated.
    const Contact m = c.mate();
    EXPECT_EQ(m.body1, c.body2);
    EXPECT_EQ(m.body2, c.body1);
    EXPECT_LT((m.position1 - c.position2).norm(), kSearchTolerance);
    EXPECT_LT((m.position2 - c.position1).norm(), kSearchTolerance);
    EXPECT_LT((m.normal + c.normal).norm(), kSearchTolerance);
    EXPECT_LT((m.frame.col(2) + c.normal).norm(), kSearchTolerance);
    EXPECT_DOUBLE_EQ(m.distance, c.distance);
    EXPECT_DOUBLE_EQ(m.mu, c.mu);
    // From the lower cube: the same contact, normal -z into the lower cube.
    const auto hit =
        std::find_if(from_lower.contacts.begin(), from_lower.contacts.end(), [&](const Contact& d) {
          return (d.position1 - c.position2).norm() < kSearchTolerance &&
                 (d.position2 - c.position1).norm() < kSearchTolerance;
        });
    ASSERT_NE(hit, from_lower.contacts.end()) << c.position1.transpose();
    EXPECT_EQ(hit->body1, s.lower);
    EXPECT_LT((hit->normal + Vector3::UnitZ()).norm(), kSearchTolerance);
    EXPECT_NEAR(hit->distance, 0.1, kSearchTolerance);
  }
}

TEST(FindContacts, IndependentOfTheBodiesOrderInTheWorld) {
  TwoCubes a = twoCubes(0.1, 5, 5);
  TwoCubes b = twoCubes(0.1, 5, 5, Material::Rubber, Material::Wood, false, /*upper_first=*/true);
  ASSERT_NE(a.upper, b.upper);
  const auto ca = findContacts(a.world, a.upper, a.lower).contacts;
  const auto cb = findContacts(b.world, b.upper, b.lower).contacts;
  ASSERT_EQ(ca.size(), cb.size());
  for (const Contact& c : ca) {
    const auto hit = std::find_if(cb.begin(), cb.end(), [&](const Contact& d) {
      return (d.position1 - c.position1).norm() < kSearchTolerance &&
             (d.normal - c.normal).norm() < kSearchTolerance;
    });
    EXPECT_NE(hit, cb.end()) << c.position1.transpose();
  }
}

TEST(FindContacts, FrictionFromTheMaterials) {
  // GraspIt!'s World::setDefaults static table.
  struct Case {
    Material upper, lower;
    double mu;
  };
  for (const Case& k :
       {Case{Material::Glass, Material::Metal, 0.2},
        Case{Material::Plastic, Material::Plastic, 0.3}, Case{Material::Wood, Material::Stone, 0.6},
        Case{Material::Rubber, Material::Rubber, 2.0}}) {
    TwoCubes s = twoCubes(0.1, 0, 0, k.upper, k.lower);
    const auto contacts = findContacts(s.world, s.upper, s.lower).contacts;
    ASSERT_FALSE(contacts.empty());
    for (const Contact& c : contacts) {
      EXPECT_DOUBLE_EQ(c.mu, k.mu) << nameOf(k.upper) << "/" << nameOf(k.lower);
      EXPECT_DOUBLE_EQ(c.mu, staticFriction(k.upper, k.lower));
      EXPECT_EQ(c.model, ContactModel::PointWithFriction);
    }
  }
}

TEST(FindContacts, FrictionlessMaterialGivesFrictionlessContacts) {
  TwoCubes s = twoCubes(0.1, 0, 0, Material::Rubber, Material::Frictionless);
  const auto contacts = findContacts(s.world, s.upper, s.lower).contacts;
  ASSERT_EQ(contacts.size(), 4u);
  for (const Contact& c : contacts) {
    EXPECT_EQ(c.mu, 0.0);
    EXPECT_EQ(c.model, ContactModel::Frictionless);
  }
}

TEST(FindContacts, ElasticBodiesMakeSoftFingers) {
  TwoCubes s = twoCubes(0.1, 0, 0, Material::Rubber, Material::Wood, /*upper_elastic=*/true);
  for (const Contact& c : findContacts(s.world, s.upper, s.lower).contacts)
    EXPECT_EQ(c.model, ContactModel::SoftFinger);
  ContactRequest rigid;
  rigid.softContacts = false;
  for (const Contact& c : findContacts(s.world, s.upper, s.lower, rigid).contacts)
    EXPECT_EQ(c.model, ContactModel::PointWithFriction);
}

TEST(FindContacts, BadBodyRefThrows) {
  TwoCubes s = twoCubes(0.1);
  EXPECT_THROW(findContacts(s.world, s.upper, BodyRef::body(7)), Error);
}

}  // namespace
}  // namespace graspkit
