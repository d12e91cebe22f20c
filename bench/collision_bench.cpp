// Collision queries on GraspIt!'s plannerMug world with the Barrett hand at the pose GraspIt!'s
// autograsp reaches (DOFs 0, 1.024375, 1.024375, 1.121875): the fingers rest on the mug, within
// a fraction of a millimetre, so the narrow phase cannot stop early on those pairs.
//
// - BM_CollisionReport: graspkit::collisionReport over the whole world. `x_graspit` is
//   GraspIt!'s 0.23 ms for the same report divided by ours; `x_raw_fcl` is the raw-FCL baseline
//   below, timed in the same run, divided by ours.
// - BM_CollideLinkMug: graspkit::collide of one fingertip against the mug.
// - BM_RawFcl<BV>: plain fcl::collide of each of the 9 hand bodies against the mug, BVHs built
//   beforehand, no box culling, no filter: the baseline, and the choice of bounding volume.

#include <benchmark/benchmark.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <optional>
#include <vector>

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/math/bv/AABB.h>
#include <fcl/math/bv/OBB.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/math/bv/RSS.h>
#include <fcl/math/bv/kIOS.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/collision_object.h>

#include "graspkit/base/log.hpp"
#include "graspkit/collision/collision.hpp"
#include "graspkit/io/graspit/world_file.hpp"
#include "graspkit/model/world.hpp"

namespace fs = std::filesystem;
using namespace graspkit;

namespace {

constexpr double kGraspitReportSeconds = 0.23e-3;

fs::path sharedDir() {
  if (const char* env = std::getenv("GRASPKIT_SHARED"); env && *env) return env;
  return GRASPKIT_SHARED_DEFAULT;
}

// The scene, loaded once; nullopt when the shared data is missing.
const std::optional<World>& scene() {
  static const std::optional<World> world = []() -> std::optional<World> {
    setWarningHandler([](const Warning&) {});
    const fs::path data = sharedDir() / "graspit-data";
    if (!fs::exists(data / "worlds/plannerMug.xml")) return std::nullopt;
    World w = loadWorldFile(data / "worlds/plannerMug.xml", LoadOptions{{data}});
    const double dofs[] = {0, 1.024375, 1.024375, 1.121875};
    w.setDofValues(0, dofs);
    return w;
  }();
  return world;
}

std::vector<BodyRef> handBodies(const World& world) {
  std::vector<BodyRef> hand;
  for (const BodyRef& ref : worldBodies(world))
    if (ref.isLink()) hand.push_back(ref);
  return hand;
}

template <typename BV>
struct RawScene {
  std::vector<std::shared_ptr<fcl::BVHModel<BV>>> models;  // hand bodies, then the mug
  std::vector<Transform> poses;
};

template <typename BV>
std::shared_ptr<fcl::BVHModel<BV>> rawModel(const TriangleMesh& mesh) {
  std::vector<fcl::Triangle> triangles;
  for (const auto& t : mesh.triangles) triangles.emplace_back(t[0], t[1], t[2]);
  auto model = std::make_shared<fcl::BVHModel<BV>>();
  model->beginModel();
  model->addSubModel(mesh.vertices, triangles);
  model->endModel();
  return model;
}

template <typename BV>
RawScene<BV> rawScene(const World& world) {
  RawScene<BV> raw;
  std::vector<BodyRef> refs = handBodies(world);
  refs.push_back(BodyRef::body(0));
  for (const BodyRef& ref : refs) {
    raw.models.push_back(rawModel<BV>(*bodyModel(world, ref).mesh));
    raw.poses.push_back(bodyPose(world, ref));
  }
  return raw;
}

// Plain FCL: every hand body against the mug, FCL's default request (one contact, no contact
// data). Returns the number of colliding pairs.
template <typename BV>
int rawCollide(const RawScene<BV>& raw) {
  const std::size_t mug = raw.models.size() - 1;
  int hits = 0;
  for (std::size_t i = 0; i < mug; ++i) {
    fcl::CollisionRequestd request;
    fcl::CollisionResultd result;
    hits += fcl::collide(raw.models[i].get(), raw.poses[i], raw.models[mug].get(), raw.poses[mug],
                         request, result) > 0;
  }
  return hits;
}

double rawBaselineSeconds(const World& world) {
  const auto raw = rawScene<fcl::OBBRSSd>(world);
  int hits = 0;
  for (int i = 0; i < 50; ++i) hits += rawCollide(raw);  // warm up
  const int reps = 2000;
  const auto start = std::chrono::steady_clock::now();
  for (int i = 0; i < reps; ++i) hits += rawCollide(raw);
  const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;
  benchmark::DoNotOptimize(hits);
  return elapsed.count() / reps;
}

void BM_CollisionReport(benchmark::State& state) {
  if (!scene()) return state.SkipWithError("shared GraspIt! data not found");
  const World& world = *scene();
  const double raw_seconds = rawBaselineSeconds(world);
  std::size_t pairs = 0;
  for (auto _ : state) {
    auto report = collisionReport(world);
    pairs = report.size();
    benchmark::DoNotOptimize(report);
  }
  state.counters["colliding_pairs"] = static_cast<double>(pairs);
  state.counters["raw_fcl_us"] = raw_seconds * 1e6;
  state.counters["x_graspit"] =
      benchmark::Counter(kGraspitReportSeconds * state.iterations(), benchmark::Counter::kIsRate);
  state.counters["x_raw_fcl"] =
      benchmark::Counter(raw_seconds * state.iterations(), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_CollisionReport)->Unit(benchmark::kMicrosecond);

void BM_CollideLinkMug(benchmark::State& state, LinkRef link) {
  if (!scene()) return state.SkipWithError("shared GraspIt! data not found");
  const World& world = *scene();
  const BodyRef hand_link = BodyRef::robotLink(0, link);
  const BodyRef mug = BodyRef::body(0);
  bool hit = false;
  for (auto _ : state) {
    hit = collide(world, hand_link, mug);
    benchmark::DoNotOptimize(hit);
  }
  state.counters["colliding"] = hit;
  state.counters["distance_mm"] = distance(world, hand_link, mug).distance;
}
BENCHMARK_CAPTURE(BM_CollideLinkMug, chain0_link2, LinkRef{0, 2})->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_CollideLinkMug, chain2_link1, LinkRef{2, 1})->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_CollideLinkMug, chain0_link0, LinkRef{0, 0})->Unit(benchmark::kMicrosecond);

template <typename BV>
void BM_RawFcl(benchmark::State& state) {
  if (!scene()) return state.SkipWithError("shared GraspIt! data not found");
  const auto raw = rawScene<BV>(*scene());
  int hits = 0;
  for (auto _ : state) {
    hits = rawCollide(raw);
    benchmark::DoNotOptimize(hits);
  }
  state.counters["colliding_pairs"] = hits;
}
BENCHMARK_TEMPLATE(BM_RawFcl, fcl::OBBRSSd)->Unit(benchmark::kMicrosecond);
BENCHMARK_TEMPLATE(BM_RawFcl, fcl::OBBd)->Unit(benchmark::kMicrosecond);
BENCHMARK_TEMPLATE(BM_RawFcl, fcl::RSSd)->Unit(benchmark::kMicrosecond);
BENCHMARK_TEMPLATE(BM_RawFcl, fcl::kIOSd)->Unit(benchmark::kMicrosecond);
BENCHMARK_TEMPLATE(BM_RawFcl, fcl::AABBd)->Unit(benchmark::kMicrosecond);

// Plain FCL through CollisionObject, made on every call, as naive callers do.
void BM_RawFclObjects(benchmark::State& state) {
  if (!scene()) return state.SkipWithError("shared GraspIt! data not found");
  const auto raw = rawScene<fcl::OBBRSSd>(*scene());
  const std::size_t mug = raw.models.size() - 1;
  int hits = 0;
  for (auto _ : state) {
    hits = 0;
    fcl::CollisionObjectd mug_object(raw.models[mug], raw.poses[mug]);
    for (std::size_t i = 0; i < mug; ++i) {
      fcl::CollisionObjectd object(raw.models[i], raw.poses[i]);
      fcl::CollisionRequestd request;
      fcl::CollisionResultd result;
      hits += fcl::collide(&object, &mug_object, request, result) > 0;
    }
    benchmark::DoNotOptimize(hits);
  }
  state.counters["colliding_pairs"] = hits;
}
BENCHMARK(BM_RawFclObjects)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
