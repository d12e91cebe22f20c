// libFuzzer target for the Lua API's argument readers: each input is a short sequence of calls,
// each a function of the graspkit module or a method of an engine object (world, robot, body,
// grasp, pose), with arguments of any type and value (NaN, infinities, huge integers, long or
// odd strings, nested tables, objects of the wrong class or of another world, a wrong `self`).
// The promise under test: a bad argument is a Lua error, never a crash, an abort or undefined
// behaviour (the sanitizers watch), and the Lua stack stays balanced.
//
// Calls that do open-ended work by design (planner runs, autograsp, file loads and saves, plugin
// loading, progress bars) are left out: their argument readers are the same helpers, and the
// file readers have targets of their own.

#include <unistd.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include <lua.hpp>

#include "graspkit/lua/script_host.hpp"

namespace {

namespace fs = std::filesystem;

// Open-ended work, kept out (see above).
const std::set<std::string> kLeftOut = {"autograsp",
                                        "approach_to_contact",
                                        "open",
                                        "run",
                                        "step",
                                        "best",
                                        "finish",
                                        "load_world",
                                        "save",
                                        "add_object",
                                        "add_obstacle",
                                        "add_robot",
                                        "load_plugin",
                                        "plugins",
                                        "progress",
                                        "planner",
                                        "inverse_kinematics"};

// The receivers: the module, then the engine objects the fixture script makes (globals).
const char* const kReceivers[] = {"graspkit", "world", "robot", "body", "grasp", "pose", "other"};

class Input {
 public:
  Input(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}
  bool empty() const { return at_ >= size_; }
  std::uint8_t byte() { return at_ < size_ ? data_[at_++] : 0; }
  template <class T>
  T raw() {
    T value{};
    const std::size_t n = std::min(sizeof(T), size_ - std::min(at_, size_));
    std::memcpy(&value, data_ + at_, n);
    at_ += n;
    return value;
  }
  std::string text(std::size_t length) {
    length = std::min(length, size_ - std::min(at_, size_));
    std::string out(reinterpret_cast<const char*>(data_ + at_), length);
    at_ += length;
    return out;
  }

 private:
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t at_ = 0;
};

struct Fixture {
  std::unique_ptr<graspkit::lua::ScriptHost> host;
  std::vector<std::string> moduleFunctions;  // the graspkit table's functions, sorted
};

std::vector<std::string> moduleFunctions(lua_State* L) {
  std::vector<std::string> names;
  lua_getglobal(L, "graspkit");
  lua_pushnil(L);
  while (lua_next(L, -2) != 0) {
    if (lua_type(L, -2) == LUA_TSTRING && lua_isfunction(L, -1)) {
      const std::string name = lua_tostring(L, -2);
      if (!kLeftOut.count(name)) names.push_back(name);
    }
    lua_pop(L, 1);
  }
  lua_pop(L, 1);
  std::sort(names.begin(), names.end());
  return names;
}

Fixture& fixture() {
  static Fixture made = [] {
    std::string pattern = (fs::temp_directory_path() / "graspkit_lua_fuzz_XXXXXX").string();
    if (mkdtemp(pattern.data()) == nullptr) std::abort();
    const fs::path folder = pattern;
    const fs::path models = GRASPKIT_FUZZ_MODELS;
    std::ofstream(folder / "fixture.lua") << "-- the lua_api fuzz target's fixture\n";
    graspkit::lua::ScriptOptions options;
    options.load.roots = {models};
    options.load.useEnvironment = false;
    options.memoryLimitBytes = std::size_t{256} << 20;
    Fixture f;
    f.host = std::make_unique<graspkit::lua::ScriptHost>(folder / "fixture.lua", options);
    const std::string world = (models / "worlds" / "gripper_box.xml").string();
    if (!f.host
             ->runString("base = graspkit.load_world('" + world + "')\nother = base:clone()",
                         "fixture")
             .ok)
      std::abort();
    f.moduleFunctions = moduleFunctions(f.host->state());
    return f;
  }();
  return made;
}

// Object methods cannot be listed through their locked metatables: these are the documented ones
// (docs/lua.md), looked up through the object as a script would.
const std::vector<std::vector<std::string>> kObjectMethods = {
    {},
    {"clone", "file", "bodies", "body", "robots", "robot", "contacts", "collides", "collisions",
     "distance", "raycast"},
    {"name", "index", "world", "type", "type_provider", "is_hand", "dof_count", "dofs",
     "dof_limits", "set_dofs", "pose", "set_pose", "chain_count", "base", "link", "links",
     "link_poses", "contacts", "grasp"},
    {"name", "kind", "pose", "set_pose", "file", "material", "mass", "cog", "inertia",
     "triangle_count", "is_dynamic", "world"},
    {"epsilon", "volume", "force_closure", "quality", "contacts", "contact_count", "object",
     "robot", "failure"},
    {},
    {"clone", "bodies", "body", "robot", "distance", "collides"}};

void pushArgument(lua_State* L, Input& in, int depth);

void pushTable(lua_State* L, Input& in, int depth) {
  const int n = in.byte() % 8;
  lua_createtable(L, n, 0);
  for (int i = 1; i <= n; ++i) {
    if (in.byte() & 1) {
      pushArgument(L, in, depth + 1);
      lua_rawseti(L, -2, i);
    } else {
      static const char* const kKeys[] = {"limits",  "gws",   "max_distance", "indent",
                                          "chain",   "speed", "max_steps",    "x",
                                          "seconds", "steps"};
      pushArgument(L, in, depth + 1);
      lua_setfield(L, -2, kKeys[in.byte() % 10]);
    }
  }
}

void pushArgument(lua_State* L, Input& in, int depth) {
  switch (in.byte() % 11) {
    case 0:
      lua_pushnil(L);
      break;
    case 1:
      lua_pushboolean(L, in.byte() & 1);
      break;
    case 2:
      lua_pushinteger(L, static_cast<lua_Integer>(static_cast<std::int8_t>(in.byte())));
      break;
    case 3:
      lua_pushinteger(L, in.raw<lua_Integer>());
      break;
    case 4:
      lua_pushnumber(L, in.raw<double>());
      break;
    case 5: {
      const std::string s = in.text(in.byte() % 48);
      lua_pushlstring(L, s.data(), s.size());
      break;
    }
    case 6: {
      static const char* const kWords[] = {"clamp", "ignore",          "error",  "L1",
                                           "Linf",  "epsilon",         "volume", "box",
                                           "floor", "gripper_box_palm"};
      lua_pushstring(L, kWords[in.byte() % 10]);
      break;
    }
    case 7:
      if (depth < 4) {
        pushTable(L, in, depth);
      } else {
        lua_pushnil(L);
      }
      break;
    case 8: {  // a list of numbers: points, poses, DOF values
      const int n = in.byte() % 8;
      lua_createtable(L, n, 0);
      for (int i = 1; i <= n; ++i) {
        lua_pushnumber(L, (in.byte() & 1) ? static_cast<double>(static_cast<std::int8_t>(in.byte()))
                                          : in.raw<double>());
        lua_rawseti(L, -2, i);
      }
      break;
    }
    case 9:
      lua_getglobal(L, kReceivers[1 + in.byte() % 6]);
      break;  // an engine object
    default:
      lua_pushcfunction(L, [](lua_State*) { return 0; });
      break;
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  Fixture& f = fixture();
  lua_State* L = f.host->state();
  const int top = lua_gettop(L);
  // A fresh world per input, so an input's calls reproduce alone.
  if (!f.host
           ->runString(R"(
        world = base:clone(); robot = world:robot(1); body = world:bodies()[1]
        pose = body:pose(); grasp = robot:grasp(world:bodies()[2]))",
                       "reset")
           .ok)
    std::abort();
  Input in(data, size);
  for (int call = 0; call < 6 && !in.empty(); ++call) {
    const int receiver = in.byte() % 7;
    const std::vector<std::string>& list =
        receiver == 0 ? f.moduleFunctions : kObjectMethods[receiver];
    if (list.empty()) continue;
    const std::string& name = list[in.byte() % list.size()];
    lua_getglobal(L, kReceivers[receiver]);
    lua_getfield(L, -1, name.c_str());  // through __index, as a script's obj:name() does
    lua_insert(L, -2);                  // function, receiver
    int nargs = 0;
    if (receiver == 0) {
      lua_pop(L, 1);  // module functions take no self
    } else {
      nargs = 1;
      if (in.byte() % 8 == 0) {  // a wrong self
        lua_pop(L, 1);
        pushArgument(L, in, 0);
      }
    }
    const int extra = in.byte() % 5;
    for (int i = 0; i < extra; ++i) pushArgument(L, in, 0);
    f.host->protectedCall(nargs + extra, 0);
    lua_settop(L, top);
  }
  if (lua_gettop(L) != top) std::abort();  // the stack must balance whatever happened
  return 0;
}
