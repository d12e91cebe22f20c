// graspkit.plugins(), graspkit.load_plugin(), and the names plugins can add to.

#include <fmt/format.h>

#include "graspkit/base/error.hpp"
#include "graspkit/plugin/plugin_loader.hpp"
#include "graspkit/plugin/registry.hpp"
#include "lua_api.hpp"
#include "module.hpp"
#include "script_context.hpp"

namespace graspkit::lua {
namespace {

namespace fs = std::filesystem;

// {file, name, version, loaded, error, provides = {{kind = "robot type", name = "Barrett"}}}
void pushPluginInfo(lua_State* L, const PluginInfo& info) {
  lua_createtable(L, 0, 6);
  lua_pushstring(L, info.file.c_str());
  lua_setfield(L, -2, "file");
  lua_pushstring(L, info.name.c_str());
  lua_setfield(L, -2, "name");
  lua_pushstring(L, info.version.c_str());
  lua_setfield(L, -2, "version");
  lua_pushboolean(L, info.loaded);
  lua_setfield(L, -2, "loaded");
  if (!info.loaded) {
    lua_pushstring(L, info.error.c_str());
    lua_setfield(L, -2, "error");
  }
  lua_createtable(L, static_cast<int>(info.provides.size()), 0);
  for (std::size_t i = 0; i < info.provides.size(); ++i) {
    lua_createtable(L, 0, 2);
    lua_pushlstring(L, nameOf(info.provides[i].first).data(),
                    nameOf(info.provides[i].first).size());
    lua_setfield(L, -2, "kind");
    lua_pushstring(L, info.provides[i].second.c_str());
    lua_setfield(L, -2, "name");
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
  lua_setfield(L, -2, "provides");
}

// Every plugin on the search path (as the probe found it, none loaded into this process),
// failures included with their reason.
int plugins(lua_State* L) {
  const std::vector<PluginInfo> infos = Registry::global().plugins().survey();
  lua_createtable(L, static_cast<int>(infos.size()), 0);
  for (std::size_t i = 0; i < infos.size(); ++i) {
    pushPluginInfo(L, infos[i]);
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
  return 1;
}

bool inFolder(const fs::path& file, const fs::path& folder) {
  std::error_code ec;
  return fs::equivalent(file.parent_path(), folder, ec);
}

// Loading a plugin runs its native code, which no sandbox can contain: a sandboxed script may
// load only plugins that sit in a folder of the plugin search path (the ones the user or the
// installation already trusts; no --allow-read is needed for them). --unsafe loads any file.
int loadPlugin(lua_State* L) {
  const ScriptContext& context = scriptContext(L);
  const std::string name = toFileName(L, 1);
  PluginLoader& loader = Registry::global().plugins();
  fs::path file = fs::absolute(fs::path(name));
  if (context.paths.restricted()) {
    bool trusted = false;
    for (const fs::path& folder : loader.searchPath()) trusted = trusted || inFolder(file, folder);
    if (!trusted) {
      throw Error(SourceLocation{file.string()},
                  fmt::format("sandbox: a script may only load plugins from the plugin search "
                              "path ({}); use GRASPKIT_PLUGIN_PATH or --unsafe",
                              loader.describeSearchPath()));
    }
  } else {
    file = context.inputPath(name);
  }
  pushPluginInfo(L, loader.load(file));
  return 1;
}

int robotTypes(lua_State* L) {
  pushStringList(L, Registry::global().plugins().availableNames(FactoryKind::RobotType));
  return 1;
}

int qualityMeasures(lua_State* L) {
  pushStringList(L, Registry::global().plugins().availableNames(FactoryKind::QualityMeasure));
  return 1;
}

}  // namespace

void openPluginFunctions(lua_State* L) {
  const luaL_Reg functions[] = {
      {"plugins", guarded<plugins>},
      {"load_plugin", guarded<loadPlugin>},
      {"robot_types", guarded<robotTypes>},
      {"quality_measures", guarded<qualityMeasures>},
      {nullptr, nullptr},
  };
  luaL_setfuncs(L, functions, 0);
}

}  // namespace graspkit::lua
