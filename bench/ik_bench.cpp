// Inverse kinematics solves per second: the Puma560 closed form (8 candidates, selection), and
// the generic iterative solver on the Puma560 and on a Barrett finger (chain 0, 2 DOFs). Each
// solve starts from a configuration 0.05 rad (per DOF) from the pose's own, so the iterative
// solver runs its usual 3 to 5 Newton steps. Counters: `solves_per_s` (a rate) and
// `iterations` (mean Newton steps per solve; 0 for the closed form), `failure_rate`. The
// iterative Puma560 rejects 2 of the 64 problems by GraspIt!'s 0.2 rad rule: one near the wrist
// singularity (theta5 = -0.05, the start crosses it and Newton lands on the flipped wrist), one
// where Newton swings joint 1 by 0.35 rad. Rejected solves still count in solves_per_s.

#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>
#include <random>
#include <vector>

#include "graspkit/base/log.hpp"
#include "graspkit/grasp/robot_type.hpp"
#include "graspkit/io/graspit/robot_file.hpp"
#include "graspkit/model/inverse_kinematics.hpp"
#include "graspkit/model/robot.hpp"

namespace fs = std::filesystem;
using namespace graspkit;

namespace {

fs::path robotsDir() {
  const char* env = std::getenv("GRASPKIT_SHARED");
  return fs::path(env && *env ? env : GRASPKIT_SHARED_DEFAULT) / "graspit-data/models/robots";
}

// One solve's input: the start configuration and the target it should reach.
struct Problem {
  std::vector<double> start;
  Transform target;
};

// 64 problems: random DOFs inside the ranges (0.2 rad margin), target = FK, start 0.05 rad off.
std::vector<Problem> problems(Robot& robot, int chain) {
  std::mt19937 rng(42);
  std::vector<Problem> all;
  for (int i = 0; i < 64; ++i) {
    std::vector<double> truth, start;
    for (const Dof& dof : robot.model().dofs) {
      truth.push_back(std::uniform_real_distribution<double>(dof.min + 0.2, dof.max - 0.2)(rng));
      start.push_back(truth.back() + (i % 2 ? 0.05 : -0.05));
    }
    robot.setDofValues(truth);
    all.push_back({start, robot.chainEndPose(chain)});
  }
  return all;
}

template <class Solver>
void runSolves(benchmark::State& state, const std::string& file, int chain, Solver solve) {
  setWarningHandler([](const Warning&) {});
  if (!fs::exists(robotsDir() / file)) return state.SkipWithError("shared GraspIt! data not found");
  Robot robot(loadRobotFile(robotsDir() / file));
  const std::vector<Problem> all = problems(robot, chain);
  std::vector<Robot> starts;  // posed once, so the loop times the solve alone
  for (const Problem& problem : all) {
    starts.push_back(robot);
    starts.back().setDofValues(problem.start);
  }
  std::size_t i = 0;
  long iterations = 0, failures = 0;
  for (auto _ : state) {
    const IkResult result = solve(starts[i], all[i].target, IkRequest{.chain = chain});
    iterations += result.iterations;
    failures += result.success ? 0 : 1;
    benchmark::DoNotOptimize(result);
    i = (i + 1) % all.size();
  }
  state.counters["solves_per_s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["iterations"] = static_cast<double>(iterations) / state.iterations();
  state.counters["failure_rate"] = static_cast<double>(failures) / state.iterations();
}

void BM_Puma560ClosedForm(benchmark::State& state) {
  runSolves(state, "Puma560/Puma560.xml", 0,
            [](const Robot& r, const Transform& t, const IkRequest& q) {
              return inverseKinematics(r, t, q);
            });
}

void BM_Puma560Iterative(benchmark::State& state) {
  runSolves(state, "Puma560/Puma560.xml", 0,
            [](const Robot& r, const Transform& t, const IkRequest& q) {
              return iterativeInverseKinematics(r, t, q);
            });
}

void BM_BarrettFingerIterative(benchmark::State& state) {
  runSolves(state, "Barrett/Barrett.xml", 0,
            [](const Robot& r, const Transform& t, const IkRequest& q) {
              return iterativeInverseKinematics(r, t, q);
            });
}

}  // namespace

BENCHMARK(BM_Puma560ClosedForm);
BENCHMARK(BM_Puma560Iterative);
BENCHMARK(BM_BarrettFingerIterative);

BENCHMARK_MAIN();
