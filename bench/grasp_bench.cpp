// Grasp analysis on GraspIt!'s plannerMug (Barrett hand, mug). The counter `x_graspit` is
// GraspIt!'s own median time for the same work (../shared/reference/graspit-figures.json,
// grasps.plannerMug_as_loaded.timing_median_s) divided by ours: above 1 means faster.
//  - Contacts: every hand link against the mug at GraspIt!'s autograsp pose (its
//    findAllContacts: 0.76 ms), and a second baseline in the same run: the same pairs through
//    FCL distance with nearest points (what a search built on exact distances would pay).
//  - CollisionReport at that pose (GraspIt!'s getCollisionReport: 0.23 ms).
//  - AutoGraspQuality: autograsp + contacts + L1 epsilon + volume from the loaded pose
//    (GraspIt!: 16 ms), and AutoGraspOnly (GraspIt!: 9.8 ms).
//  - ContactsPadsFaceToFace: a dense gripper's pads pressed together (see below).

#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "graspkit/base/log.hpp"
#include "graspkit/collision/collision.hpp"
#include "graspkit/collision/contact_search.hpp"
#include "graspkit/grasp/autograsp.hpp"
#include "graspkit/grasp/grasp.hpp"
#include "graspkit/io/graspit/world_file.hpp"
#include "graspkit/model/world.hpp"

namespace fs = std::filesystem;
using namespace graspkit;

namespace {

fs::path sharedDir() {
  if (const char* env = std::getenv("GRASPKIT_SHARED"); env && *env) return env;
  return GRASPKIT_SHARED_DEFAULT;
}

// plannerMug as loaded; with `at_grasp`, the hand at GraspIt!'s autograsp result.
std::optional<World> plannerMug(bool at_grasp) {
  setWarningHandler([](const Warning&) {});
  const fs::path file = sharedDir() / "graspit-data/worlds/plannerMug.xml";
  if (!fs::exists(file)) return std::nullopt;
  World world = loadWorldFile(file);
  if (at_grasp) {
    const std::vector<double> dofs = {0, 1.024375, 1.024375, 1.121875};
    world.setDofValues(0, dofs);
  }
  return world;
}

std::vector<BodyRef> handLinks(const World& world) {
  std::vector<BodyRef> links;
  for (const BodyRef& ref : worldBodies(world))
    if (ref.isLink() && ref.index == 0) links.push_back(ref);
  return links;
}

void rate(benchmark::State& state, double graspit_seconds) {
  state.counters["x_graspit"] =
      benchmark::Counter(graspit_seconds * state.iterations(), benchmark::Counter::kIsRate);
}

void BM_Contacts(benchmark::State& state) {
  auto world = plannerMug(true);
  if (!world) return state.SkipWithError("shared GraspIt! data not found");
  const auto links = handLinks(*world);
  std::size_t count = 0;
  for (auto _ : state) {
    count = 0;
    for (const BodyRef& link : links)
      count += findContacts(*world, link, BodyRef::body(0)).contacts.size();
  }
  state.counters["contacts"] = count;
  rate(state, 0.000755677);
}
BENCHMARK(BM_Contacts)->Unit(benchmark::kMicrosecond);

void BM_Contacts_FclDistanceBaseline(benchmark::State& state) {
  auto world = plannerMug(true);
  if (!world) return state.SkipWithError("shared GraspIt! data not found");
  const auto links = handLinks(*world);
  std::size_t near = 0;
  for (auto _ : state) {
    near = 0;
    for (const BodyRef& link : links)
      near += distance(*world, link, BodyRef::body(0)).distance < kContactThreshold;
  }
  state.counters["pairs_within_threshold"] = near;
  rate(state, 0.000755677);
}
BENCHMARK(BM_Contacts_FclDistanceBaseline)->Unit(benchmark::kMicrosecond);

void BM_CollisionReport(benchmark::State& state) {
  auto world = plannerMug(true);
  if (!world) return state.SkipWithError("shared GraspIt! data not found");
  std::size_t pairs = 0;
  for (auto _ : state) pairs = collisionReport(*world).size();
  state.counters["colliding_pairs"] = pairs;
  rate(state, 0.000229992);
}
BENCHMARK(BM_CollisionReport)->Unit(benchmark::kMicrosecond);

void BM_AutoGraspOnly(benchmark::State& state) {
  auto world = plannerMug(false);
  if (!world) return state.SkipWithError("shared GraspIt! data not found");
  for (auto _ : state) {
    World w = world->clone();
    benchmark::DoNotOptimize(autoGrasp(w, 0));
  }
  rate(state, 0.009796201);
}
BENCHMARK(BM_AutoGraspOnly)->Unit(benchmark::kMillisecond);

void BM_AutoGraspQuality(benchmark::State& state, HullMethod method) {
  auto world = plannerMug(false);
  if (!world) return state.SkipWithError("shared GraspIt! data not found");
  GraspRequest request;
  request.wrenchSpace.method = method;
  double epsilon = 0;
  for (auto _ : state) {
    World w = world->clone();
    AutoGraspResult closed = autoGrasp(w, 0);
    epsilon = analyzeGrasp(w, 0, BodyRef::body(0), closed.contacts, request).epsilon;
  }
  state.counters["epsilon"] = epsilon;
  rate(state, 0.015895678);
}
BENCHMARK_CAPTURE(BM_AutoGraspQuality, graspit_hull, HullMethod::GraspIt)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_AutoGraspQuality, skip_non_force_closure, HullMethod::SkipNonForceClosure)
    ->Unit(benchmark::kMillisecond);

// Menagerie's Robotiq 2F-85 closed on nothing: its two finger pads (19,134 triangles each) meet
// face to face, as in a validation squeeze of a grasp that missed. The contact search between
// them as a simulation step asks for it (0.7 mm, every contact kept): about 2 million point
// pairs from the triangle tests, a quarter million of them distinct, for a few dozen survivors. No
// GraspIt! figure; compare builds with farm-bench.
void BM_ContactsPadsFaceToFace(benchmark::State& state) {
  setWarningHandler([](const Warning&) {});
  const fs::path hand = sharedDir() / "hands/menagerie/robotiq_2f85_v4/2f85.xml";
  const fs::path object = fs::path(GRASPKIT_SOURCE_DIR) / "models/objects/box.xml";
  if (!fs::exists(hand)) return state.SkipWithError("Menagerie's 2F-85 not found");
  const fs::path file = fs::temp_directory_path() / "graspkit_bench_2f85_empty.xml";
  std::ofstream(file) << "<world><graspableBody><filename>" << object.string()
                      << "</filename><transform><fullTransform>(+1 +0 +0 +0)[+0 +0 +1000]"
                      << "</fullTransform></transform></graspableBody><robot><filename>"
                      << hand.string() << "</filename><dofValues>0</dofValues></robot></world>";
  World world = loadWorldFile(file);
  fs::remove(file);
  autoGrasp(world, 0);
  const BodyRef left = BodyRef::robotLink(0, {1, 1});
  const BodyRef right = BodyRef::robotLink(0, {3, 1});
  ContactRequest request;
  request.threshold = 0.7;
  request.compact = false;
  request.graspitDuplicates = false;
  request.touchingIsContact = true;
  std::size_t count = 0;
  for (auto _ : state) count = findContacts(world, left, right, request).contacts.size();
  state.counters["contacts"] = count;
}
BENCHMARK(BM_ContactsPadsFaceToFace)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
