// How far statics can stand in for simulation in grasp validation, and what it saves.
//
// Plans grasps with a hand on generated objects (graspkit objects), as graspkit batch does,
// then validates each grasp twice in the same process: every direction simulated (the
// reference), and with ValidationRequest::statics (a direction statics shows held is not
// simulated). Prints the agreement of the labels, grasp by grasp and direction by direction, and
// the CPU time of each way with their ratio.
//
//   validation_statics_bench HAND OBJECTS_FOLDER [GRASPS_PER_OBJECT] [STEPS] [THREADS]
//
// OBJECTS_FOLDER holds the objects.txt that graspkit objects writes. Environment:
//   S_CONFIGS="load,disturbance,share,least;..."  margins to compare (default: the defaults)
//   S_LABELS_ONLY=1  agreement only, without the timed dataset-mode runs
//   S_VERBOSE=1      each grasp's CPU time, settle and per-direction seconds and failures

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <sstream>
#include <string>
#include <vector>

#include "graspkit/base/parallel_for.hpp"
#include "graspkit/dataset/dataset_planning.hpp"
#include "graspkit/dynamics/grasp_validation.hpp"
#include "graspkit/dynamics/static_hold.hpp"

namespace {

using namespace graspkit;

std::vector<std::filesystem::path> objectFiles(const std::filesystem::path& folder) {
  std::vector<std::filesystem::path> files;
  std::ifstream list(folder / "objects.txt");
  for (std::string line; std::getline(list, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream words(line);
    std::string name;
    words >> name;
    files.push_back(folder / name);
  }
  return files;
}

double cpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

struct Tally {
  int grasps = 0, heldFull = 0, heldStatics = 0, labelsAgree = 0;
  int graspsAllByStatics = 0;
  int directionsByStatics = 0, directionsByStaticsHeldInFull = 0;
  double fullSeconds = 0.0, staticsSeconds = 0.0;  // validations as datasets run them

  void add(const Tally& other) {
    grasps += other.grasps;
    heldFull += other.heldFull;
    heldStatics += other.heldStatics;
    labelsAgree += other.labelsAgree;
    graspsAllByStatics += other.graspsAllByStatics;
    directionsByStatics += other.directionsByStatics;
    directionsByStaticsHeldInFull += other.directionsByStaticsHeldInFull;
    fullSeconds += other.fullSeconds;
    staticsSeconds += other.staticsSeconds;
  }
  void print(const char* name) const {
    std::printf(
        "%-28s grasps %4d held %4d/%4d agree %4d (%.2f %%)  directions by statics %4d "
        "(held when simulated %4d)  all 6 %4d  CPU %.2f s -> %.2f s (%.2fx)\n",
        name, grasps, heldFull, heldStatics, labelsAgree, 100.0 * labelsAgree / std::max(1, grasps),
        directionsByStatics, directionsByStaticsHeldInFull, graspsAllByStatics, fullSeconds,
        staticsSeconds, fullSeconds / std::max(1e-9, staticsSeconds));
  }
};

// Margins to try, from S_CONFIGS="load,disturbance,share,least;..." (default: the defaults).
std::vector<StaticHoldMargins> marginsToTry() {
  std::vector<StaticHoldMargins> all;
  const char* text = std::getenv("S_CONFIGS");
  if (!text) return {StaticHoldMargins{}};
  std::istringstream configs(text);
  for (std::string config; std::getline(configs, config, ';');) {
    StaticHoldMargins m;
    char comma;
    std::istringstream(config) >> m.loadFactor >> comma >> m.disturbance >> comma >>
        m.frictionShare >> comma >> m.leastShare;
    all.push_back(m);
  }
  return all;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: %s HAND OBJECTS_FOLDER [GRASPS] [STEPS] [THREADS]\n", argv[0]);
    return 2;
  }
  const std::filesystem::path hand = argv[1];
  const int grasps = argc > 3 ? std::stoi(argv[3]) : 10;
  const std::int64_t steps = argc > 4 ? std::stoll(argv[4]) : 40000;
  const int threads = argc > 5 ? std::stoi(argv[5]) : 1;
  const std::vector<StaticHoldMargins> margins = marginsToTry();
  std::vector<Tally> tallies(margins.size());
  std::mutex lock;
  for (const std::filesystem::path& object : objectFiles(argv[2])) {
    DatasetRequest request{.hand = hand, .object = object, .grasps = grasps, .steps = steps};
    const GraspDataset dataset = planGraspDataset(request);
    std::vector<World> worlds;
    for (const DatasetGrasp& grasp : dataset.grasps)
      worlds.push_back(datasetGraspWorld(request, grasp));
    std::vector<Tally> here(margins.size());
    parallelFor({.end = static_cast<std::int64_t>(worlds.size()), .threads = threads},
                [&](int, std::int64_t i) {
                  const ValidationRequest full;  // every direction simulated: the reference
                  const double reference_start = cpuSeconds();
                  const ValidationResult reference = validateGrasp(worlds[i], 0, 0, full);
                  if (std::getenv("S_VERBOSE")) {
                    std::string line = "grasp " + std::to_string(i) + " cpu " +
                                       std::to_string(cpuSeconds() - reference_start) + " settle " +
                                       std::to_string(reference.settleSeconds) + " held " +
                                       std::to_string(reference.held) + " seconds";
                    for (const DirectionResult& d : reference.directions)
                      line += " " + std::to_string(d.seconds) + (d.held ? "+" : "-") + d.failure;
                    std::printf("%s\n", line.c_str());
                  }
                  // As datasets validate: stop at the first direction let go, timed both ways (with
                  // the first margins). S_LABELS_ONLY: the labels alone, no timed runs.
                  const bool timed = std::getenv("S_LABELS_ONLY") == nullptr;
                  ValidationRequest dataset_full = full;
                  dataset_full.allDirections = false;
                  double start = cpuSeconds();
                  const ValidationResult timed_full =
                      timed ? validateGrasp(worlds[i], 0, 0, dataset_full) : reference;
                  const double full_seconds = cpuSeconds() - start;
                  for (std::size_t m = 0; m < margins.size(); ++m) {
                    ValidationRequest statics = full;
                    statics.statics = true;
                    statics.staticsMargins = margins[m];
                    const ValidationResult shortcut = validateGrasp(worlds[i], 0, 0, statics);
                    ValidationResult timed_statics = shortcut;
                    double statics_seconds = 0.0;
                    if (m == 0 && timed) {
                      ValidationRequest dataset_statics = statics;
                      dataset_statics.allDirections = false;
                      start = cpuSeconds();
                      timed_statics = validateGrasp(worlds[i], 0, 0, dataset_statics);
                      statics_seconds = cpuSeconds() - start;
                    }
                    std::lock_guard guard(lock);
                    Tally& t = here[m];
                    ++t.grasps;
                    t.heldFull += reference.held;
                    t.heldStatics += shortcut.held;
                    t.labelsAgree += reference.held == shortcut.held &&
                                     timed_full.held == reference.held &&
                                     timed_statics.held == shortcut.held;
                    int by_statics = 0;
                    for (int k = 0; k < 6; ++k) {
                      if (!shortcut.directions[k].byStatics) continue;
                      ++by_statics;
                      ++t.directionsByStatics;
                      if (reference.directions[k].held) {
                        ++t.directionsByStaticsHeldInFull;
                      } else {
                        std::printf(
                            "  disagreement (margins %zu): %s grasp %lld direction %d: simulated "
                            "slip %.3f mm turn %.4f rad %s\n",
                            m, object.filename().c_str(), static_cast<long long>(i), k,
                            reference.directions[k].slip, reference.directions[k].turn,
                            reference.directions[k].failure.c_str());
                      }
                    }
                    t.graspsAllByStatics += by_statics == 6;
                    if (m == 0) {
                      t.fullSeconds += full_seconds;
                      t.staticsSeconds += statics_seconds;
                    }
                  }
                });
    for (std::size_t m = 0; m < margins.size(); ++m) {
      here[m].print((object.filename().string() + " #" + std::to_string(m)).c_str());
      tallies[m].add(here[m]);
    }
    std::fflush(stdout);
  }
  std::printf("\n");
  for (std::size_t m = 0; m < margins.size(); ++m) {
    std::printf("margins #%zu: load %.2f disturbance %.2f friction share %.2f least share %.3f\n",
                m, margins[m].loadFactor, margins[m].disturbance, margins[m].frictionShare,
                margins[m].leastShare);
    tallies[m].print("TOTAL");
  }
  return 0;
}
