// Load times of the shared GraspIt! files: worlds/plannerMug.xml and every robot of the corpus.
// Each iteration reads everything from disk (a fresh ModelCache). The counter
// `x_graspit` is GraspIt!'s own load time (../shared/reference) divided by ours.

#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "graspkit/base/log.hpp"
#include "graspkit/io/graspit/robot_file.hpp"
#include "graspkit/io/graspit/world_file.hpp"

namespace fs = std::filesystem;
using namespace graspkit;

namespace {

fs::path sharedDir() {
  if (const char* env = std::getenv("GRASPKIT_SHARED"); env && *env) return env;
  return GRASPKIT_SHARED_DEFAULT;
}

std::size_t meshBytes(const TriangleMesh& mesh) {
  return mesh.vertices.size() * sizeof(Vector3) + mesh.triangles.size() * sizeof(mesh.triangles[0]);
}

std::size_t robotBytes(const RobotModel& robot) {
  std::size_t bytes = meshBytes(*robot.palm->mesh);
  for (const auto& chain : robot.chains)
    for (const auto& link : chain.links) bytes += meshBytes(*link.body->mesh);
  return bytes;
}

void quiet() {
  setWarningHandler([](const Warning&) {});
}

void BM_LoadWorld(benchmark::State& state, std::string file, double graspit_seconds) {
  quiet();
  const fs::path data = sharedDir() / "graspit-data";
  if (!fs::exists(data / file)) return state.SkipWithError("shared GraspIt! data not found");
  std::size_t bytes = 0;
  for (auto _ : state) {
    ModelCache cache;  // nothing cached between iterations: a cold load from files
    World world = loadWorldFile(data / file, LoadOptions{{data}}, &cache);
    bytes = 0;
    for (const Body& body : world.bodies()) bytes += meshBytes(*body.model->mesh);
    for (int r = 0; r < world.robotCount(); ++r) bytes += robotBytes(world.robot(r).model());
    benchmark::DoNotOptimize(world);
  }
  state.counters["mesh_MB"] = bytes / 1e6;
  state.counters["x_graspit"] =
      benchmark::Counter(graspit_seconds * state.iterations(), benchmark::Counter::kIsRate);
}

void BM_LoadRobot(benchmark::State& state, std::string file, double graspit_seconds) {
  quiet();
  const fs::path data = sharedDir() / "graspit-data";
  std::size_t bytes = 0;
  for (auto _ : state) {
    auto robot = loadRobotFile(data / file);
    bytes = robotBytes(*robot);
    benchmark::DoNotOptimize(robot);
  }
  state.counters["mesh_MB"] = bytes / 1e6;
  state.counters["x_graspit"] =
      benchmark::Counter(graspit_seconds * state.iterations(), benchmark::Counter::kIsRate);
}

// Registers one benchmark per shared robot that GraspIt! loads, with its reference time.
bool registerAll() {
  std::ifstream in(sharedDir() / "reference" / "graspit-figures.json");
  if (!in) {
    benchmark::RegisterBenchmark("LoadWorld/plannerMug", BM_LoadWorld, "worlds/plannerMug.xml",
                                 0.0);
    return false;
  }
  const auto figures = nlohmann::json::parse(in);
  const double mug = figures["grasps"]["plannerMug_as_loaded"]["load_time_s"].get<double>();
  benchmark::RegisterBenchmark("LoadWorld/plannerMug", BM_LoadWorld, "worlds/plannerMug.xml", mug)
      ->Unit(benchmark::kMillisecond);
  for (const auto& entry : figures["robot_survey_shared"]) {
    if (!entry["load_ok"].get<bool>()) continue;
    const std::string file = entry["file"];
    benchmark::RegisterBenchmark(("LoadRobot/" + fs::path(file).stem().string()).c_str(),
                                 BM_LoadRobot, file, entry["load_time_s"].get<double>())
        ->Unit(benchmark::kMillisecond);
  }
  return true;
}

const bool registered = registerAll();

}  // namespace

BENCHMARK_MAIN();
