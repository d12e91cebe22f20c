// The planning framework (eigengrasp map, search spaces, best list, energies) and the simann
// planner plugin, against truths computed here by other means:
//
// - GraspIt!'s Barrett eigengrasps (models/robots/Barrett/eigen/barrett_eigen.xml): e0 = d0,
//   e1 = (d1 + d2 + d3) / sqrt(3) (the file's (1, 1, 1) normalised), origin (1.13, 0.79, 0.79,
//   0.79), no <Limits> so amplitudes range over GraspIt!'s default [-4, 4]; the DOF ranges are
//   d0 in [0, 180] degrees and d1..d3 in [0, 144] degrees (Barrett.xml's joint limits).
// - The search variables' ranges and jumps: spec/graspit-behaviour.md section 6.
// - Hand poses composed here from the formula, e.g. axis-angle: reference * T(t) * R(axis(theta,
//   phi), alpha) * approach^-1.
// - Contact energy: the nearest object point found by brute force over the mug's triangles.
// - Planned grasps: re-placed and re-measured in a fresh clone of the world.

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <random>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <fmt/format.h>

#include "graspkit/base/error.hpp"
#include "graspkit/collision/collision.hpp"
#include "graspkit/grasp/autograsp.hpp"
#include "graspkit/grasp/grasp.hpp"
#include "graspkit/io/graspit/robot_file.hpp"
#include "graspkit/io/graspit/world_file.hpp"
#include "graspkit/model/robot.hpp"
#include "graspkit/model/virtual_contact.hpp"
#include "graspkit/model/world.hpp"
#include "graspkit/planning/best_list.hpp"
#include "graspkit/planning/centred_close.hpp"
#include "graspkit/planning/distinct_grasps.hpp"
#include "graspkit/planning/eigengrasp_map.hpp"
#include "graspkit/planning/planner.hpp"
#include "graspkit/planning/planning_scene.hpp"
#include "graspkit/planning/search_energy.hpp"
#include "graspkit/planning/search_space.hpp"
#include "graspkit/plugin/registry.hpp"
#include "test_paths.hpp"

namespace graspkit {
namespace {

constexpr double kPi = 3.14159265358979323846;
const double kSqrt3 = std::sqrt(3.0);
constexpr double kDegree = kPi / 180.0;

// ---------------------------------------------------------------------------------------------
// Fixtures

std::shared_ptr<const RobotModel> barrett() {
  return loadRobotFile(*test::graspitDataDir() / "models/robots/Barrett/Barrett.xml");
}

World plannerMug() {
  return loadWorldFile(*test::graspitDataDir() / "worlds/plannerMug.xml");
}

BodyRef mugOf(const World& world) {
  for (int i = 0; i < static_cast<int>(world.bodies().size()); ++i)
    if (world.bodies()[static_cast<std::size_t>(i)].name == "mug") return BodyRef::body(i);
  ADD_FAILURE() << "plannerMug has no body called mug";
  return {};
}

PlanningRequest mugRequest(std::shared_ptr<const World> world) {
  PlanningRequest request;
  request.object = mugOf(*world);
  request.world = std::move(world);
  return request;
}

// A pose from a translation and a rotation about an axis, composed by hand.
Transform poseOf(const Vector3& t, double angle = 0.0, const Vector3& axis = Vector3::UnitZ()) {
  Transform pose = Transform::Identity();
  pose.linear() = Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
  pose.translation() = t;
  return pose;
}

// Poses compared as poses: the origins within `mm`, the rotations within `rad`.
::testing::AssertionResult samePose(const Transform& a, const Transform& b, double mm = 1e-7,
                                    double rad = 1e-9) {
  const double dt = (a.translation() - b.translation()).norm();
  const double dr = Eigen::AngleAxisd(a.rotation() * b.rotation().transpose()).angle();
  if (dt <= mm && std::abs(dr) <= rad) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "poses differ by " << dt << " mm and " << dr << " rad\n"
                                       << a.matrix() << "\nvs\n"
                                       << b.matrix();
}

Vector3 unitRandom(std::mt19937_64& random) {
  std::normal_distribution<double> n;
  Vector3 v(n(random), n(random), n(random));
  return v.normalized();
}

// ---------------------------------------------------------------------------------------------
// EigengraspMap

TEST(EigengraspMap, BarrettAmplitudesGiveDofsByHand) {
  GRASPKIT_REQUIRE_SHARED();
  const auto hand = barrett();
  // Barrett.xml's joint limits, independently of how the loader turns them into DOF ranges.
  ASSERT_EQ(hand->dofs.size(), 4u);
  EXPECT_NEAR(hand->dofs[0].max, 180 * kDegree, 1e-12);
  EXPECT_NEAR(hand->dofs[1].max, 144 * kDegree, 1e-12);
  const EigengraspMap map(*hand);
  ASSERT_EQ(map.size(), 2);
  ASSERT_EQ(map.dofCount(), 4);
  for (int i = 0; i < 2; ++i) {
    EXPECT_EQ(map.minAmplitude(i), -4.0);  // the file's <Limits> are commented out
    EXPECT_EQ(map.maxAmplitude(i), 4.0);
  }
  const Eigen::VectorXd q = map.dofs(Eigen::Vector2d(0.2, 0.3));
  EXPECT_NEAR(q[0], 1.13 + 0.2, 1e-12);
  for (int d = 1; d < 4; ++d) EXPECT_NEAR(q[d], 0.79 + 0.3 / kSqrt3, 1e-12);
  const Eigen::VectorXd origin = map.dofs(Eigen::Vector2d::Zero());
  EXPECT_NEAR(origin[0], 1.13, 1e-12);
  EXPECT_NEAR(origin[3], 0.79, 1e-12);
}

TEST(EigengraspMap, BarrettAmplitudesRoundTripWhereNoDofClamps) {
  GRASPKIT_REQUIRE_SHARED();
  const EigengraspMap map(*barrett());
  // d0 = 1.13 + a0 stays in [0, pi] for a0 in [-1.13, 2.01]; d1 = 0.79 + a1/sqrt3 stays in
  // [0, 0.8 pi] for a1 in [-1.368, 2.985].
  std::mt19937_64 random(11);
  std::uniform_real_distribution<double> a0(-1.1, 2.0), a1(-1.35, 2.95);
  for (int k = 0; k < 200; ++k) {
    const Eigen::Vector2d a(a0(random), a1(random));
    const Eigen::VectorXd back = map.amplitudes(map.dofs(a));
    ASSERT_NEAR(back[0], a[0], 1e-12) << k;
    ASSERT_NEAR(back[1], a[1], 1e-12) << k;
  }
  // A posture off the subspace projects to the least-squares amplitudes: the mean of d1..d3.
  const Eigen::VectorXd a = map.amplitudes(Eigen::Vector4d(1.13, 0.5, 0.8, 1.1));
  EXPECT_NEAR(a[0], 0.0, 1e-12);
  EXPECT_NEAR(a[1], ((0.5 + 0.8 + 1.1) - 3 * 0.79) / kSqrt3, 1e-12);
}

TEST(EigengraspMap, BarrettDofsClampToTheirLimits) {
  GRASPKIT_REQUIRE_SHARED();
  const EigengraspMap map(*barrett());
  const Eigen::VectorXd high = map.dofs(Eigen::Vector2d(4.0, 4.0));  // 5.13 and 3.1 unclamped
  EXPECT_DOUBLE_EQ(high[0], kPi);
  for (int d = 1; d < 4; ++d) EXPECT_DOUBLE_EQ(high[d], 144 * kDegree);
  const Eigen::VectorXd low = map.dofs(Eigen::Vector2d(-4.0, -4.0));
  for (int d = 0; d < 4; ++d) EXPECT_DOUBLE_EQ(low[d], 0.0);
  // One DOF clamps, the others follow the formula.
  const Eigen::VectorXd mixed = map.dofs(Eigen::Vector2d(3.0, -1.0));
  EXPECT_DOUBLE_EQ(mixed[0], kPi);
  EXPECT_NEAR(mixed[2], 0.79 - 1.0 / kSqrt3, 1e-12);
}

TEST(EigengraspMap, RobotWithoutAFileHasIdentityEigengrasps) {
  // models/robots/parallel_jaw: one prismatic DOF in [0, 40] mm and no <eigenGrasps>: one
  // eigengrasp per DOF, origin at the middle of the range, amplitude spanning the DOF's range
  // (-20 .. 20 mm about the origin at 20), so the search can open and close the jaw fully.
  const auto jaw = loadRobotFile(test::modelsDir() / "robots/parallel_jaw/parallel_jaw.xml");
  ASSERT_EQ(jaw->dofs.size(), 1u);
  ASSERT_EQ(jaw->dofs[0].min, 0.0);
  ASSERT_EQ(jaw->dofs[0].max, 40.0);
  const EigengraspMap map(*jaw);
  ASSERT_EQ(map.size(), 1);
  EXPECT_DOUBLE_EQ(map.dofs(Eigen::VectorXd::Constant(1, 3.0))[0], 23.0);
  EXPECT_DOUBLE_EQ(map.dofs(Eigen::VectorXd::Constant(1, -4.0))[0], 16.0);
  EXPECT_DOUBLE_EQ(map.amplitudes(Eigen::VectorXd::Constant(1, 35.0))[0], 15.0);
  EXPECT_DOUBLE_EQ(map.dofs(Eigen::VectorXd::Constant(1, 30.0))[0], 40.0);  // clamped
  EXPECT_DOUBLE_EQ(map.minAmplitude(0), -20.0);
  EXPECT_DOUBLE_EQ(map.maxAmplitude(0), 20.0);
}

// ---------------------------------------------------------------------------------------------
// SearchSpace

// Barrett with an approach frame away from the palm origin and tilted, so that approach^-1 in
// the pose formulas is not the identity (Barrett.xml's own is).
std::shared_ptr<RobotModel> tiltedApproachBarrett() {
  auto model = std::make_shared<RobotModel>(*barrett());
  ApproachDirection approach;
  approach.referenceLocation = Vector3(10, -5, 30);
  approach.direction = Vector3(0.3, 0.2, 1.0).normalized();
  model->approach = approach;
  return model;
}

const Transform kReference = poseOf(Vector3(3, 0.8, 105.8), 0.7, Vector3(1, 2, 3));

TEST(SearchSpace, ApproachFrameIsWhereTheModelSays) {
  GRASPKIT_REQUIRE_SHARED();
  const auto hand = tiltedApproachBarrett();
  const Transform a = hand->approachFrame();
  EXPECT_TRUE(a.translation().isApprox(Vector3(10, -5, 30), 1e-12));
  EXPECT_TRUE(a.linear().col(2).isApprox(Vector3(0.3, 0.2, 1.0).normalized(), 1e-12));
  EXPECT_NEAR(std::abs(a.linear().determinant() - 1.0), 0.0, 1e-12);
}

void expectVariable(const SearchVariable& v, const char* name, double min, double max, double jump,
                    bool circular = false) {
  SCOPED_TRACE(name);
  EXPECT_EQ(v.name, name);
  EXPECT_NEAR(v.min, min, 1e-15);
  EXPECT_NEAR(v.max, max, 1e-15);
  EXPECT_NEAR(v.jump, jump, 1e-15);
  EXPECT_EQ(v.circular, circular);
  EXPECT_FALSE(v.fixed);
}

TEST(SearchSpace, VariablesMatchGraspItsTable) {
  GRASPKIT_REQUIRE_SHARED();
  const auto hand = barrett();
  {
    const SearchSpace s(*hand, PositionSpace::AxisAngle, PostureSpace::Eigen, kReference);
    ASSERT_EQ(s.size(), 8);
    ASSERT_EQ(s.postureSize(), 2);
    const auto v = s.variables();
    // Eigen: [-4, 4] without <Limits>, jump = range / 4.
    expectVariable(v[0], "EG 0", -4, 4, 2);
    expectVariable(v[1], "EG 1", -4, 4, 2);
    expectVariable(v[2], "Tx", -250, 250, 150);
    expectVariable(v[3], "Ty", -250, 250, 150);
    expectVariable(v[4], "Tz", -250, 350, 150);
    expectVariable(v[5], "theta", 0, kPi, kPi / 5);
    expectVariable(v[6], "phi", -kPi, kPi, kPi / 2, true);
    expectVariable(v[7], "alpha", 0, kPi, kPi / 2);
  }
  {
    const SearchSpace s(*hand, PositionSpace::Complete, PostureSpace::Dof, kReference);
    ASSERT_EQ(s.size(), 4 + 7);
    const auto v = s.variables();
    // DOF postures: the DOF's range, jump = range / 2.
    EXPECT_NEAR(v[0].jump, kPi / 2, 1e-12);
    EXPECT_NEAR(v[1].max, 144 * kDegree, 1e-12);
    EXPECT_NEAR(v[1].jump, 72 * kDegree, 1e-12);
    for (int i = 4; i < 7; ++i) {
      EXPECT_EQ(v[i].min, -250);
      EXPECT_EQ(v[i].max, 250);
      EXPECT_EQ(v[i].jump, 100);
    }
    for (int i = 7; i < 11; ++i) {
      EXPECT_EQ(v[i].min, -5);
      EXPECT_EQ(v[i].max, 5);
      EXPECT_EQ(v[i].jump, 1);
    }
  }
  {
    const SearchSpace s(*hand, PositionSpace::Ellipsoid, PostureSpace::Eigen, kReference);
    const auto v = s.variables();
    ASSERT_EQ(s.size(), 2 + 4);
    EXPECT_NEAR(v[2].min, -kPi / 2, 1e-15);
    EXPECT_NEAR(v[2].max, kPi / 2, 1e-15);
    EXPECT_TRUE(v[3].circular);
    EXPECT_TRUE(v[4].circular);
    EXPECT_EQ(v[5].min, -50);
    EXPECT_EQ(v[5].max, 100);
  }
  {
    const SearchSpace s(*hand, PositionSpace::Approach, PostureSpace::Eigen, kReference);
    const auto v = s.variables();
    ASSERT_EQ(s.size(), 2 + 3);
    EXPECT_EQ(v[2].min, -30);
    EXPECT_EQ(v[2].max, 200);
    for (int i = 3; i < 5; ++i) {
      EXPECT_NEAR(v[i].min, -kPi / 3, 1e-15);
      EXPECT_NEAR(v[i].max, kPi / 3, 1e-15);
    }
  }
}

TEST(SearchSpace, AxisAngleHandPoseByHand) {
  GRASPKIT_REQUIRE_SHARED();
  const auto hand = tiltedApproachBarrett();
  const SearchSpace space(*hand, PositionSpace::AxisAngle, PostureSpace::Eigen, kReference);
  const Transform approachInverse = hand->approachFrame().inverse();
  std::mt19937_64 random(5);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int k = 0; k < 100; ++k) {
    const double tx = -250 + 500 * unit(random), ty = -250 + 500 * unit(random),
                 tz = -250 + 600 * unit(random), theta = kPi * unit(random),
                 phi = -kPi + 2 * kPi * unit(random), alpha = kPi * unit(random);
    const std::vector<double> values = {0.5, -0.5, tx, ty, tz, theta, phi, alpha};
    const Vector3 axis(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                       std::cos(theta));
    const Transform expected = kReference * poseOf(Vector3(tx, ty, tz)) *
                               poseOf(Vector3::Zero(), alpha, axis) * approachInverse;
    ASSERT_TRUE(samePose(space.handPose(values), expected, 1e-9)) << k;
  }
}

TEST(SearchSpace, CompleteHandPoseByHand) {
  GRASPKIT_REQUIRE_SHARED();
  const auto hand = tiltedApproachBarrett();
  const SearchSpace space(*hand, PositionSpace::Complete, PostureSpace::Eigen, kReference);
  // An unnormalised quaternion (2, 0, 0, 2) is a quarter turn about x: GraspIt! normalises.
  const std::vector<double> values = {0, 0, 10, -20, 30, 2, 2, 0, 0};
  const Transform expected = kReference * poseOf(Vector3(10, -20, 30), kPi / 2, Vector3::UnitX());
  EXPECT_TRUE(samePose(space.handPose(values), expected, 1e-9));
}

// encode() then handPose() gives back the pose; dofs() gives back the posture.
void expectRoundTrip(const SearchSpace& space, const Transform& pose,
                     const std::vector<double>& dofs) {
  const std::vector<double> values = space.encode(pose, dofs);
  ASSERT_EQ(static_cast<int>(values.size()), space.size());
  EXPECT_TRUE(samePose(space.handPose(values), pose, 1e-8, 1e-9));
  const std::vector<double> back = space.dofs(values);
  for (std::size_t d = 0; d < dofs.size(); ++d) EXPECT_NEAR(back[d], dofs[d], 1e-12) << d;
}

TEST(SearchSpace, EncodeRoundTripsPosesInEveryInvertibleSpace) {
  GRASPKIT_REQUIRE_SHARED();
  const auto hand = tiltedApproachBarrett();
  const EigengraspMap map(*hand);
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (PostureSpace posture : {PostureSpace::Eigen, PostureSpace::Dof}) {
    for (PositionSpace position : {PositionSpace::Complete, PositionSpace::AxisAngle}) {
      SCOPED_TRACE(fmt::format("{} {}", nameOf(position), nameOf(posture)));
      const SearchSpace space(*hand, position, posture, kReference);
      for (int k = 0; k < 50; ++k) {
        // Any orientation; the approach origin within 150 mm of the reference, inside both
        // spaces' translation ranges.
        const Vector3 origin = unitRandom(random) * 150 * unit(random);
        const Transform core = poseOf(origin, kPi * unit(random), unitRandom(random));
        const Transform pose = kReference * core * hand->approachFrame().inverse();
        const Eigen::VectorXd q = map.dofs(Eigen::Vector2d(-1 + 2 * unit(random), unit(random)));
        expectRoundTrip(space, pose, {q.data(), q.data() + q.size()});
      }
    }
  }
  // Rotations by 0 and by pi, where the axis-angle encoding has special cases.
  const SearchSpace axisAngle(*hand, PositionSpace::AxisAngle, PostureSpace::Dof, kReference);
  const std::vector<double> dofs = {0.1, 0.2, 0.3, 0.4};
  for (const Vector3& axis :
       {Vector3(0, 0, 1), Vector3(0, 0, -1), Vector3(1, 0, 0), Vector3(0.6, -0.8, 0)}) {
    for (double angle : {0.0, kPi, kPi - 1e-9}) {
      SCOPED_TRACE(::testing::Message() << axis.transpose() << " angle " << angle);
      expectRoundTrip(
          axisAngle,
          kReference * poseOf(Vector3(5, 6, 7), angle, axis) * hand->approachFrame().inverse(),
          dofs);
    }
  }
}

TEST(SearchSpace, ApproachSpaceRoundTripsDistanceAlongTheApproach) {
  GRASPKIT_REQUIRE_SHARED();
  const auto hand = tiltedApproachBarrett();
  const Transform approach = hand->approachFrame();
  const Transform start = kReference;  // the hand's starting pose
  const SearchSpace space(*hand, PositionSpace::Approach, PostureSpace::Eigen, start);
  // The approach space recovers only the distance moved along the approach direction (its
  // wrist angles encode as 0), so the poses tested are the start moved along that direction.
  for (double dist : {-30.0, 0.0, 12.5, 200.0}) {
    const Transform pose = start * approach * poseOf(Vector3(0, 0, dist)) * approach.inverse();
    // By hand: the palm moves by dist along the approach direction, turned into the world.
    EXPECT_TRUE((pose.translation() - start.translation())
                    .isApprox(dist * (start.linear() * approach.linear().col(2)), 1e-12) ||
                dist == 0.0);
    expectRoundTrip(space, pose, {1.13, 0.79, 0.79, 0.79});
    const std::vector<double> values = {0, 0, dist, 0, 0};
    EXPECT_TRUE(samePose(space.handPose(values), pose, 1e-9));
  }
}

TEST(SearchSpace, EllipsoidSpaceRefusesToEncode) {
  GRASPKIT_REQUIRE_SHARED();
  const SearchSpace space(*barrett(), PositionSpace::Ellipsoid, PostureSpace::Eigen, kReference);
  EXPECT_THROW(space.encode(kReference, std::vector<double>{0, 0, 0, 0}), Error);
}

TEST(SearchSpace, DistanceIsGraspItsRule) {
  GRASPKIT_REQUIRE_SHARED();
  World world = plannerMug();
  const BodyRef mug = mugOf(world);
  const BodyModel& model = bodyModel(world, mug);
  // The mug's max radius by brute force: the largest CoG-to-vertex distance.
  double r = 0.0;
  for (const Vector3& v : model.mesh->vertices) r = std::max(r, (v - model.cog).norm());
  ASSERT_GT(r, 10.0);
  EXPECT_NEAR(model.maxRadius, r, 1e-9);

  const auto hand = tiltedApproachBarrett();
  const SearchSpace space(*hand, PositionSpace::AxisAngle, PostureSpace::Eigen,
                          bodyPose(world, mug));
  const std::vector<double> a = {0, 0, 20, 30, 40, 1.0, 0.5, 0.3};
  std::vector<double> moved = a;
  moved[2] += 10;  // 10 mm along the object's x
  EXPECT_NEAR(space.distance(a, moved, r), 10.0 / r, 1e-12);
  std::vector<double> turned = a;
  turned[7] += 0.4;  // 0.4 rad more about the same axis, same approach origin
  EXPECT_NEAR(space.distance(a, turned, r), 0.2 / kPi, 1e-12);
  EXPECT_NEAR(space.distance(turned, a, r), 0.2 / kPi, 1e-12);
  std::vector<double> both = moved;
  both[7] += 0.4;
  EXPECT_NEAR(space.distance(a, both, r), std::max(10.0 / r, 0.2 / kPi), 1e-12);
  // Postures do not count.
  std::vector<double> shaped = a;
  shaped[0] = 3, shaped[1] = -2;
  EXPECT_NEAR(space.distance(a, shaped, r), 0.0, 1e-12);
  // No radius: GraspIt!'s 200 mm.
  EXPECT_NEAR(space.distance(a, moved, 0.0), 10.0 / 200.0, 1e-12);
}

// ---------------------------------------------------------------------------------------------
// BestList

double planeDistance(std::span<const double> a, std::span<const double> b) {
  return std::hypot(a[0] - b[0], a[1] - b[1]);
}

TEST(BestList, RandomOffersKeepEveryInvariant) {
  constexpr int kCapacity = 6;
  constexpr double kThreshold = 0.2;
  std::mt19937_64 random(1234);
  std::uniform_real_distribution<double> coordinate(0.0, 1.0), energy(-50.0, 50.0);
  for (int run = 0; run < 20; ++run) {
    BestList list(kCapacity, kThreshold, planeDistance);
    for (int k = 0; k < 400; ++k) {
      SearchState s{{coordinate(random), coordinate(random)}, energy(random)};
      if (k % 37 == 0) s.energy = 1e5 + k;  // never enters a list that is not full
      const std::vector<SearchState> before = list.states();
      const bool wasFull = list.full();
      const double worst = before.empty() ? 0.0 : before.back().energy;
      bool nearAtLeastAsGood = false;
      for (const SearchState& listed : before)
        if (planeDistance(listed.values, s.values) < kThreshold && listed.energy <= s.energy)
          nearAtLeastAsGood = true;
      const bool entered = list.offer(s);

      // The entry rule, from before/after alone.
      const bool shouldEnter = (wasFull ? s.energy < worst : s.energy < 1e5) && !nearAtLeastAsGood;
      ASSERT_EQ(entered, shouldEnter) << "run " << run << " offer " << k;
      const auto& after = list.states();
      if (!entered) {
        ASSERT_EQ(after.size(), before.size());
        for (std::size_t i = 0; i < after.size(); ++i) ASSERT_EQ(after[i].values, before[i].values);
      } else {
        ASSERT_TRUE(std::any_of(after.begin(), after.end(),
                                [&](const SearchState& x) { return x.values == s.values; }));
        // Every listed state it displaced was near it and worse.
        for (const SearchState& old : before) {
          const bool kept = std::any_of(after.begin(), after.end(), [&](const SearchState& x) {
            return x.values == old.values;
          });
          if (!kept && old.energy <= after.back().energy)
            ASSERT_LT(planeDistance(old.values, s.values), kThreshold);
        }
      }
      // Invariants.
      ASSERT_LE(static_cast<int>(after.size()), kCapacity);
      ASSERT_TRUE(std::is_sorted(after.begin(), after.end(),
                                 [](const auto& x, const auto& y) { return x.energy < y.energy; }));
      for (std::size_t i = 0; i < after.size(); ++i)
        for (std::size_t j = i + 1; j < after.size(); ++j)
          ASSERT_GE(planeDistance(after[i].values, after[j].values), kThreshold);
    }
    EXPECT_TRUE(list.full());  // 400 offers over a unit square fill 6 places 0.2 apart
  }
}

TEST(BestList, ANearBetterStateDisplacesTheWorse) {
  BestList list(3, 0.2, planeDistance);
  EXPECT_TRUE(list.offer({{0.0, 0.0}, 5.0}));
  EXPECT_TRUE(list.offer({{1.0, 0.0}, 6.0}));
  EXPECT_FALSE(list.offer({{0.1, 0.0}, 5.0}));  // near and no better
  EXPECT_TRUE(list.offer({{0.1, 0.0}, 3.0}));   // near and better: takes the place
  ASSERT_EQ(list.states().size(), 2u);
  EXPECT_EQ(list.states()[0].values, (std::vector<double>{0.1, 0.0}));
  EXPECT_EQ(list.states()[1].energy, 6.0);
  // One state near two listed ones displaces both when better than both.
  EXPECT_TRUE(list.offer({{0.5, 0.0}, 7.0}));
  EXPECT_TRUE(list.offer({{0.6, 0.0}, 1.0}));  // within 0.2 of (0.5, 0) only
  EXPECT_EQ(list.states().size(), 3u);
  EXPECT_TRUE(list.offer({{0.9, 0.0}, 0.5}));  // near (1, 0) and not (0.6, 0): list was full
  ASSERT_EQ(list.states().size(), 3u);
  EXPECT_EQ(list.states()[0].energy, 0.5);
  EXPECT_EQ(list.states()[1].energy, 1.0);
  EXPECT_EQ(list.states()[2].energy, 3.0);
}

TEST(BestList, EntryBarAndCapacity) {
  BestList list(2, 0.2, planeDistance);
  EXPECT_EQ(list.entryEnergy(), 1e5);
  EXPECT_FALSE(list.offer({{0, 0}, 1e5}));  // the bar is strict
  EXPECT_FALSE(list.offer({{0, 0}, kUnevaluatedEnergy}));
  EXPECT_TRUE(list.offer({{0, 0}, 99999.0}));
  EXPECT_TRUE(list.offer({{1, 0}, 10.0}));
  EXPECT_TRUE(list.full());
  EXPECT_EQ(list.entryEnergy(), 99999.0);
  EXPECT_FALSE(list.offer({{2, 0}, 1e6}));  // worse than the worst of a full list
  EXPECT_TRUE(list.offer({{3, 0}, 20.0}));  // better than the worst: the worst leaves
  ASSERT_EQ(list.states().size(), 2u);
  EXPECT_EQ(list.states()[0].energy, 10.0);
  EXPECT_EQ(list.states()[1].energy, 20.0);
  // A bad list is refused.
  EXPECT_THROW(BestList(0, 0.2, planeDistance), Error);
  EXPECT_THROW(BestList(3, -1.0, planeDistance), Error);
  EXPECT_THROW(BestList(3, 0.2, nullptr), Error);
}

TEST(BestList, MergeKeepsTheRule) {
  BestList a(4, 0.2, planeDistance), b(4, 0.2, planeDistance);
  a.offer({{0, 0}, 5});
  a.offer({{1, 0}, 2});
  b.offer({{0.05, 0}, 4});  // near a's (0, 0) and better
  b.offer({{2, 0}, 9});
  a.merge(b);
  ASSERT_EQ(a.states().size(), 3u);
  EXPECT_EQ(a.states()[0].energy, 2);
  EXPECT_EQ(a.states()[1].energy, 4);
  EXPECT_EQ(a.states()[2].energy, 9);
}

// ---------------------------------------------------------------------------------------------
// Energies on plannerMug, against a brute-force nearest point over the mug's triangles.

// The point of triangle (a, b, c) nearest p (Ericson, Real-Time Collision Detection 5.1.5).
Vector3 nearestOnTriangle(const Vector3& p, const Vector3& a, const Vector3& b, const Vector3& c) {
  const Vector3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Vector3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + ab * (d1 / (d1 - d3));
  const Vector3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + ac * (d2 / (d2 - d6));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
  const double denom = 1.0 / (va + vb + vc);
  return a + ab * (vb * denom) + ac * (vc * denom);
}

struct ObjectSurface {
  std::vector<Vector3> vertices;  // world
  const TriangleMesh* mesh = nullptr;

  Vector3 nearest(const Vector3& p) const {
    Vector3 best = Vector3::Zero();
    double bestSq = std::numeric_limits<double>::infinity();
    for (const auto& t : mesh->triangles) {
      const Vector3 q = nearestOnTriangle(p, vertices[t[0]], vertices[t[1]], vertices[t[2]]);
      if ((q - p).squaredNorm() < bestSq) bestSq = (q - p).squaredNorm(), best = q;
    }
    return best;
  }
};

ObjectSurface surfaceOf(const World& world, const BodyRef& body) {
  ObjectSurface s;
  s.mesh = bodyModel(world, body).mesh.get();
  const Transform pose = bodyPose(world, body);
  for (const Vector3& v : s.mesh->vertices) s.vertices.push_back(pose * v);
  return s;
}

// Virtual contacts placed from the model by hand: the link's world pose times the contact's
// location; the normal turned by the link's rotation.
struct HandContact {
  Vector3 point;
  Vector3 normal;
};

std::vector<HandContact> handContacts(const Robot& robot) {
  std::vector<HandContact> out;
  for (const VirtualContact& c : robot.model().virtualContacts) {
    const Transform link = c.finger < 0 ? robot.pose() : robot.linkPose(c.finger, c.link);
    out.push_back({link * c.location, (link.linear() * c.normal).normalized()});
  }
  return out;
}

double contactEnergyByHand(const Robot& robot, const ObjectSurface& surface) {
  const auto contacts = handContacts(robot);
  double total = 0.0;
  for (const HandContact& c : contacts) {
    const Vector3 d = surface.nearest(c.point) - c.point;
    total += d.norm() + 50.0 * (1.0 - c.normal.dot(d.normalized()));
  }
  return total / static_cast<double>(contacts.size());
}

TEST(SearchEnergies, ContactEnergyIsTheMeanOverVirtualContacts) {
  GRASPKIT_REQUIRE_SHARED();
  auto request = mugRequest(std::make_shared<World>(plannerMug()));
  auto space = makeSearchSpace(request);
  auto scene = makePlanningScene(request, space);
  // all_16_contacts.xml holds 19 contacts (its <num_contacts>), despite its name.
  ASSERT_EQ(scene->hand().model().virtualContacts.size(), 19u);
  const ObjectSurface surface = surfaceOf(scene->world(), scene->object());
  auto energy = Registry::global().makeSearchEnergy("contact");
  auto graspitNamed = Registry::global().makeSearchEnergy("CONTACT_ENERGY");
  std::mt19937_64 random(3);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int checked = 0;
  for (int k = 0; k < 40 && checked < 8; ++k) {
    // Approach origins 60..160 mm from the mug's frame, any orientation and posture.
    const std::vector<double> values = {-4 + 8 * unit(random),         -4 + 8 * unit(random),
                                        -160 + 320 * unit(random),     -160 + 320 * unit(random),
                                        -100 + 300 * unit(random),     kPi * unit(random),
                                        -kPi + 2 * kPi * unit(random), kPi * unit(random)};
    scene->place(values);
    if (scene->handCollides()) continue;
    const double expected = contactEnergyByHand(scene->hand(), surface);
    EXPECT_NEAR(energy->evaluate(*scene), expected, 1e-6 * std::max(1.0, expected)) << k;
    EXPECT_NEAR(graspitNamed->evaluate(*scene), expected, 1e-6 * std::max(1.0, expected)) << k;
    ++checked;
  }
  EXPECT_GE(checked, 4);
}

TEST(SearchEnergies, PotentialQualityIsOneWhenTheHandIsFarAway) {
  GRASPKIT_REQUIRE_SHARED();
  auto request = mugRequest(std::make_shared<World>(plannerMug()));
  auto scene = makePlanningScene(request, makeSearchSpace(request));
  const ObjectSurface surface = surfaceOf(scene->world(), scene->object());
  auto energy = Registry::global().makeSearchEnergy("potential-quality");
  // The hand 300 mm from the mug, facing it: no virtual contact within 50 mm.
  scene->place(std::vector<double>{0, 0, 0, 0, -300, 0, 0, 0});
  double nearest = std::numeric_limits<double>::infinity();
  for (const HandContact& c : handContacts(scene->hand()))
    nearest = std::min(nearest, (surface.nearest(c.point) - c.point).norm());
  ASSERT_GT(nearest, 50.0);
  EXPECT_EQ(energy->evaluate(*scene), 1.0);
  EXPECT_EQ(Registry::global().makeSearchEnergy("POTENTIAL_QUALITY_ENERGY")->evaluate(*scene), 1.0);
}

TEST(SearchEnergies, UnknownEnergyIsRefusedByName) {
  try {
    Registry::global().makeSearchEnergy("no-such-energy");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("no-such-energy"), std::string::npos) << e.what();
  }
}

// ---------------------------------------------------------------------------------------------
// simann

std::vector<PlannedGrasp> plan(const PlanningRequest& request, std::int64_t steps) {
  auto planner = Registry::global().makePlanner("simann", request);
  PlanningBudget budget;
  budget.steps = steps;
  return runPlanner(*planner, budget).grasps;
}

PlanningRequest annealRequest(std::shared_ptr<const World> world, std::uint64_t seed, int threads) {
  PlanningRequest request = mugRequest(std::move(world));
  request.seed = seed;
  request.threads = threads;
  request.options = {{"mode", "anneal"}};
  return request;
}

void expectSameGrasps(const std::vector<PlannedGrasp>& a, const std::vector<PlannedGrasp>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].values, b[i].values) << i;
    EXPECT_EQ(a[i].energy, b[i].energy) << i;
  }
}

// The hand's links in a world.
std::vector<BodyRef> handLinks(const World& world, int robot) {
  std::vector<BodyRef> links;
  for (const BodyRef& b : worldBodies(world))
    if (b.isLink() && b.index == robot) links.push_back(b);
  return links;
}

class SimAnn : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!test::sharedDir()) GTEST_SKIP() << "SKIPPED: ../shared (GraspIt! corpus) not found";
    world_ = std::make_shared<World>(plannerMug());
  }
  std::shared_ptr<const World> world_;
};

// A registered energy evaluated in full every time: what the search did before it learned to
// stop summing once the Metropolis test must reject.
class EnergyInFull final : public SearchEnergy {
 public:
  explicit EnergyInFull(const std::string& name)
      : energy_(Registry::global().makeSearchEnergy(name)) {}
  double evaluate(PlanningScene& scene) override { return energy_->evaluate(scene); }
  bool expensive() const override { return false; }

 private:
  std::unique_ptr<SearchEnergy> energy_;
};

TEST_F(SimAnn, StoppingTheEnergySumEarlyChangesNothing) {
  for (const std::string name : {"contact", "guided-potential-quality"})
    for (std::uint64_t seed : {1u, 7u}) {
      SCOPED_TRACE(name + " seed " + std::to_string(seed));
      auto bounded = annealRequest(world_, seed, 1);
      bounded.energy = name;
      auto full = bounded;
      full.customEnergy = [name] { return std::make_unique<EnergyInFull>(name); };
      const auto expected = plan(full, 4000);
      ASSERT_FALSE(expected.empty());
      expectSameGrasps(plan(bounded, 4000), expected);
    }
}

TEST_F(SimAnn, ABoundedContactEnergyIsExactBelowItsBound) {
  auto request = annealRequest(world_, 1, 1);
  auto scene = makePlanningScene(request, makeSearchSpace(request));
  auto energy = Registry::global().makeSearchEnergy("contact");
  std::mt19937_64 random(5);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int k = 0; k < 20; ++k) {
    const std::vector<double> values = {-4 + 8 * unit(random),         -4 + 8 * unit(random),
                                        -160 + 320 * unit(random),     -160 + 320 * unit(random),
                                        -100 + 300 * unit(random),     kPi * unit(random),
                                        -kPi + 2 * kPi * unit(random), kPi * unit(random)};
    scene->place(values);
    const double full = energy->evaluate(*scene);
    EXPECT_EQ(energy->evaluateBelow(*scene, full), full) << k;
    EXPECT_EQ(energy->evaluateBelow(*scene, 2.0 * full + 1.0), full) << k;
    // Below the energy: anything above the bound, never below it.
    EXPECT_GT(energy->evaluateBelow(*scene, 0.25 * full), 0.25 * full) << k;
  }
}

TEST_F(SimAnn, SameSeedSameBestListForEachThreadCount) {
  for (int threads : {1, 2}) {
    SCOPED_TRACE(threads);
    const auto request = annealRequest(world_, 3, threads);
    const auto first = plan(request, 1500);
    ASSERT_FALSE(first.empty());
    expectSameGrasps(first, plan(request, 1500));
  }
  // Another seed searches elsewhere.
  const auto a = plan(annealRequest(world_, 3, 1), 1500);
  const auto b = plan(annealRequest(world_, 4, 1), 1500);
  EXPECT_NE(a.front().values, b.front().values);
}

TEST_F(SimAnn, GraspsAreCollisionFreeDistinctAndRanked) {
  const auto request = annealRequest(world_, 5, 2);
  const auto grasps = plan(request, 3000);
  ASSERT_GE(grasps.size(), 2u);
  const auto space = makeSearchSpace(request);
  const double radius = bodyModel(*world_, request.object).maxRadius;
  for (std::size_t i = 0; i < grasps.size(); ++i) {
    SCOPED_TRACE(i);
    // Re-placed in a fresh clone, from the pose and DOFs the planner reports.
    World clone = world_->clone();
    clone.setRobotPose(0, grasps[i].pose);
    clone.setDofValues(0, grasps[i].dofs, LimitPolicy::Clamp);
    const auto links = handLinks(clone, 0);
    EXPECT_FALSE(anyCollision(clone, links));
    CollisionRequest report;
    report.interest = links;
    EXPECT_TRUE(collisionReport(clone, report).empty());
    // The pose and DOFs are those of the state's values.
    EXPECT_TRUE(samePose(grasps[i].pose, space->handPose(grasps[i].values), 1e-9));
    // Ranked, below GraspIt!'s entry bar, and no two within the best list's distance.
    EXPECT_LT(grasps[i].energy, 1e5);
    if (i > 0) EXPECT_LE(grasps[i - 1].energy, grasps[i].energy);
    for (std::size_t j = i + 1; j < grasps.size(); ++j)
      EXPECT_GE(space->distance(grasps[i].values, grasps[j].values, radius), 0.2) << j;
  }
}

TEST_F(SimAnn, ContactEnergyOfReturnedGraspsIsRecomputedByHand) {
  const auto request = annealRequest(world_, 6, 1);
  const auto grasps = plan(request, 1500);
  ASSERT_FALSE(grasps.empty());
  World clone = world_->clone();
  const ObjectSurface surface = surfaceOf(clone, request.object);
  for (std::size_t i = 0; i < std::min<std::size_t>(grasps.size(), 5); ++i) {
    clone.setRobotPose(0, grasps[i].pose);
    clone.setDofValues(0, grasps[i].dofs, LimitPolicy::Clamp);
    EXPECT_NEAR(grasps[i].energy, contactEnergyByHand(clone.robot(0), surface), 1e-6) << i;
  }
}

// Closes the hand from a grasp's pose and DOFs in a fresh clone and measures it.
Grasp remeasure(const World& world, const BodyRef& object, const PlannedGrasp& g) {
  World clone = world.clone();
  clone.setRobotPose(0, g.pose);
  clone.setDofValues(0, g.dofs, LimitPolicy::Clamp);
  autoGrasp(clone, 0);
  return analyzeGrasp(clone, 0, object);
}

PlanningRequest restartRequest(std::shared_ptr<const World> world, std::uint64_t seed,
                               int threads) {
  PlanningRequest request = mugRequest(std::move(world));
  request.seed = seed;
  request.threads = threads;
  request.options = {{"mode", "restarts"}};
  return request;
}

int forceClosureCount(const std::vector<PlannedGrasp>& grasps) {
  return static_cast<int>(std::count_if(grasps.begin(), grasps.end(),
                                        [](const PlannedGrasp& g) { return g.forceClosure; }));
}

// Every grasp a restarts plan returns is closed and measured, and ranked by that measure; a
// fresh clone closed from the grasp's pre-grasp state by hand measures the same (GraspIt!'s
// epsilon and volume).
TEST_F(SimAnn, RestartsReturnClosedGraspsRankedByQuality) {
  const auto request = restartRequest(world_, 1, 2);
  const auto grasps = plan(request, 5000);
  ASSERT_FALSE(grasps.empty());
  // GraspIt!'s single search found 2 force-closure grasps in 340 autograsped states.
  EXPECT_GE(forceClosureCount(grasps), 5);
  for (std::size_t i = 0; i < grasps.size(); ++i) {
    SCOPED_TRACE(i);
    ASSERT_TRUE(grasps[i].evaluated);
    if (i > 0) EXPECT_FALSE(betterGrasp(grasps[i], grasps[i - 1]));
    const Grasp fresh = remeasure(*world_, request.object, grasps[i]);
    EXPECT_EQ(grasps[i].contacts, static_cast<int>(fresh.contacts.size()));
    EXPECT_NEAR(grasps[i].epsilon, fresh.epsilon, 1e-9);
    EXPECT_EQ(grasps[i].forceClosure, fresh.forceClosure);
    // The closes were ranked without hulls; what is returned carries GraspIt!'s figures.
    EXPECT_NEAR(grasps[i].volume, fresh.volume, 1e-9 * fresh.volume);
  }
}

// The bug: saved grasps lost the breakaway state autograsp left, and reloaded with the hand
// inside the mug. The world graspWorld() gives, saved and loaded back, measures the same.
TEST_F(SimAnn, SavedGraspWorldsReloadToTheSameGrasp) {
  const auto request = restartRequest(world_, 2, 2);
  const auto grasps = plan(request, 3000);
  ASSERT_FALSE(grasps.empty());
  const auto folder =
      std::filesystem::temp_directory_path() / ("graspkit_reload_" + std::to_string(::getpid()));
  std::filesystem::create_directories(folder);
  LoadOptions load;
  load.roots = {*test::graspitDataDir()};
  int broken = 0;
  for (std::size_t i = 0; i < grasps.size(); ++i) {
    SCOPED_TRACE(i);
    const auto file = folder / ("grasp_" + std::to_string(i) + ".xml");
    saveWorldFile(graspWorld(request, grasps[i]), file);
    const World loaded = loadWorldFile(file, load);
    const Robot& hand = loaded.robot(request.robot);
    for (const BreakawayState& b : hand.breakaway()) broken += b.engaged ? 1 : 0;
    const Grasp again = analyzeGrasp(loaded, request.robot, request.object);
    EXPECT_EQ(static_cast<int>(again.contacts.size()), grasps[i].contacts);
    EXPECT_NEAR(again.epsilon, grasps[i].epsilon,
                1e-6 * std::max(1.0, std::abs(grasps[i].epsilon)));
    EXPECT_NEAR(again.volume, grasps[i].volume, 1e-6 * std::max(1.0, grasps[i].volume));
    EXPECT_EQ(again.forceClosure, grasps[i].forceClosure);
  }
  // The check means something only if some Barrett finger broke away.
  EXPECT_GT(broken, 0);
  std::filesystem::remove_all(folder);
}

// More budget runs the same restarts and more: force-closure grasps and the best epsilon never
// fall as the budget grows (they fell from 6 to 0 with the old two-stage search).
TEST_F(SimAnn, MoreBudgetNeverFindsFewerForceClosureGrasps) {
  int previous = -1;
  double best = -1.0;
  for (std::int64_t steps : {1000, 4000, 10000}) {
    SCOPED_TRACE(steps);
    const auto grasps = plan(restartRequest(world_, 3, 2), steps);
    ASSERT_FALSE(grasps.empty());
    EXPECT_GE(forceClosureCount(grasps), previous);
    EXPECT_GE(grasps.front().epsilon, best);
    previous = forceClosureCount(grasps);
    best = grasps.front().epsilon;
  }
  EXPECT_GE(previous, 5);
}

// A step budget is a number of restarts, shared out among the threads: the thread count
// changes the speed, not the grasps.
TEST_F(SimAnn, RestartsGiveTheSameGraspsForEveryThreadCount) {
  const auto one = plan(restartRequest(world_, 4, 1), 2500);
  const auto two = plan(restartRequest(world_, 4, 2), 2500);
  expectSameGrasps(one, two);
  for (std::size_t i = 0; i < std::min(one.size(), two.size()); ++i)
    EXPECT_EQ(one[i].epsilon, two[i].epsilon) << i;
}

// A time budget covers every stage: the run returns close to it.
TEST_F(SimAnn, SecondsBudgetIsKept) {
  auto planner = Registry::global().makePlanner("simann", restartRequest(world_, 5, 2));
  PlanningBudget budget;
  // Long enough for whole restarts even in a sanitizer build on a busy machine (one restart
  // there takes about two seconds: 600 steps and four closes, each with its centring moves).
  budget.seconds = 6.0;
  const PlanningRun run = runPlanner(*planner, budget);
  EXPECT_LT(run.seconds, 6.0 * 1.05 + 0.1);  // one autograsp of slack
  EXPECT_FALSE(run.grasps.empty());
}

// finishGrasps() closes every grasp in one reused scene per thread. Each grasp must be measured
// as if alone: the breakaway joints the previous autograsp engaged must not carry over (when they
// did, later grasps closed with stuck distal joints, sank into the mug and were reported as
// force closure with dozens of contacts).
TEST_F(SimAnn, FinishGraspsMeasuresEachGraspAsAFreshWorldWould) {
  PlanningRequest request = mugRequest(world_);
  request.seed = 3;
  request.threads = 1;
  request.bestListSize = 6;
  request.options = {{"mode", "anneal"}};
  auto grasps = plan(request, 2000);
  ASSERT_GE(grasps.size(), 2u);
  finishGrasps(request, grasps, 1);
  for (std::size_t i = 0; i < grasps.size(); ++i) {
    SCOPED_TRACE(i);
    ASSERT_TRUE(grasps[i].evaluated);
    const Grasp fresh = remeasure(*world_, request.object, grasps[i]);
    EXPECT_EQ(grasps[i].contacts, static_cast<int>(fresh.contacts.size()));
    EXPECT_NEAR(grasps[i].epsilon, fresh.epsilon, 1e-9);
    EXPECT_NEAR(grasps[i].volume, fresh.volume, 1e-9);
    EXPECT_EQ(grasps[i].forceClosure, fresh.forceClosure);
  }
}

void expectRefused(const PlanningRequest& request, const std::string& words) {
  try {
    plan(request, 10);
    ADD_FAILURE() << "no error; expected one saying '" << words << "'";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
  }
}

TEST_F(SimAnn, BadRequestsAreRefusedClearly) {
  PlanningRequest base = annealRequest(world_, 1, 1);
  {
    PlanningRequest r = base;
    r.threads = 0;
    expectRefused(r, "0 threads");
  }
  {
    PlanningRequest r = base;
    r.options["preset"] = "FAST";
    expectRefused(r, "unknown preset 'FAST'");
  }
  {
    PlanningRequest r = base;
    r.options["bogus"] = "1";
    expectRefused(r, "unknown option 'bogus'");
  }
  {
    PlanningRequest r = base;
    r.options["mode"] = "sideways";
    expectRefused(r, "mode 'sideways'");
  }
  {
    PlanningRequest r = base;
    r.options = {{"mode", "restarts"}, {"start", "nowhere"}};
    expectRefused(r, "start 'nowhere'");
  }
  {
    PlanningRequest r = base;
    r.options = {{"mode", "restarts"}, {"restart-steps", "2.5"}};
    expectRefused(r, "restart-steps");
  }
  {
    PlanningRequest r = base;
    r.options["threshold"] = "-1";
    expectRefused(r, "threshold");
  }
  {
    PlanningRequest r = base;
    r.states = {SearchState{{1.0, 2.0, 3.0}}};
    expectRefused(r, "the start state has 3 values; the axis-angle space has 8");
  }
  {
    PlanningRequest r = base;
    r.energy = "no-such-energy";
    expectRefused(r, "no-such-energy");
  }
  EXPECT_THROW(Registry::global().makePlanner("no-such-planner", base), Error);
}

// A restarts request naming an unknown refinement energy must be refused when the planner is
// made, like an unknown search energy, not after the search has spent its budget.
TEST_F(SimAnn, UnknownRefineEnergyIsRefusedBeforeTheSearch) {
  PlanningRequest r = annealRequest(world_, 1, 1);
  r.options = {{"mode", "restarts"}, {"refine-steps", "5"}, {"refine-energy", "no-such-energy"}};
  try {
    Registry::global().makePlanner("simann", r);
    ADD_FAILURE() << "an unknown refine-energy is accepted until the search has run";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("no-such-energy"), std::string::npos) << e.what();
  }
}

// ---------------------------------------------------------------------------------------------
// Hands without virtual contacts

// models/worlds/gripper_box.xml: the parallel jaw (no virtual-contact file) centred over the box,
// its approach direction down, jaws open: inner faces at x = +-40 mm, finger pads centred 30 mm
// below the palm face (z = 131 - 31 = 100), palm face at z = 131 (the model file's comments).
TEST(DerivedVirtualContacts, ParallelJawPadsAndPalmByHand) {
  const World world = loadWorldFile(test::modelsDir() / "worlds" / "gripper_box.xml");
  ASSERT_TRUE(world.robot(0).model().virtualContacts.empty());
  const auto derived = deriveVirtualContacts(world.robot(0));
  ASSERT_EQ(derived.size(), 3u);
  EXPECT_EQ(derived[0].finger, -1);  // the palm first
  PlanningRequest request;
  request.world = std::make_shared<World>(world);
  request.object = BodyRef::body(1);
  auto scene = makePlanningScene(request, makeSearchSpace(request));
  ASSERT_TRUE(scene->virtualContactsDerived());
  const auto placed = scene->virtualContacts();
  ASSERT_EQ(placed.size(), 3u);
  EXPECT_TRUE(placed[0].point.isApprox(Vector3(0, 0, 131), 1e-9)) << placed[0].point.transpose();
  EXPECT_TRUE(placed[0].normal.isApprox(Vector3(0, 0, -1), 1e-9));
  for (int f : {1, 2}) {
    const double side = placed[f].point.x() > 0 ? 1.0 : -1.0;
    EXPECT_NEAR(std::abs(placed[f].point.x()), 40.0, 1e-9);
    EXPECT_NEAR(placed[f].point.z(), 100.0, 1e-9);
    EXPECT_TRUE(placed[f].normal.isApprox(Vector3(-side, 0, 0), 1e-9)) << f;  // facing the box
  }
  // The contact energy is no longer 0 everywhere: the palm 11 mm above the box top, the pads
  // 10 mm from its faces, all facing it: (11 + 10 + 10) / 3.
  auto energy = Registry::global().makeSearchEnergy("contact");
  EXPECT_NEAR(energy->evaluate(*scene), 31.0 / 3.0, 1e-6);
}

// The plan of a hand without virtual contacts finds force closure; GraspIt!'s start state there
// closes to epsilon 0.307, and a plan never does worse than its start.
TEST(DerivedVirtualContacts, GripperBoxPlansForceClosure) {
  auto world =
      std::make_shared<World>(loadWorldFile(test::modelsDir() / "worlds" / "gripper_box.xml"));
  PlanningRequest request;
  request.world = world;
  request.object = BodyRef::body(1);
  request.threads = 2;
  request.options = {{"mode", "restarts"}};
  const auto grasps = plan(request, 40000);
  ASSERT_FALSE(grasps.empty());
  EXPECT_TRUE(grasps.front().forceClosure);
  // Not just the start state: the searched grasps close on both jaws too (the compliant-wrist
  // close; without it a rigid two-jaw gripper grips only when centred to a fraction of a mm).
  EXPECT_GE(forceClosureCount(grasps), 5);
  EXPECT_GT(grasps.front().epsilon, 0.3);
  for (const PlannedGrasp& g : grasps) EXPECT_LT(g.energy, 1e5);  // evaluated, never a silent 0
}

// ---------------------------------------------------------------------------------------------
// Closing with a compliant wrist

// gripper_box with the hand moved 6 mm along +x: the jaws (inner faces at x = 46 and -34) stand
// 16 and 4 mm off the box faces (x = +-30). One rigid DOF closes both, so the -x jaw touches
// after 4 mm and stops the +x jaw 12 mm short: one jaw touches, no force closure. Half that gap
// back along -x centres the hand exactly (flat faces, so the FCL gap is exact), and closing
// again grips with both jaws.
TEST(CentredClose, OffCentreParallelJawGripsWithBothJaws) {
  World world = loadWorldFile(test::modelsDir() / "worlds" / "gripper_box.xml");
  const Transform centred = world.robot(0).pose();
  Transform offCentre = centred;
  offCentre.translation().x() += 6.0;
  world.setRobotPose(0, offCentre);
  PlanningRequest request;
  request.world = std::make_shared<World>(world);
  request.object = BodyRef::body(1);
  request.options = {{"mode", "restarts"}};
  const auto space = makeSearchSpace(request);
  auto scene = makePlanningScene(request, space);

  PlannedGrasp plain;
  plain.pose = offCentre;
  plain.dofs = {0.0};
  plain.values = space->encode(plain.pose, plain.dofs);
  PlannedGrasp centredGrasp = plain;
  finishGrasp(*scene, plain);
  EXPECT_FALSE(plain.forceClosure);
  EXPECT_NEAR(plain.closed.dofs.at(0), 4.0, 0.1);  // the near jaw's gap, to the contact band

  closeCentred(*scene, centredGrasp);
  ASSERT_TRUE(centredGrasp.forceClosure);
  EXPECT_NEAR(centredGrasp.pose.translation().x(), centred.translation().x(), 0.05);
  EXPECT_NEAR(centredGrasp.closed.dofs.at(0), 10.0, 0.1);  // both jaws travel 10 mm
  std::set<int> chains;
  for (const Contact& c : centredGrasp.contactList)
    for (const BodyRef& b : {c.body1, c.body2})
      if (b.isLink() && !b.link.isBase()) chains.insert(b.link.chain);
  EXPECT_EQ(chains, (std::set<int>{0, 1}));
  // The moved grasp is one the search space names, and its saved world reloads to it.
  EXPECT_TRUE(space->handPose(centredGrasp.values).isApprox(centredGrasp.pose, 1e-9));
  const Grasp reloaded = analyzeGrasp(graspWorld(request, centredGrasp), 0, request.object);
  EXPECT_NEAR(reloaded.epsilon, centredGrasp.epsilon, 1e-6 * centredGrasp.epsilon);
  EXPECT_EQ(static_cast<int>(reloaded.contacts.size()), centredGrasp.contacts);
  // Closing a fresh world from the moved pre-grasp gives the same grasp again.
  const Grasp reclosed = remeasure(world, request.object, centredGrasp);
  EXPECT_NEAR(reclosed.epsilon, centredGrasp.epsilon, 1e-6 * centredGrasp.epsilon);
}

// A linkage gripper's inner bars close with its fingers but never reach the object, so only the
// chains with virtual contacts (its fingers) say where to move. MuJoCo Menagerie's Robotiq 2F-85
// points down at the 60 x 60 x 120 mm box, its pads across the box's 60 mm width; moved 8 mm
// along the way its pads close, the near pad touches alone. The centred close moves the hand
// back over the box and grips with both pads (the two follower chains). Counting the drivers'
// gaps too, which lie along the approach, the move pushed the palm into the box instead.
TEST(CentredClose, LinkageGripperCentresOnItsFingersNotItsInnerBars) {
  GRASPKIT_REQUIRE_SHARED();
  const std::filesystem::path hand =
      *test::sharedDir() / "hands/menagerie/robotiq_2f85_v4/2f85.xml";
  if (!std::filesystem::exists(hand)) GTEST_SKIP() << "SKIPPED: " << hand << " not found";
  const std::filesystem::path file = test::scratchDir() / "robotiq_box.xml";
  std::ofstream(file) << fmt::format(
      "<world><graspableBody><filename>{}</filename></graspableBody>"
      "<robot><filename>{}</filename><dofValues>0</dofValues><transform>"
      "<fullTransform>(+0 +1 +0 +0)[+8 +0 +185]</fullTransform></transform></robot></world>",
      (test::modelsDir() / "objects" / "box.xml").string(), hand.string());
  const World world = loadWorldFile(file);
  PlanningRequest request;
  request.world = std::make_shared<World>(world);
  request.object = BodyRef::body(0);
  request.options = {{"mode", "restarts"}};
  const auto space = makeSearchSpace(request);
  auto scene = makePlanningScene(request, space);
  // The fingers are the chains the derived virtual contacts sit on: the two followers.
  std::set<int> fingers;
  for (const VirtualContact& contact : scene->virtualContactModels())
    if (contact.finger >= 0) fingers.insert(contact.finger);
  ASSERT_EQ(fingers.size(), 2u);
  auto touching = [](const PlannedGrasp& grasp) {
    std::set<int> chains;
    for (const Contact& c : grasp.contactList)
      for (const BodyRef& b : {c.body1, c.body2})
        if (b.isLink() && !b.link.isBase()) chains.insert(b.link.chain);
    return chains;
  };

  PlannedGrasp plain;
  plain.pose = world.robot(0).pose();
  plain.dofs = {0.0};
  plain.values = space->encode(plain.pose, plain.dofs);
  PlannedGrasp centred = plain;
  finishGrasp(*scene, plain);
  EXPECT_FALSE(plain.forceClosure);
  EXPECT_EQ(touching(plain).size(), 1u);

  closeCentred(*scene, centred);
  ASSERT_TRUE(centred.forceClosure);
  EXPECT_EQ(touching(centred), fingers);
  // Back over the box (the pads need not meet it at one instant: within 2 of the 8 mm), and
  // neither down along the approach nor sideways.
  EXPECT_LT(std::abs(centred.pose.translation().x()), 2.0);
  EXPECT_NEAR(centred.pose.translation().y(), 0.0, 1.0);
  EXPECT_NEAR(centred.pose.translation().z(), 185.0, 1.0);
}

// A close measured for ranking builds no hull: the same contacts, the exact hull's epsilon and
// force closure (qhull "Qt", a second method) and no volume; measureVolume() then gives GraspIt!'s
// volume bit for bit and measureAsGraspIt() all of GraspIt!'s figures, from the grasp's contacts
// alone (in the request's world, where the hand still stands open). The Barrett is closed on
// plannerMug from its world pose moved sideways in steps: the far ones touch the mug with one
// or two fingers.
TEST(CentredClose, ARankingCloseMeasuresTheExactHullAndLaterGraspItsOwn) {
  GRASPKIT_REQUIRE_SHARED();
  const auto world = std::make_shared<const World>(plannerMug());
  const PlanningRequest request = mugRequest(world);
  const auto space = makeSearchSpace(request);
  auto scene = makePlanningScene(request, space);
  GraspRequest exact;
  exact.wrenchSpace.method = HullMethod::ExactHull;
  int closures = 0, others = 0;
  for (const double dx : {0.0, 20.0, 40.0, 60.0, -20.0, -40.0, -60.0}) {
    SCOPED_TRACE(dx);
    PlannedGrasp measured;
    measured.pose = world->robot(0).pose();
    measured.pose.translation().x() += dx;
    measured.dofs.assign(world->robot(0).dofValues().begin(), world->robot(0).dofValues().end());
    PlannedGrasp ranked = measured;
    finishGrasp(*scene, measured);
    finishGrasp(*scene, ranked, {}, CloseMeasure::Ranking);
    ASSERT_EQ(ranked.contacts, measured.contacts);
    EXPECT_TRUE(std::isnan(ranked.volume));
    const Grasp exactHull =
        analyzeGrasp(*request.world, request.robot, request.object, ranked.contactList, exact);
    EXPECT_EQ(ranked.forceClosure, exactHull.forceClosure);
    EXPECT_EQ(ranked.forceClosure, measured.forceClosure);  // none of these is near-degenerate
    if (ranked.forceClosure) {
      EXPECT_NEAR(ranked.epsilon, exactHull.epsilon, 1e-9 * exactHull.epsilon);
      EXPECT_NEAR(ranked.epsilon, measured.epsilon, 0.05 * measured.epsilon);  // qhull's merges
      ++closures;
    } else {
      EXPECT_EQ(ranked.epsilon, -1.0);
      ++others;
    }
    PlannedGrasp volumeOnly = ranked;
    measureVolume(*request.world, request.robot, request.object, volumeOnly);
    EXPECT_EQ(volumeOnly.volume, measured.volume);
    EXPECT_EQ(volumeOnly.epsilon, ranked.epsilon);
    measureAsGraspIt(*request.world, request.robot, request.object, ranked);
    EXPECT_EQ(ranked.epsilon, measured.epsilon);
    EXPECT_EQ(ranked.forceClosure, measured.forceClosure);
    EXPECT_EQ(ranked.volume, measured.volume);
  }
  EXPECT_GE(closures, 1);
  EXPECT_GE(others, 1);
}

// A grasp already in force closure is left as it is: the rule only acts on a failed close.
TEST(CentredClose, ForceClosureGraspIsNotMoved) {
  World world = loadWorldFile(test::modelsDir() / "worlds" / "gripper_box.xml");
  PlanningRequest request;
  request.world = std::make_shared<World>(world);
  request.object = BodyRef::body(1);
  const auto space = makeSearchSpace(request);
  auto scene = makePlanningScene(request, space);
  PlannedGrasp grasp;
  grasp.pose = world.robot(0).pose();
  grasp.dofs = {0.0};
  grasp.values = space->encode(grasp.pose, grasp.dofs);
  closeCentred(*scene, grasp);
  ASSERT_TRUE(grasp.forceClosure);
  EXPECT_TRUE(grasp.pose.isApprox(world.robot(0).pose(), 1e-12));
}

// ---------------------------------------------------------------------------------------------
// DistinctGrasps

TEST(DistinctGrasps, ForceClosureCountAndBestEpsilonNeverFall) {
  // States on a line, distance = |a - b|, threshold 1: random offers of random quality.
  DistinctGrasps kept(1.0, [](std::span<const double> a, std::span<const double> b) {
    return std::abs(a[0] - b[0]);
  });
  std::mt19937 random(7);
  std::uniform_real_distribution<double> where(0.0, 30.0), quality(-0.5, 0.5);
  int previousCount = 0;
  double previousBest = -1.0;
  for (int i = 0; i < 2000; ++i) {
    PlannedGrasp g;
    g.values = {where(random)};
    g.evaluated = true;
    g.epsilon = quality(random);
    g.forceClosure = g.epsilon > 0;
    if (!g.forceClosure) g.epsilon = -1.0;
    kept.offer(g);
    ASSERT_GE(kept.forceClosureCount(), previousCount);
    const auto top = kept.best(5);
    ASSERT_GE(top.front().epsilon, previousBest);
    previousCount = kept.forceClosureCount();
    previousBest = top.front().epsilon;
    // No two kept grasps within the threshold.
    const auto all = kept.best(kept.size());
    for (std::size_t a = 0; a < all.size(); ++a)
      for (std::size_t b = a + 1; b < all.size(); ++b)
        ASSERT_GE(std::abs(all[a].values[0] - all[b].values[0]), 1.0);
  }
  EXPECT_GT(previousCount, 5);
}

// Grasps whose volumes are deferred, measured only where the ranking reads them, are kept and
// ranked as the same grasps with every volume known: after each offer, the best 1, 3 and 8 and
// the whole list are the same grasps in the same order. Force closure kept beyond the list asked
// for spares the measurements.
TEST(DistinctGrasps, DeferredVolumesRankAsKnownOnes) {
  const auto distance = [](std::span<const double> a, std::span<const double> b) {
    return std::abs(a[0] - b[0]);
  };
  std::vector<double> volumes;  // of the grasp numbered values[1]
  int measured = 0;
  DistinctGrasps known(1.0, distance);
  DistinctGrasps deferred(1.0, distance, [&](PlannedGrasp& g) {
    if (!std::isnan(g.volume)) return;
    g.volume = volumes.at(static_cast<std::size_t>(g.values[1]));
    ++measured;
  });
  std::mt19937 random(11);
  std::uniform_real_distribution<double> where(0.0, 40.0), quality(-0.8, 0.2), volume(0.0, 1.0);
  int offeredWithoutClosure = 0;
  for (int i = 0; i < 1500; ++i) {
    PlannedGrasp g;
    g.values = {where(random), static_cast<double>(i)};
    g.evaluated = true;
    g.epsilon = quality(random);
    g.forceClosure = g.epsilon > 0;
    if (!g.forceClosure) g.epsilon = -1.0;
    g.volume = volume(random);
    g.energy = where(random);
    volumes.push_back(g.volume);
    known.offer(g);
    if (!g.forceClosure) {
      g.volume = std::numeric_limits<double>::quiet_NaN();
      ++offeredWithoutClosure;
    }
    deferred.offer(g);
    for (const std::size_t count : {std::size_t{1}, std::size_t{3}, std::size_t{8}}) {
      const auto a = known.best(count), b = deferred.best(count);
      ASSERT_EQ(a.size(), b.size());
      for (std::size_t k = 0; k < a.size(); ++k) {
        ASSERT_EQ(a[k].values, b[k].values) << "offer " << i << ", best " << count;
        // A volume the order did not need (a grasp alone at its epsilon) may stay unknown.
        if (!std::isnan(b[k].volume)) ASSERT_EQ(a[k].volume, b[k].volume);
      }
    }
  }
  const int measuredBeforeTheWholeList = measured;
  const auto a = known.best(known.size()), b = deferred.best(deferred.size());
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) EXPECT_EQ(a[k].values, b[k].values);
  EXPECT_GT(deferred.forceClosureCount(), 8);
  EXPECT_LT(measuredBeforeTheWholeList, offeredWithoutClosure / 2);
}

// best(count) measures the volumes its order reads, each once: none while `count` force-closure
// grasps are kept, those of the grasps that are not force closure (tied at epsilon -1) otherwise.
TEST(DistinctGrasps, BestMeasuresEachVolumeItsOrderReadsOnce) {
  const auto distance = [](std::span<const double> a, std::span<const double> b) {
    return std::abs(a[0] - b[0]);
  };
  int measured = 0;
  DistinctGrasps kept(1.0, distance, [&](PlannedGrasp& g) {
    if (!std::isnan(g.volume)) return;
    g.volume = g.values[1];  // a volume known to the test, revealed only by measuring
    ++measured;
  });
  // Three force-closure grasps and five that are not, 2 apart (none replaces another).
  for (int i = 0; i < 8; ++i) {
    PlannedGrasp g;
    g.values = {2.0 * i, 1.0 + (i * 5) % 8};
    g.evaluated = true;
    g.forceClosure = i % 3 == 0;
    g.epsilon = g.forceClosure ? 0.1 * g.values[1] : -1.0;
    g.volume = std::numeric_limits<double>::quiet_NaN();
    kept.offer(g);
  }
  ASSERT_EQ(kept.forceClosureCount(), 3);
  ASSERT_EQ(measured, 0);
  EXPECT_EQ(kept.best(3).size(), 3u);  // three force-closure grasps fill it: nothing to measure
  EXPECT_EQ(measured, 0);
  const auto a = kept.best(6);
  EXPECT_EQ(measured, 5);  // the five grasps that are not force closure
  const auto again = kept.best(6);
  EXPECT_EQ(measured, 5);
  ASSERT_EQ(a.size(), 6u);
  ASSERT_EQ(again.size(), 6u);
  for (std::size_t k = 0; k < a.size(); ++k) EXPECT_EQ(a[k].values, again[k].values) << k;
  for (std::size_t k = 3; k < a.size(); ++k) EXPECT_EQ(a[k].volume, a[k].values[1]) << k;
  // By hand: force closure by epsilon (0.8, 0.7, 0.1 at i = 3, 6, 0), then the rest by volume
  // (6, 5, 4 at i = 1, 4, 7).
  EXPECT_EQ(a[0].values[0], 6.0);
  EXPECT_EQ(a[1].values[0], 12.0);
  EXPECT_EQ(a[2].values[0], 0.0);
  EXPECT_EQ(a[3].values[0], 2.0);
  EXPECT_EQ(a[4].values[0], 8.0);
  EXPECT_EQ(a[5].values[0], 14.0);
}

}  // namespace
}  // namespace graspkit
