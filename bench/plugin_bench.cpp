// Plugin load time. Three costs:
//   ColdLoad          a plugin file never mapped before (a fresh copy each iteration):
//                     dlopen with relocation, descriptor checks, registration;
//   LoadIntoRegistry  an already-mapped plugin into a fresh Registry (what a second Registry
//                     or a host that makes one per job pays);
//   OnDemandLookup    a fresh Registry resolving robot type "Shadow" from the default search
//                     path (scans the folder in order until a plugin provides it).
// Baseline in the same run: reading the project's own bh8 robot file, the work a type lookup
// sits beside when a robot is loaded.

#include <benchmark/benchmark.h>

#include <filesystem>

#include "graspkit/io/graspit/robot_file.hpp"
#include "graspkit/plugin/registry.hpp"

namespace fs = std::filesystem;
using namespace graspkit;

namespace {

const fs::path kPlugins = GRASPKIT_PLUGIN_DIR;

void ColdLoad(benchmark::State& state) {
  const fs::path dir = fs::temp_directory_path() / "graspkit_plugin_bench";
  fs::create_directories(dir);
  int serial = 0;
  for (auto _ : state) {
    state.PauseTiming();
    const fs::path copy = dir / ("robonaut_" + std::to_string(serial++) + ".so");
    fs::copy_file(kPlugins / "robonaut.so", copy, fs::copy_options::overwrite_existing);
    Registry registry;
    state.ResumeTiming();
    // A distinct file is a distinct mapping; only the plugin name clash is avoided by using
    // a fresh registry.
    benchmark::DoNotOptimize(registry.plugins().load(copy));
  }
  fs::remove_all(dir);  // the mappings stay until exit; the files can go
}
BENCHMARK(ColdLoad)->Unit(benchmark::kMicrosecond)->Iterations(200);

void LoadIntoRegistry(benchmark::State& state) {
  for (auto _ : state) {
    Registry registry;
    benchmark::DoNotOptimize(registry.plugins().load(kPlugins / "robonaut.so"));
  }
}
BENCHMARK(LoadIntoRegistry)->Unit(benchmark::kMicrosecond);

void OnDemandLookup(benchmark::State& state) {
  for (auto _ : state) {
    Registry registry;
    benchmark::DoNotOptimize(registry.robotType("Shadow"));
  }
}
BENCHMARK(OnDemandLookup)->Unit(benchmark::kMicrosecond);

void EmptyRegistry(benchmark::State& state) {
  for (auto _ : state) {
    Registry registry;
    benchmark::DoNotOptimize(&registry);
  }
}
BENCHMARK(EmptyRegistry)->Unit(benchmark::kMicrosecond);

void BaselineReadRobotFile(benchmark::State& state) {
  const fs::path file = fs::path(GRASPKIT_SOURCE_DIR) / "models/robots/bh8/bh8.xml";
  for (auto _ : state) benchmark::DoNotOptimize(loadRobotFile(file));
}
BENCHMARK(BaselineReadRobotFile)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
