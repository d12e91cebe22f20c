#include "module.hpp"

#include <algorithm>

#include "graspkit/base/version.hpp"
#include "lua_api.hpp"
#include "script_context.hpp"

namespace graspkit::lua {
namespace {

int version(lua_State* L) {
  lua_pushstring(L, engineVersion());
  return 1;
}

// graspkit.progress(done, total [, label]): reported to the host (ScriptOptions::progress), which
// draws it; the command line shows it as it shows every command's progress.
int progress(lua_State* L) {
  const double done = toNumber(L, 1);
  const double total = toNumber(L, 2);
  const std::string label = isNone(L, 3) ? "" : toString(L, 3);
  reportProgress(L, total > 0 ? done / total : 1.0, label);
  return 0;
}

}  // namespace

void reportProgress(lua_State* L, double fraction, const std::string& text) {
  const auto& progress = scriptContext(L).options.progress;
  if (progress) progress(std::clamp(fraction, 0.0, 1.0), text);
}

int openGraspkitModule(lua_State* L) {
  registerBodyClass(L);
  registerRobotClass(L);
  registerGraspClass(L);
  const luaL_Reg functions[] = {
      {"version", guarded<version>},
      {"progress", guarded<progress>},
      {nullptr, nullptr},
  };
  luaL_newlib(L, functions);
  openPoseFunctions(L);
  openWorldFunctions(L);
  openPluginFunctions(L);
  openJsonFunctions(L);
  openPlannerFunctions(L);
  openDatasetFunctions(L);
  lua_pushstring(L, scriptContext(L).script.string().c_str());
  lua_setfield(L, -2, "script_path");
  lua_pushstring(L, scriptContext(L).scriptFolder.string().c_str());
  lua_setfield(L, -2, "script_folder");
  return 1;
}

}  // namespace graspkit::lua
