// graspkit.planner from Lua on GraspIt!'s plannerMug world (Barrett hand and mug, from the shared
// corpus; skipped loudly without it). Truths: a Lua energy with a closed form (the squared
// distance of the palm from a target point), the C++ planner run directly with the same request
// (the binding must hand every option through), the robot binding's own autograsp and grasp
// analysis for the finished grasps, and the error contract (a failing energy is a clean error
// naming the function, bad options are refused, the --timeout limit still stops a run).

#include <chrono>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <lua.hpp>

#include "graspkit/io/graspit/world_file.hpp"
#include "graspkit/lua/script_host.hpp"
#include "graspkit/planning/planner.hpp"
#include "graspkit/plugin/registry.hpp"
#include "test_paths.hpp"

namespace graspkit {
namespace {

namespace fs = std::filesystem;

class LuaPlanner : public ::testing::Test {
 protected:
  void SetUp() override {
    GRASPKIT_REQUIRE_SHARED();
    world_ = (*test::graspitDataDir() / "worlds" / "plannerMug.xml").string();
    folder_ = test::scratchDir();
    script_ = folder_ / "scenario.lua";
    std::ofstream(script_) << "-- empty: the tests run chunks through runString\n";
  }

  lua::ScriptHost& host(std::optional<double> timeout = std::nullopt) {
    if (!host_) {
      lua::ScriptOptions options;
      options.load.useEnvironment = false;
      options.sandbox.allowRead = {*test::sharedDir()};
      options.timeoutSeconds = timeout;
      host_ = std::make_unique<lua::ScriptHost>(script_, options);
    }
    return *host_;
  }

  // The world loaded as `world`, then `code`; fails the test if the chunk fails.
  void run(const std::string& code) {
    const lua::ScriptOutcome outcome =
        host().runString("world = graspkit.load_world('" + world_ + "')\n" + code, "check.lua");
    ASSERT_TRUE(outcome.ok) << outcome.message;
  }

  double global(const char* name) {
    lua_State* L = host().state();
    lua_getglobal(L, name);
    EXPECT_TRUE(lua_isnumber(L, -1)) << name << " is " << luaL_typename(L, -1);
    const double value = lua_tonumber(L, -1);
    lua_pop(L, 1);
    return value;
  }

  // Runs `code` (after loading the world), which must fail; returns the message.
  std::string error(const std::string& code) {
    const lua::ScriptOutcome outcome =
        host().runString("world = graspkit.load_world('" + world_ + "')\n" + code, "check.lua");
    EXPECT_FALSE(outcome.ok) << "no error from: " << code;
    return outcome.message;
  }

  std::string world_;
  fs::path folder_;
  fs::path script_;
  std::unique_ptr<lua::ScriptHost> host_;
};

// Squared distance of the palm from (30, -20, 150) mm: the planner must bring the palm nearer
// than where the world starts it, and the energy it reports for its best grasp must be that
// closed form at the grasp's pose.
const char* kPalmTarget = R"(
target = {30, -20, 150}
function palm_distance2(pose)
  local t = pose.translation
  return (t[1] - target[1])^2 + (t[2] - target[2])^2 + (t[3] - target[3])^2
end
calls, mismatch = 0, 0
function energy(state)
  calls = calls + 1
  -- the state's pose is the robot's pose in the state's world
  local a, b = state.pose.translation, state.robot:pose().translation
  mismatch = math.max(mismatch, math.abs(a[1] - b[1]), math.abs(a[2] - b[2]), math.abs(a[3] - b[3]))
  return palm_distance2(state.pose)
end
)";

TEST_F(LuaPlanner, LuaEnergyBringsThePalmToTheTarget) {
  run(std::string(kPalmTarget) + R"(
    local p = graspkit.planner("simann", {world = world, energy = energy, seed = 4, top = 5,
                                          mode = "anneal"})
    steps = p:run{steps = 1500}
    local best = p:best()
    count = #best
    best_energy = best[1].energy
    bx, by, bz = table.unpack(best[1].pose.translation)
    sx, sy, sz = table.unpack(world:robot(1):pose().translation)
    sorted = 1
    for i = 2, #best do if best[i].energy < best[i - 1].energy then sorted = 0 end end
    dof_count = #best[1].dofs
  )");
  const Vector3 target(30, -20, 150);
  const double best = (Vector3(global("bx"), global("by"), global("bz")) - target).squaredNorm();
  const double start = (Vector3(global("sx"), global("sy"), global("sz")) - target).squaredNorm();
  EXPECT_EQ(global("steps"), 1500);
  EXPECT_GT(global("count"), 0);
  EXPECT_LE(global("count"), 5);
  EXPECT_NEAR(global("best_energy"), best, 1e-6 * (1 + best));
  EXPECT_LT(best, 0.25 * start) << "best " << best << " mm^2, start " << start << " mm^2";
  EXPECT_EQ(global("sorted"), 1);
  EXPECT_EQ(global("dof_count"), 4);  // the Barrett hand
  EXPECT_GT(global("calls"), 100);
  EXPECT_LT(global("mismatch"), 1e-9);
}

TEST_F(LuaPlanner, FixedSeedGivesTheSameListTwiceAndAnotherSeedDoesNot) {
  run(std::string(kPalmTarget) + R"(
    local function plan(seed)
      local p = graspkit.planner("simann", {world = world, energy = energy, seed = seed,
                                            mode = "anneal"})
      p:step(400)
      p:step(400)  -- chunking must not matter
      return p:best()
    end
    local function same(a, b)
      if #a ~= #b then return 0 end
      for i = 1, #a do
        if a[i].energy ~= b[i].energy then return 0 end
        for k = 1, 3 do
          if a[i].pose.translation[k] ~= b[i].pose.translation[k] then return 0 end
        end
        for k = 1, #a[i].dofs do if a[i].dofs[k] ~= b[i].dofs[k] then return 0 end end
      end
      return 1
    end
    local a, b, c = plan(9), plan(9), plan(10)
    repeated, different, length = same(a, b), 1 - same(a, c), #a
  )");
  EXPECT_GT(global("length"), 0);
  EXPECT_EQ(global("repeated"), 1);
  EXPECT_EQ(global("different"), 1);
}

// The binding against the C++ planner given the same request by hand.
TEST_F(LuaPlanner, RegisteredEnergyMatchesTheCppPlanner) {
  run(R"(
    local p = graspkit.planner("simann", {world = world, energy = "CONTACT_ENERGY", seed = 11,
                                          top = 6, robot = "Barrett", object = "mug",
                                          mode = "anneal", threads = 1,
                                          set = {threshold = 0.2}})
    p:run{steps = 1200}
    energies = {}
    for i, g in ipairs(p:best()) do energies[i] = g.energy end
    count = #energies
  )");
  PlanningRequest request;
  request.world = std::make_shared<const World>(loadWorldFile(world_));
  request.robot = 0;
  request.object = BodyRef::body(0);
  request.energy = "contact";
  request.seed = 11;
  request.bestListSize = 6;
  request.options = {{"mode", "anneal"}, {"threshold", "0.2"}};
  auto planner = Registry::global().makePlanner("simann", request);
  const PlanningRun direct = runPlanner(*planner, PlanningBudget{.steps = 1200});
  ASSERT_FALSE(direct.grasps.empty());
  ASSERT_EQ(global("count"), static_cast<double>(direct.grasps.size()));
  lua_State* L = host().state();
  lua_getglobal(L, "energies");
  for (std::size_t i = 0; i < direct.grasps.size(); ++i) {
    lua_rawgeti(L, -1, static_cast<lua_Integer>(i + 1));
    EXPECT_EQ(lua_tonumber(L, -1), direct.grasps[i].energy) << "grasp " << i + 1;
    lua_pop(L, 1);
  }
  lua_pop(L, 1);
}

// Each finished grasp, closed again through the robot binding (autograsp, then the L1 grasp
// analysis), gives the same closed DOFs, epsilon, volume, contact count and force closure.
TEST_F(LuaPlanner, FinishedGraspsMatchTheRobotBindingsAutograsp) {
  run(R"(
    local p = graspkit.planner("simann", {world = world, seed = 2, top = 3, mode = "anneal"})
    p:run{steps = 800}
    local grasps = p:best{autograsp = true}
    count, worst_dof, worst_quality, mismatches = #grasps, 0, 0, 0
    for _, g in ipairs(grasps) do
      local copy = world:clone()
      local hand = copy:robot(1)
      hand:set_pose(g.pose)
      hand:set_dofs(g.dofs)
      hand:autograsp()
      local closed = hand:dofs()
      for k = 1, #closed do worst_dof = math.max(worst_dof, math.abs(closed[k] - g.closed_dofs[k])) end
      local grasp = hand:grasp("mug")
      worst_quality = math.max(worst_quality, math.abs(grasp:epsilon() - g.epsilon),
                               math.abs(grasp:volume() - g.volume))
      if grasp:contact_count() ~= g.contacts or grasp:force_closure() ~= g.force_closure then
        mismatches = mismatches + 1
      end
    end
    local plain = p:best()[1]
    plain_has_epsilon = plain.epsilon == nil and 0 or 1
  )");
  EXPECT_GT(global("count"), 0);
  EXPECT_LT(global("worst_dof"), 1e-9);
  EXPECT_LT(global("worst_quality"), 1e-9);
  EXPECT_EQ(global("mismatches"), 0);
  EXPECT_EQ(global("plain_has_epsilon"), 0);  // only asked-for grasps are closed
}

TEST_F(LuaPlanner, StatesOptionSetsTheStart) {
  // The hand where the world has it is the planner's default start: giving it as a state must
  // not change the search; a state moved by 40 mm must.
  run(R"(
    local hand = world:robot(1)
    local here = {pose = hand:pose(), dofs = hand:dofs()}
    local t = hand:pose().translation
    local moved = {pose = graspkit.pose({t[1] + 40, t[2], t[3]}, hand:pose().quaternion),
                   dofs = hand:dofs()}
    local function first(states)
      local p = graspkit.planner("simann", {world = world, seed = 5, states = states,
                                            mode = "anneal"})
      p:step(300)
      return p:best()[1].energy
    end
    local default = first(nil)
    -- the pose goes through a quaternion and back: equal to rounding
    same_start = math.abs(first({here}) - default) <= 1e-9 * math.max(1, math.abs(default)) and 1 or 0
    other_start = first({moved}) ~= default and 1 or 0
  )");
  EXPECT_EQ(global("same_start"), 1);
  EXPECT_EQ(global("other_start"), 1);
}

TEST_F(LuaPlanner, EnergyErrorsAreCleanAndNameTheFunction) {
  const std::string raised = error(R"(
    local p = graspkit.planner("simann", {world = world, energy = function(state)
      error("no good")
    end})
    p:step(10)
  )");
  EXPECT_NE(raised.find("energy function (check.lua:3) failed"), std::string::npos) << raised;
  EXPECT_NE(raised.find("check.lua:4: no good"), std::string::npos) << raised;
  EXPECT_NE(raised.find("check.lua:6:"), std::string::npos) << raised;  // where :step was called

  const std::string text = error(R"(
    local p = graspkit.planner("simann", {world = world, energy = function() return "low" end})
    p:run{steps = 10}
  )");
  EXPECT_NE(text.find("energy function (check.lua:3) returned string, not a number"),
            std::string::npos)
      << text;

  const std::string nan = error(R"(
    local p = graspkit.planner("simann", {world = world, energy = function() return 0 / 0 end})
    p:step(5)
  )");
  EXPECT_NE(nan.find("energy function (check.lua:3) returned NaN"), std::string::npos) << nan;

  // The state survives: a caught energy error leaves a usable planner and Lua state.
  run(R"(
    local fail = true
    local p = graspkit.planner("simann", {world = world, seed = 1, energy = function(s)
      if fail then error("once") end
      return s.pose.translation[3]
    end})
    ok1 = pcall(p.step, p, 3) and 1 or 0
    fail = false
    p:step(50)
    after = #p:best()
  )");
  EXPECT_EQ(global("ok1"), 0);
  EXPECT_GT(global("after"), 0);
}

TEST_F(LuaPlanner, BadOptionsAreRefused) {
  EXPECT_NE(error("graspkit.planner('simann', {world = world, thread = 2})")
                .find("unknown option 'thread'"),
            std::string::npos);
  EXPECT_NE(error("graspkit.planner('simann', {seed = 2})").find("option 'world'"),
            std::string::npos);
  const std::string threads = error(
      "graspkit.planner('simann', {world = world, threads = 2, energy = function() return 0 "
      "end})");
  EXPECT_NE(threads.find("a Lua energy runs on one thread"), std::string::npos) << threads;
  EXPECT_NE(error("graspkit.planner('simann', {world = world, energy = 'warmth'})").find("warmth"),
            std::string::npos);
  EXPECT_NE(error("graspkit.planner('simann', {world = world, robot = 2})").find("option 'robot'"),
            std::string::npos);
  EXPECT_NE(error("graspkit.planner('simann', {world = world, object = 'cup'})").find("'cup'"),
            std::string::npos);
  EXPECT_NE(
      error("graspkit.planner('simann', {world = world, set = {colour = 'red'}})").find("colour"),
      std::string::npos);
  const std::string states = error(
      "graspkit.planner('simann', {world = world, states = {{pose = graspkit.pose(), "
      "dofs = {1, 2}, speed = 3}}})");
  EXPECT_NE(states.find("option 'states'[1]: unknown option 'speed'"), std::string::npos) << states;
  EXPECT_NE(error("graspkit.planner('simann', {world = world}):run{steps = 5, seconds = 1}")
                .find("either steps or seconds"),
            std::string::npos);
}

TEST_F(LuaPlanner, TimeLimitStopsALongRun) {
  host(0.5);
  const auto start = std::chrono::steady_clock::now();
  const lua::ScriptOutcome outcome =
      host().runString("local w = graspkit.load_world('" + world_ +
                           "')\n"
                           "local p = graspkit.planner('simann', {world = w})\n"
                           "pcall(p.run, p, {seconds = 60})\n",  // catching the error must not help
                       "check.lua");
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_FALSE(outcome.ok);
  EXPECT_TRUE(outcome.timedOut);
  EXPECT_NE(outcome.message.find("--timeout 0.5"), std::string::npos) << outcome.message;
  EXPECT_LT(seconds, 5.0);
}

// With no 'robot' option the hand is the world's first robot that is a hand, as GraspIt! picks
// its current hand: in barrettGlassDyn the Puma arm comes first and the Barrett is planned.
TEST_F(LuaPlanner, DefaultRobotIsTheFirstHand) {
  const std::string glass = (*test::graspitDataDir() / "worlds" / "barrettGlassDyn.xml").string();
  const lua::ScriptOutcome outcome = host().runString(
      "local w = graspkit.load_world('" + glass +
          "')\n"
          "assert(w:robot(1):name() == 'Puma560', w:robot(1):name())\n"
          "local seen\n"
          "local q = graspkit.planner('simann', {world = w, energy = function(state)\n"
          "  seen = state.robot:name(); return 0 end})\n"
          "q:step(1)\n"
          "assert(seen == 'Barrett', tostring(seen))\n",
      "hand.lua");
  EXPECT_TRUE(outcome.ok) << outcome.message;
}

}  // namespace
}  // namespace graspkit
