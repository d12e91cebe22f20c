#include "module.hpp"

#include <unistd.h>
#include <cstdio>

#include "graspkit/version.hpp"
#include "lua_api.hpp"
#include "script_context.hpp"

namespace graspkit::lua {
namespace {

int version(lua_State* L) {
  lua_pushstring(L, engineVersion());
  return 1;
}

// graspkit.progress(done, total [, label]): a one-line bar on stderr when it is a terminal
// (and --quiet is off); nothing otherwise, so scripts can call it freely in CI.
int progress(lua_State* L) {
  const double done = toNumber(L, 1);
  const double total = toNumber(L, 2);
  const std::string label = isNone(L, 3) ? "" : toString(L, 3);
  drawProgress(L, done, total, label);
  return 0;
}

}  // namespace

void drawProgress(lua_State* L, double done, double total, const std::string& label) {
  if (!scriptContext(L).options.showProgress || isatty(STDERR_FILENO) == 0) return;
  const double fraction = total > 0 ? std::min(1.0, std::max(0.0, done / total)) : 1.0;
  const int width = 30;
  const int filled = static_cast<int>(fraction * width + 0.5);
  std::fprintf(stderr, "\r[%-*s] %3.0f%% %s", width, std::string(filled, '#').c_str(),
               fraction * 100.0, label.c_str());
  if (done >= total) std::fputc('\n', stderr);
  std::fflush(stderr);
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
  lua_pushstring(L, scriptContext(L).script.string().c_str());
  lua_setfield(L, -2, "script_path");
  lua_pushstring(L, scriptContext(L).scriptFolder.string().c_str());
  lua_setfield(L, -2, "script_folder");
  return 1;
}

}  // namespace graspkit::lua
