// The C ABI's cost: 1e6 rays at the mug of GraspIt!'s plannerMug (world loaded through the C
// ABI, the mug alone in the scene), cast through graspkit_ray_scene_intersect and, as the
// baseline in the same run, through the C++ RayScene::intersect on the same world and rays.
// Counter `x_cpp`: the C++ call's time divided by the C ABI's, both in every iteration (1 is
// parity; 0.95 means the binding costs 5 %). Rays: from random points on a sphere of radius 200 mm
// about the mug towards random points of its bounding box (raycast_bench's set). One thread, CPU
// time.

#include <benchmark/benchmark.h>

#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <optional>
#include <random>
#include <vector>

#include "graspkit.h"
#include "graspkit/base/log.hpp"
#include "graspkit/io/graspit/world_file.hpp"
#include "graspkit/raycast/ray_scene.hpp"

namespace fs = std::filesystem;
using namespace graspkit;

namespace {

constexpr std::size_t kRays = 1'000'000;

fs::path sharedDir() {
  if (const char* env = std::getenv("GRASPKIT_SHARED"); env && *env) return env;
  return GRASPKIT_SHARED_DEFAULT;
}

double cpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

struct Fixture {
  graspkit_world* cWorld = nullptr;
  graspkit_ray_scene* cScene = nullptr;
  std::optional<World> world;
  std::optional<RayScene> scene;
  std::vector<graspkit_ray> cRays;
  std::vector<Ray> rays;
  bool ok() const { return cScene != nullptr; }
};

Fixture& fixture() {
  static Fixture f = [] {
    Fixture f;
    const fs::path file = sharedDir() / "graspit-data/worlds/plannerMug.xml";
    if (!fs::exists(file)) return f;
    setWarningHandler([](const Warning&) {});
    if (graspkit_world_load(file.c_str(), nullptr, &f.cWorld) != GRASPKIT_OK) return f;
    if (graspkit_ray_scene_new(f.cWorld, 0, &f.cScene) != GRASPKIT_OK) return f;
    f.world = loadWorldFile(file);
    RaySceneOptions only_bodies;
    only_bodies.include = [](const BodyRef& b) { return !b.isLink(); };
    f.scene.emplace(*f.world, only_bodies);

    const Body& mug = f.world->bodies().front();
    Eigen::AlignedBox3d box;
    for (const Vector3& v : mug.model->mesh->vertices) box.extend(mug.pose * v);
    std::mt19937_64 rng(7);
    std::normal_distribution<double> normal;
    std::uniform_real_distribution<double> unit;
    for (std::size_t i = 0; i < kRays; ++i) {
      const Vector3 from =
          box.center() + 200.0 * Vector3(normal(rng), normal(rng), normal(rng)).normalized();
      const Vector3 to =
          box.min() + Vector3(unit(rng), unit(rng), unit(rng)).cwiseProduct(box.sizes());
      Ray r;
      r.origin = from;
      r.direction = to - from;
      f.rays.push_back(r);
      graspkit_ray c{};
      for (int k = 0; k < 3; ++k) {
        c.origin[k] = from[k];
        c.direction[k] = r.direction[k];
      }
      c.tmin = 0;
      c.tmax = INFINITY;
      f.cRays.push_back(c);
    }
    return f;
  }();
  return f;
}

// Both calls in every iteration, one after the other, each timed on its own: the ratio is
// taken under the same machine load, and the two are reported apart as well.
void BM_Rays_CAbi_vs_Cpp(benchmark::State& state) {
  Fixture& f = fixture();
  if (!f.ok()) return state.SkipWithError("../shared/graspit-data not found");
  std::vector<graspkit_ray_hit> cHits(kRays);
  std::vector<std::optional<RayHit>> hits(kRays);
  double cSeconds = 0, cppSeconds = 0;
  for (auto _ : state) {
    double start = cpuSeconds();
    f.scene->intersect(f.rays, hits);
    cppSeconds += cpuSeconds() - start;
    start = cpuSeconds();
    if (graspkit_ray_scene_intersect(f.cScene, f.cRays.data(), cHits.data(), kRays) != GRASPKIT_OK)
      return state.SkipWithError(graspkit_last_error());
    cSeconds += cpuSeconds() - start;
    benchmark::DoNotOptimize(hits.data());
    benchmark::DoNotOptimize(cHits.data());
  }
  const double n = static_cast<double>(kRays) * static_cast<double>(state.iterations());
  state.counters["cpp_rays_per_s"] = n / cppSeconds;
  state.counters["c_rays_per_s"] = n / cSeconds;
  state.counters["x_cpp"] = cppSeconds / cSeconds;
}

}  // namespace

BENCHMARK(BM_Rays_CAbi_vs_Cpp)->Unit(benchmark::kMillisecond)->Iterations(20);
BENCHMARK_MAIN();
