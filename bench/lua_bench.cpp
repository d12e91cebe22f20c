// What the Lua layer costs over calling the engine from C++, on the project's default world
// (bh8 over a mug). Each pair does the same engine work; the Lua one goes through the graspkit
// module (argument checks, tables in and out, userdata). Compare the pairs' times:
//   SetDofsLinkPoses: set 4 DOFs and read the 3 x 3 link poses (kinematics only: the binding's
//                     overhead is most visible here);
//   Autograsp:        reset the DOFs, close the hand, build the grasp and its epsilon (engine
//                     work dominates: the binding should be lost in the noise).

#include <benchmark/benchmark.h>

#include <filesystem>
#include <fstream>

#include "graspkit/grasp/autograsp.hpp"
#include "graspkit/grasp/grasp.hpp"
#include "graspkit/io/graspit/world_file.hpp"
#include "graspkit/lua/script_host.hpp"
#include "graspkit/model/world.hpp"

#include <lua.hpp>

namespace fs = std::filesystem;
using namespace graspkit;

namespace {

const fs::path kModels = fs::path(GRASPKIT_SOURCE_DIR) / "models";

// A host whose script defines the Lua side of each pair as a global function.
std::unique_ptr<lua::ScriptHost> makeHost() {
  const fs::path script = fs::temp_directory_path() / "graspkit_lua_bench.lua";
  std::ofstream(script) << R"(
    world = graspkit.load_world('worlds/default.xml')
    hand = world:robot(1)
    mug = world:body('mug')
    start = hand:dofs()
    function set_dofs_link_poses(t)
      hand:set_dofs({0.1, t, t, t})
      return hand:link_poses()
    end
    function autograsp()
      hand:set_dofs(start)
      hand:autograsp()
      return hand:grasp(mug):epsilon()
    end
  )";
  lua::ScriptOptions options;
  options.load.roots = {kModels};
  auto host = std::make_unique<lua::ScriptHost>(script, options);
  if (!host->run().ok) throw std::runtime_error("bench script failed");
  return host;
}

void callLua(lua::ScriptHost& host, const char* function, double argument) {
  lua_State* L = host.state();
  lua_getglobal(L, function);
  lua_pushnumber(L, argument);
  if (!host.protectedCall(1, 1).ok) throw std::runtime_error(function);
  lua_pop(L, 1);
}

void BM_LuaSetDofsLinkPoses(benchmark::State& state) {
  auto host = makeHost();
  double t = 0.0;
  for (auto _ : state) {
    callLua(*host, "set_dofs_link_poses", t);
    t = t > 1.0 ? 0.0 : t + 0.01;
  }
}
BENCHMARK(BM_LuaSetDofsLinkPoses);

void BM_CppSetDofsLinkPoses(benchmark::State& state) {
  World world = loadWorldFile(kModels / "worlds" / "default.xml", LoadOptions{.roots = {kModels}});
  double t = 0.0;
  for (auto _ : state) {
    const double dofs[4] = {0.1, t, t, t};
    world.setDofValues(0, dofs);
    benchmark::DoNotOptimize(world.robot(0).linkPoses());
    t = t > 1.0 ? 0.0 : t + 0.01;
  }
}
BENCHMARK(BM_CppSetDofsLinkPoses);

void BM_LuaAutograsp(benchmark::State& state) {
  auto host = makeHost();
  for (auto _ : state) callLua(*host, "autograsp", 0.0);
}
BENCHMARK(BM_LuaAutograsp)->Unit(benchmark::kMillisecond);

void BM_CppAutograsp(benchmark::State& state) {
  World world = loadWorldFile(kModels / "worlds" / "default.xml", LoadOptions{.roots = {kModels}});
  const std::vector<double> start(world.robot(0).dofValues().begin(),
                                  world.robot(0).dofValues().end());
  const BodyRef mug = BodyRef::body(1);
  for (auto _ : state) {
    world.setDofValues(0, start);
    autoGrasp(world, 0);
    benchmark::DoNotOptimize(analyzeGrasp(world, 0, mug).epsilon);
  }
}
BENCHMARK(BM_CppAutograsp)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
