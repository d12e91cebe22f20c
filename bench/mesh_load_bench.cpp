// Geometry loading: GraspIt!'s mug, every Robonaut link (40092 triangles in the full robot;
// GraspIt! loads the robot in 240 ms, graspkit aims at a fifth of that), mass properties of
// those links, and the OFF parser on a large generated mesh.

#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "graspkit/geometry/mass_properties.hpp"
#include "graspkit/geometry/mesh_loader.hpp"

namespace {

namespace fs = std::filesystem;

// ../shared/graspit-data beside the checkout, or under $GRASPKIT_SHARED.
std::optional<fs::path> graspitData() {
  fs::path shared = GRASPKIT_SHARED_DEFAULT;
  if (const char* env = std::getenv("GRASPKIT_SHARED"); env != nullptr && *env != '\0') {
    shared = env;
  }
  if (!fs::is_directory(shared / "graspit-data")) return std::nullopt;
  return shared / "graspit-data";
}

constexpr const char* kNoSharedData =
    "skipped: ../shared/graspit-data not found (set GRASPKIT_SHARED)";

std::vector<fs::path> robonautLinkFiles(const fs::path& data) {
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(data / "models/robots/Robonaut/iv")) {
    if (entry.path().extension() == ".iv") files.push_back(entry.path());
  }
  return files;
}

void BM_LoadMug(benchmark::State& state) {
  const auto data = graspitData();
  if (!data) return state.SkipWithError(kNoSharedData);
  graspkit::initInventorReader();  // Coin's one-off start-up is not part of a load
  std::size_t triangles = 0;
  for (auto _ : state) {
    const graspkit::TriangleMesh mesh = graspkit::loadMesh(*data / "models/objects/mug.iv");
    triangles = mesh.triangleCount();
    benchmark::DoNotOptimize(mesh.vertices.data());
  }
  state.counters["triangles"] = static_cast<double>(triangles);
}
BENCHMARK(BM_LoadMug)->Unit(benchmark::kMillisecond);

void BM_LoadRobonautLinks(benchmark::State& state) {
  const auto data = graspitData();
  if (!data) return state.SkipWithError(kNoSharedData);
  graspkit::initInventorReader();
  const std::vector<fs::path> files = robonautLinkFiles(*data);
  std::size_t triangles = 0;
  for (auto _ : state) {
    triangles = 0;
    for (const fs::path& file : files) triangles += graspkit::loadMesh(file).triangleCount();
  }
  state.counters["files"] = static_cast<double>(files.size());
  state.counters["triangles"] = static_cast<double>(triangles);
  state.counters["triangles/s"] = benchmark::Counter(static_cast<double>(triangles),
                                                     benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_LoadRobonautLinks)->Unit(benchmark::kMillisecond);

void BM_MassPropertiesRobonautLinks(benchmark::State& state) {
  const auto data = graspitData();
  if (!data) return state.SkipWithError(kNoSharedData);
  std::vector<graspkit::TriangleMesh> meshes;
  for (const fs::path& file : robonautLinkFiles(*data)) meshes.push_back(graspkit::loadMesh(file));
  for (auto _ : state) {
    for (const graspkit::TriangleMesh& mesh : meshes) {
      benchmark::DoNotOptimize(graspkit::computeMassProperties(mesh));
      benchmark::DoNotOptimize(graspkit::surfaceCentroid(mesh));
    }
  }
}
BENCHMARK(BM_MassPropertiesRobonautLinks)->Unit(benchmark::kMicrosecond);

// A height-field grid as OFF text: (n+1)^2 vertices and n^2 quads, i.e. 2 n^2 triangles.
std::string gridOff(int n) {
  std::string text =
      "OFF\n" + std::to_string((n + 1) * (n + 1)) + " " + std::to_string(n * n) + " 0\n";
  char line[96];
  for (int i = 0; i <= n; ++i) {
    for (int j = 0; j <= n; ++j) {
      std::snprintf(line, sizeof line, "%d %d %.6f\n", i, j, 0.01 * ((i * j) % 97));
      text += line;
    }
  }
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const int a = i * (n + 1) + j;
      std::snprintf(line, sizeof line, "4 %d %d %d %d\n", a, a + 1, a + n + 2, a + n + 1);
      text += line;
    }
  }
  return text;
}

void BM_ParseOffGrid(benchmark::State& state) {
  const std::string text = gridOff(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    benchmark::DoNotOptimize(graspkit::parseOff(text, "grid.off").triangles.data());
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * text.size()));
  state.counters["triangles"] = 2.0 * static_cast<double>(state.range(0) * state.range(0));
}
BENCHMARK(BM_ParseOffGrid)->Arg(150)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
