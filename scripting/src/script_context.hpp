#pragma once
// What every binding of a script's Lua state shares: the options, the sandbox's path policy,
// one model cache (a robot or mesh used by several worlds is read once) and the time limit.
// Reached from any C function through the state's extra space.

#include <chrono>
#include <filesystem>
#include <optional>
#include <string>

#include "graspkit/io/common/model_cache.hpp"
#include "graspkit/lua/script_host.hpp"
#include "memory_limit.hpp"

namespace graspkit::lua {

struct ScriptContext {
  ScriptOptions options;
  std::filesystem::path script;                   // absolute
  std::filesystem::path scriptFolder;             // absolute
  std::vector<std::filesystem::path> modelRoots;  // --root, GRASPKIT_ROOT, GRASPIT
  PathPolicy paths;
  std::shared_ptr<ModelCache> cache = std::make_shared<ModelCache>();
  std::optional<std::chrono::steady_clock::time_point> deadline;
  bool timeLimitReached = false;  // set by the time-limit hook, even if the script caught its error
  std::optional<int> exitStatus;  // set by os.exit
  LuaMemory memory;               // the Lua heap and its limit

  // A file the script names for reading: absolute as given; relative, the first that exists of
  // the current folder, the script's folder and each model root (the current folder when none
  // does). The sandbox's read check applies.
  std::filesystem::path inputPath(const std::string& name) const;
  // A file the script names for writing: relative to the current folder, checked for writing.
  std::filesystem::path outputPath(const std::string& name) const;
};

ScriptContext& scriptContext(lua_State* L);

}  // namespace graspkit::lua
