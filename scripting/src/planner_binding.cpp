// graspkit.planner and the Planner class: a registered grasp planner run on a clone of a
// script's world, with a registered search energy or one written in Lua.
//
// A Lua energy is called from deep inside the planner's C++ frames, so a Lua error must never
// longjmp out of it: the function runs under lua_pcall, through a trampoline that keeps no C++
// object alive, and a failure becomes a graspkit::Error thrown by the energy, which unwinds the
// planner normally before guarded<> raises it in the script.

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <memory>

#include "bound_objects.hpp"
#include "graspkit/base/error.hpp"
#include "graspkit/host/plan_task.hpp"
#include "graspkit/host/subject.hpp"
#include "graspkit/planning/planner.hpp"
#include "graspkit/planning/planning_scene.hpp"
#include "graspkit/plugin/registry.hpp"
#include "lua_api.hpp"
#include "module.hpp"
#include "script_context.hpp"
#include "time_limit.hpp"

namespace graspkit::lua {
namespace {

constexpr const char* kPlannerClass = "graspkit.Planner";
using Clock = std::chrono::steady_clock;

// What a Lua energy needs to reach its function: the registry references, the world the script
// sees the hand in, and the Lua thread calling into the planner right now.
struct LuaEnergyLink {
  lua_State* caller = nullptr;  // set for the length of each call into the planner
  int function = LUA_NOREF;
  int context = LUA_NOREF;  // {world = World, robot = Robot, object = Body} of `view`
  WorldHandle view;         // a clone of the planning world; the hand is copied in per call
  int robot = 0;
  std::string name;  // "energy function (file:line)"
};

// The arguments of one call, read by the trampoline (plain data: it may be unwound by longjmp).
struct EnergyCall {
  int function;
  int context;
  const Transform* pose;
  const double* dofs;
  std::size_t dofCount;
};

// Runs under lua_pcall: builds the state table and calls the script's function. No C++ object
// with a destructor lives here, since any Lua call may raise.
int callEnergyFunction(lua_State* L) {
  const auto* call = static_cast<const EnergyCall*>(lua_touserdata(L, 1));
  lua_rawgeti(L, LUA_REGISTRYINDEX, call->function);
  lua_createtable(L, 0, 5);
  lua_rawgeti(L, LUA_REGISTRYINDEX, call->context);
  for (const char* key : {"world", "robot", "object"}) {
    lua_getfield(L, -1, key);
    lua_setfield(L, -3, key);
  }
  lua_pop(L, 1);
  pushPose(L, *call->pose);
  lua_setfield(L, -2, "pose");
  pushNumberList(L, {call->dofs, call->dofCount});
  lua_setfield(L, -2, "dofs");
  lua_call(L, 1, 1);
  return 1;
}

class LuaSearchEnergy final : public SearchEnergy {
 public:
  explicit LuaSearchEnergy(std::shared_ptr<LuaEnergyLink> link) : link_(std::move(link)) {}

  double evaluate(PlanningScene& scene) override {
    LuaEnergyLink& link = *link_;
    lua_State* L = link.caller;
    if (L == nullptr) throw Error(link.name + " called outside a planner call");
    World& view = link.view->world;
    view.setRobotPose(link.robot, scene.hand().pose());
    view.setDofValues(link.robot, scene.hand().dofValues(), LimitPolicy::Ignore);
    const auto& dofs = scene.hand().dofValues();
    const EnergyCall call{link.function, link.context, &view.robot(link.robot).pose(), dofs.data(),
                          dofs.size()};
    if (!lua_checkstack(L, 4)) throw Error(link.name + ": Lua stack overflow");
    lua_pushcfunction(L, callEnergyFunction);
    lua_pushlightuserdata(L, const_cast<EnergyCall*>(&call));
    const int status = lua_pcall(L, 1, 1, 0);
    const int type = lua_type(L, -1);
    const std::string text = type == LUA_TSTRING ? lua_tostring(L, -1) : "";
    const double value = lua_tonumber(L, -1);
    lua_pop(L, 1);
    if (status != LUA_OK)
      throw Error(fmt::format("{} failed: {}", link.name,
                              type == LUA_TSTRING ? text : "(error object is not a string)"));
    if (type != LUA_TNUMBER)
      throw Error(fmt::format("{} returned {}, not a number", link.name, lua_typename(L, type)));
    // An infinite energy would win (or lose) every comparison and poison averages: refused as
    // NaN is, naming the function's file and line.
    if (!std::isfinite(value))
      throw Error(fmt::format("{} returned {}", link.name,
                              std::isnan(value) ? "NaN" : (value > 0 ? "inf" : "-inf")));
    return value;
  }

 private:
  std::shared_ptr<LuaEnergyLink> link_;
};

struct BoundPlanner {
  std::string name;
  PlanningRequest request;
  std::shared_ptr<LuaEnergyLink> luaEnergy;  // null with a registered energy
  std::unique_ptr<Planner> planner;
  bool busy = false;
};

// For the length of a call into the planner: refuses re-entry (an energy calling its own
// planner) and tells a Lua energy which thread to call on.
class PlannerCall {
 public:
  PlannerCall(lua_State* L, BoundPlanner& bound) : bound_(bound) {
    if (bound.busy) throw Error("the planner is busy (called from its own energy function?)");
    bound.busy = true;
    if (bound.luaEnergy) bound.luaEnergy->caller = L;
  }
  ~PlannerCall() {
    bound_.busy = false;
    if (bound_.luaEnergy) bound_.luaEnergy->caller = nullptr;
  }
  PlannerCall(const PlannerCall&) = delete;
  PlannerCall& operator=(const PlannerCall&) = delete;

 private:
  BoundPlanner& bound_;
};

BoundPlanner& toPlanner(lua_State* L, int arg) {
  BoundPlanner& bound = toObject<BoundPlanner>(L, arg, kPlannerClass, "Planner");
  if (!bound.planner) throw ArgumentError(L, arg, "the planner was never made");
  return bound;
}

// The script's --timeout: a long planner call never returns to the VM, so the hook cannot stop
// it; the planner calls check the clock between chunks of steps instead.
void checkTimeLimit(lua_State* L) {
  ScriptContext& context = scriptContext(L);
  if (!context.deadline || Clock::now() < *context.deadline) return;
  context.timeLimitReached = true;
  lua_sethook(L, lua_gethook(L), lua_gethookmask(L), 1);  // every later instruction raises too
  throw Error(timeLimitMessage(context.options.timeoutSeconds.value_or(0.0)));
}

// About a hundredth of a second's worth of steps, once the speed is known.
std::int64_t chunkFor(std::int64_t done, double seconds) {
  if (done <= 0 || seconds <= 0) return 8;
  return std::clamp<std::int64_t>(static_cast<std::int64_t>(done / seconds / 100.0), 1, 100000);
}

// ---- graspkit.planner(name, options) ----

// options[key] pushed without metamethods; returns its type.
int pushOption(lua_State* L, int options, const char* key) {
  lua_pushstring(L, key);
  return lua_rawget(L, options);
}

// "bad argument #7 to 'planner' (pose expected, got number)" -> "pose expected, got number":
// a nested reader names a stack slot the script never wrote, so only its reason is kept.
std::string reasonOf(const std::exception& e) {
  const std::string text = e.what();
  const auto open = text.find(" (");
  if (text.rfind("bad argument", 0) != 0 || open == std::string::npos || text.back() != ')')
    return text;
  return text.substr(open + 2, text.size() - open - 3);
}

int robotOption(lua_State* L, int options, const World& world) {
  const int type = pushOption(L, options, "robot");
  if (type == LUA_TNIL) {  // the host layer's choice: the world's first hand
    try {
      return host::defaultHand(world);
    } catch (const Error& e) {
      throw ArgumentError(L, options, std::string(e.what()) + " (option 'robot')");
    }
  }
  if (const auto* robot = testObject<BoundRobot>(L, lua_gettop(L), kRobotClass)) {
    if (&robot->world->world != &world)
      throw ArgumentError(L, options, "option 'robot': the robot belongs to another world");
    return robot->index;
  }
  if (type == LUA_TSTRING) {
    const std::string name = lua_tostring(L, -1);
    if (const auto index = world.findRobot(name)) return *index;
    throw ArgumentError(L, options,
                        fmt::format("option 'robot': no robot '{}' in the world", name));
  }
  const double index = lua_tonumber(L, -1);
  if (type != LUA_TNUMBER || index != std::floor(index) || index < 1 || index > world.robotCount())
    throw ArgumentError(
        L, options,
        fmt::format("option 'robot' must be a Robot, a robot name or an index from 1 to {}",
                    world.robotCount()));
  return static_cast<int>(index) - 1;
}

BodyRef objectOption(lua_State* L, int options, const ScriptWorld& world) {
  if (pushOption(L, options, "object") != LUA_TNIL) {
    try {
      return toBodyOf(L, lua_gettop(L), world);
    } catch (const ArgumentError& e) {
      throw ArgumentError(L, options, "option 'object': " + reasonOf(e));
    }
  }
  try {
    return host::defaultObject(world.world);
  } catch (const Error& e) {
    throw ArgumentError(L, options, std::string(e.what()) + " (option 'object')");
  }
}

// `set = {key = value}`: planner-specific settings, values strings or numbers.
void settingsOption(lua_State* L, int options, std::map<std::string, std::string>& settings) {
  const int type = pushOption(L, options, "set");
  if (type == LUA_TNIL) return;
  if (type != LUA_TTABLE)
    throw ArgumentError(L, options, "option 'set' must be a table of planner settings");
  const int table = lua_gettop(L);
  lua_pushnil(L);
  while (lua_next(L, table) != 0) {
    const bool ok = lua_type(L, -2) == LUA_TSTRING &&
                    (lua_type(L, -1) == LUA_TSTRING || lua_type(L, -1) == LUA_TNUMBER);
    if (!ok)
      throw ArgumentError(L, options, "option 'set' maps setting names to strings or numbers");
    lua_pushvalue(L, -1);  // lua_tostring converts a number in place: convert a copy
    settings[lua_tostring(L, -3)] = lua_tostring(L, -1);
    lua_pop(L, 2);
  }
}

// `states = {{pose = ..., dofs = {...}}, ...}`, encoded in the request's search space.
void statesOption(lua_State* L, int options, PlanningRequest& request) {
  const int type = pushOption(L, options, "states");
  if (type == LUA_TNIL) return;
  if (type != LUA_TTABLE)
    throw ArgumentError(L, options, "option 'states' must be a list of {pose =, dofs =}");
  const int list = lua_gettop(L);
  const auto space = makeSearchSpace(request);
  const auto count = static_cast<lua_Integer>(lua_rawlen(L, list));
  for (lua_Integer i = 1; i <= count; ++i) {
    lua_rawgeti(L, list, i);
    const int entry = lua_gettop(L);
    try {
      const OptionsTable fields(L, entry, {"pose", "dofs"});
      if (lua_type(L, entry) != LUA_TTABLE || !fields.has("pose") || !fields.has("dofs"))
        throw ArgumentError(L, entry, "needs a pose and dofs");
      pushOption(L, entry, "pose");
      const Transform pose = toPose(L, -1);
      pushOption(L, entry, "dofs");
      const std::vector<double> dofs = toNumberList(L, -1);
      request.states.push_back(SearchState{space->encode(pose, dofs)});
    } catch (const std::exception& e) {
      throw ArgumentError(L, options, fmt::format("option 'states'[{}]: {}", i, reasonOf(e)));
    }
    lua_settop(L, list);
  }
}

// "energy function (plan.lua:12)"
std::string describeFunction(lua_State* L, int index) {
  lua_Debug ar;
  lua_pushvalue(L, index);
  lua_getinfo(L, ">S", &ar);
  if (ar.linedefined < 0) return fmt::format("energy function ({})", ar.short_src);
  return fmt::format("energy function ({}:{})", ar.short_src, ar.linedefined);
}

// The energy option when it is a Lua function, which gets a world of its own (a clone) to look
// at the hand in. (A name is a setting like any other: readRequest passes it on.)
void energyFunctionOption(lua_State* L, int options, const WorldHandle& source,
                          BoundPlanner& bound) {
  PlanningRequest& request = bound.request;
  if (pushOption(L, options, "energy") != LUA_TFUNCTION) return;
  auto link = std::make_shared<LuaEnergyLink>();
  link->name = describeFunction(L, -1);
  link->robot = request.robot;
  link->function = luaL_ref(L, LUA_REGISTRYINDEX);
  bound.luaEnergy = link;  // from here on the planner's __gc releases the references
  link->view = std::make_shared<ScriptWorld>();
  link->view->world = source->world.clone();
  link->view->file = source->file;
  lua_createtable(L, 0, 3);
  pushWorld(L, link->view);
  lua_setfield(L, -2, "world");
  pushRobot(L, link->view, request.robot);
  lua_setfield(L, -2, "robot");
  pushBody(L, link->view, request.object);
  lua_setfield(L, -2, "object");
  link->context = luaL_ref(L, LUA_REGISTRYINDEX);
  request.energy = "lua";
  request.customEnergy = [link] { return std::make_unique<LuaSearchEnergy>(link); };
}

// The options table read into the host layer's settings, so that what a script leaves out is
// what `graspkit plan` and every other front end leave out too.
void readRequest(lua_State* L, int options, BoundPlanner& bound) {
  const OptionsTable table(L, options,
                           {"world", "robot", "object", "energy", "space", "posture", "seed",
                            "threads", "top", "preset", "mode", "set", "states"});
  if (pushOption(L, options, "world") == LUA_TNIL)
    throw ArgumentError(L, options, "option 'world' (a World) is required");
  const WorldHandle source = toObject<WorldHandle>(L, lua_gettop(L), kWorldClass, "World");
  host::PlanSettings settings;
  settings.planner = bound.name;
  const int robot = robotOption(L, options, source->world);
  const BodyRef object = objectOption(L, options, *source);
  settings.space = parseNamed<PositionSpace>(
      table.string("space", std::string(nameOf(settings.space))), "position space");
  settings.posture = parseNamed<PostureSpace>(
      table.string("posture", std::string(nameOf(settings.posture))), "posture space");
  const double seed = table.number("seed", static_cast<double>(settings.seed));
  if (seed < 0 || seed != std::floor(seed) || seed > 9007199254740992.0)
    throw ArgumentError(L, options, "option 'seed' must be a whole number >= 0");
  settings.seed = static_cast<std::uint64_t>(seed);
  const int energyType = pushOption(L, options, "energy");
  if (energyType == LUA_TSTRING)
    settings.energy = lua_tostring(L, -1);
  else if (energyType != LUA_TNIL && energyType != LUA_TFUNCTION)
    throw ArgumentError(L, options, "option 'energy' must be an energy name or a function");
  // A Lua energy runs on the script's thread: one search thread unless the script asks for more
  // (which is refused below).
  settings.threads = energyType == LUA_TFUNCTION ? 1 : 0;
  if (table.has("threads")) {
    settings.threads = table.integer("threads", 1);
    if (settings.threads < 1) throw ArgumentError(L, options, "option 'threads' must be >= 1");
  }
  settings.top = table.integer("top", settings.top);
  if (settings.top < 1) throw ArgumentError(L, options, "option 'top' must be >= 1");
  if (table.has("preset")) settings.preset = table.string("preset", "");
  if (table.has("mode")) settings.mode = table.string("mode", "");
  settingsOption(L, options, settings.options);
  bound.request = host::planningRequest(std::make_shared<const World>(source->world.clone()), robot,
                                        object, settings);
  statesOption(L, options, bound.request);
  energyFunctionOption(L, options, source, bound);
  if (bound.luaEnergy && bound.request.threads != 1)
    throw ArgumentError(L, options,
                        fmt::format("a Lua energy runs on one thread; option 'threads' is {}",
                                    bound.request.threads));
}

int newPlanner(lua_State* L) {
  const std::string name = toString(L, 1);
  checkTable(L, 2);
  // The object first: if reading the options fails, __gc still releases what was referenced.
  BoundPlanner& bound = newObject<BoundPlanner>(L, kPlannerClass);
  const int self = lua_gettop(L);
  bound.name = name;
  readRequest(L, 2, bound);
  PlannerCall call(L, bound);  // a planner may evaluate its start state while being made
  bound.planner = Registry::global().makePlanner(name, bound.request);
  lua_pushvalue(L, self);
  return 1;
}

// ---- Planner methods ----

// Each grasp as a table; a closed one also carries `world`, a World with the hand closed as
// measured (breakaway state included), ready for world:save.
void pushGrasps(lua_State* L, const PlanningRequest& request,
                const std::vector<PlannedGrasp>& grasps) {
  lua_createtable(L, static_cast<int>(grasps.size()), 0);
  for (std::size_t i = 0; i < grasps.size(); ++i) {
    const PlannedGrasp& g = grasps[i];
    lua_createtable(L, 0, 10);
    pushPose(L, g.pose);
    lua_setfield(L, -2, "pose");
    pushNumberList(L, g.dofs);
    lua_setfield(L, -2, "dofs");
    pushNumberList(L, g.values);
    lua_setfield(L, -2, "values");
    lua_pushnumber(L, g.energy);
    lua_setfield(L, -2, "energy");
    if (g.evaluated) {
      pushNumberList(L, g.closed.dofs);
      lua_setfield(L, -2, "closed_dofs");
      lua_pushnumber(L, g.epsilon);
      lua_setfield(L, -2, "epsilon");
      lua_pushnumber(L, g.volume);
      lua_setfield(L, -2, "volume");
      lua_pushinteger(L, g.contacts);
      lua_setfield(L, -2, "contacts");
      lua_pushboolean(L, g.forceClosure);
      lua_setfield(L, -2, "force_closure");
      auto closed = std::make_shared<ScriptWorld>();
      closed->world = graspWorld(request, g);
      pushWorld(L, std::move(closed));
      lua_setfield(L, -2, "world");
    }
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
}

// planner:step([n]): n more steps (default 1), in chunks so the time limit is heard.
int step(lua_State* L) {
  BoundPlanner& bound = toPlanner(L, 1);
  const double wanted = isNone(L, 2) ? 1.0 : toNumber(L, 2);
  if (wanted < 0 || wanted != std::floor(wanted) || wanted > 1e15)
    throw ArgumentError(L, 2, "a whole number of steps >= 0 expected");
  const auto total = static_cast<std::int64_t>(wanted);
  PlannerCall call(L, bound);
  const auto start = Clock::now();
  // Progress is what the planner says it did: a planner whose work comes in pieces (simann's
  // restarts) may do more than a chunk asks.
  const std::int64_t first = bound.planner->stepsDone();
  std::int64_t done = 0;
  while (done < total && !bound.planner->done()) {
    const double elapsed = std::chrono::duration<double>(Clock::now() - start).count();
    const std::int64_t chunk = std::min(total - done, chunkFor(done, elapsed));
    bound.planner->step(chunk);
    done = std::max(done + 1, bound.planner->stepsDone() - first);
    checkTimeLimit(L);
  }
  lua_pushinteger(L, bound.planner->stepsDone());
  return 1;
}

// planner:run{steps = N} or planner:run{seconds = S}: then the planner's last stage.
int run(lua_State* L) {
  BoundPlanner& bound = toPlanner(L, 1);
  const OptionsTable options(L, 2, {"steps", "seconds"});
  if (options.has("steps") == options.has("seconds"))
    throw ArgumentError(L, 2, "give either steps or seconds");
  PlanningBudget budget;
  if (options.has("steps")) {
    const double steps = options.number("steps", 0);
    if (steps < 0 || steps != std::floor(steps) || steps > 1e15)
      throw ArgumentError(L, 2, "option 'steps' must be a whole number >= 0");
    budget.steps = static_cast<std::int64_t>(steps);
  } else {
    budget.seconds = options.number("seconds", 0);
    if (*budget.seconds < 0) throw ArgumentError(L, 2, "option 'seconds' must be >= 0");
  }
  budget.reportEvery = 0.05;
  const std::int64_t first = bound.planner->stepsDone();
  budget.progress = [L, &budget, first](const PlannerProgress& p) {
    checkTimeLimit(L);
    const double done = budget.steps ? static_cast<double>(p.steps - first) : p.seconds;
    const double total = budget.steps ? static_cast<double>(*budget.steps) : *budget.seconds;
    reportProgress(L, total > 0 ? std::min(done / total, 0.999) : 0.0,
                   fmt::format("{} steps, best energy {:.5g}", p.steps - first, p.bestEnergy));
    return true;
  };
  PlanningRun result;
  {
    PlannerCall call(L, bound);
    result = runPlanner(*bound.planner, budget);
  }
  reportProgress(L, 1.0, fmt::format("{} steps in {:.2f} s", result.steps, result.seconds));
  lua_pushinteger(L, result.steps);
  lua_pushnumber(L, result.seconds);
  return 2;
}

std::vector<PlannedGrasp> finishedGrasps(lua_State* L, BoundPlanner& bound, bool autograsp) {
  PlannerCall call(L, bound);
  std::vector<PlannedGrasp> grasps = bound.planner->best();
  if (!autograsp) return grasps;
  // finishGrasps closes each grasp on a fresh clone of the world the script gave, as
  // `graspkit plan` does; one thread, since a Lua energy may be called from here.
  finishGrasps(bound.request, grasps, 1);
  return grasps;
}

// planner:best([{autograsp = true}])
int best(lua_State* L) {
  BoundPlanner& bound = toPlanner(L, 1);
  const OptionsTable options(L, 2, {"autograsp"});
  pushGrasps(L, bound.request, finishedGrasps(L, bound, options.boolean("autograsp", false)));
  return 1;
}

// planner:finish(): the planner's last stage (simann's two-stage refinement; nothing for most),
// then the best list with each grasp closed and measured.
int finish(lua_State* L) {
  BoundPlanner& bound = toPlanner(L, 1);
  {
    PlannerCall call(L, bound);
    bound.planner->finish();
  }
  pushGrasps(L, bound.request, finishedGrasps(L, bound, true));
  return 1;
}

int steps(lua_State* L) {
  lua_pushinteger(L, toPlanner(L, 1).planner->stepsDone());
  return 1;
}

int plannerToString(lua_State* L) {
  const BoundPlanner& bound = toPlanner(L, 1);
  const std::string energy =
      bound.luaEnergy ? bound.luaEnergy->name : canonicalEnergyName(bound.request.energy);
  const std::string text =
      fmt::format("Planner({}, {}, {} steps)", bound.name, energy, bound.planner->stepsDone());
  lua_pushlstring(L, text.data(), text.size());
  return 1;
}

// Releases the Lua energy's references, then the C++ object.
int collectPlanner(lua_State* L) {
  BoundPlanner* bound = testObject<BoundPlanner>(L, 1, kPlannerClass);
  if (bound == nullptr) return 0;  // not a live planner
  if (bound->luaEnergy) {
    luaL_unref(L, LUA_REGISTRYINDEX, bound->luaEnergy->function);
    luaL_unref(L, LUA_REGISTRYINDEX, bound->luaEnergy->context);
  }
  return destroyObject<BoundPlanner>(L);
}

}  // namespace

void openPlannerFunctions(lua_State* L) {
  const luaL_Reg methods[] = {
      {"step", guarded<step>},     {"run", guarded<run>},     {"best", guarded<best>},
      {"finish", guarded<finish>}, {"steps", guarded<steps>}, {nullptr, nullptr},
  };
  defineClass(L, kPlannerClass, methods, collectPlanner, guarded<plannerToString>);
  lua_pushcfunction(L, guarded<newPlanner>);
  lua_setfield(L, -2, "planner");
}

}  // namespace graspkit::lua
