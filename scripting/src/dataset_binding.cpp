// graspkit.load_dataset: a grasp dataset file that graspkit batch wrote (docs/dataset.md), as a
// plain table, so a script can pick, filter and replay a dataset's grasps.

#include "graspkit/base/error.hpp"
#include "graspkit/io/dataset/grasp_dataset_file.hpp"
#include "lua_api.hpp"
#include "module.hpp"
#include "script_context.hpp"

namespace graspkit::lua {
namespace {

void setNumber(lua_State* L, const char* key, double value) {
  lua_pushnumber(L, value);
  lua_setfield(L, -2, key);
}

void setString(lua_State* L, const char* key, const std::string& value) {
  lua_pushlstring(L, value.data(), value.size());
  lua_setfield(L, -2, key);
}

void pushGrasp(lua_State* L, const DatasetGrasp& g) {
  lua_createtable(L, 0, 9);
  pushPose(L, g.grasp);
  lua_setfield(L, -2, "pose");
  pushPose(L, g.pregrasp);
  lua_setfield(L, -2, "pregrasp");
  pushNumberList(L, g.openDofs);
  lua_setfield(L, -2, "open_dofs");
  pushNumberList(L, g.closedDofs);
  lua_setfield(L, -2, "closed_dofs");
  setNumber(L, "epsilon", g.epsilon);
  setNumber(L, "volume", g.volume);
  lua_pushboolean(L, g.forceClosure);
  lua_setfield(L, -2, "force_closure");
  if (g.held >= 0) {  // nil: not validated
    lua_pushboolean(L, g.held == 1);
    lua_setfield(L, -2, "held");
  }
  if (!g.validation.empty()) {  // nil: not validated, or a file from before schema 2
    lua_createtable(L, static_cast<int>(g.validation.size()), 0);
    for (std::size_t k = 0; k < g.validation.size(); ++k) {
      const DatasetDirection& d = g.validation[k];
      lua_createtable(L, 0, 7);
      pushVector3(L, d.direction);
      lua_setfield(L, -2, "direction");
      if (d.tried) {  // held nil: not tried (another direction let go first)
        lua_pushboolean(L, d.held);
        lua_setfield(L, -2, "held");
      }
      lua_pushboolean(L, d.tried);
      lua_setfield(L, -2, "tried");
      setNumber(L, "slip", d.slip);
      setNumber(L, "turn", d.turn);
      setNumber(L, "seconds", d.seconds);
      lua_pushboolean(L, d.failed);
      lua_setfield(L, -2, "failed");
      lua_rawseti(L, -2, static_cast<lua_Integer>(k + 1));
    }
    lua_setfield(L, -2, "validation");
  }
  lua_createtable(L, static_cast<int>(g.breakaway.size()), 0);
  for (std::size_t j = 0; j < g.breakaway.size(); ++j) {
    lua_createtable(L, 0, 2);
    lua_pushboolean(L, g.breakaway[j].engaged);
    lua_setfield(L, -2, "engaged");
    setNumber(L, "value", g.breakaway[j].value);
    lua_rawseti(L, -2, static_cast<lua_Integer>(j + 1));
  }
  lua_setfield(L, -2, "breakaway");
  lua_createtable(L, static_cast<int>(g.contactPoints.size()), 0);
  for (std::size_t k = 0; k < g.contactPoints.size(); ++k) {
    lua_createtable(L, 0, 2);
    pushVector3(L, g.contactPoints[k]);
    lua_setfield(L, -2, "point");
    pushVector3(L, g.contactNormals[k]);
    lua_setfield(L, -2, "normal");
    lua_rawseti(L, -2, static_cast<lua_Integer>(k + 1));
  }
  lua_setfield(L, -2, "contacts");
}

// graspkit.load_dataset(file) -> {object = {file, name, mass}, hand = {file, name},
//   engine_version, seed, grasps = {{pose, pregrasp, open_dofs, closed_dofs, epsilon, volume,
//   force_closure, held, validation = {{direction, held, slip, turn, seconds, failed, tried},
//   ...} (held nil where not tried: another direction let go first),
//   breakaway = {{engaged, value}, ...}, contacts = {{point, normal}, ...}},
//   ...}}
int loadDataset(lua_State* L) {
  const std::filesystem::path file = scriptContext(L).inputPath(toFileName(L, 1));
  const GraspDataset dataset = loadGraspDataset(file);
  if (!lua_checkstack(L, 8)) throw Error("load_dataset: out of Lua stack");
  lua_createtable(L, 0, 5);
  lua_createtable(L, 0, 3);
  setString(L, "file", dataset.objectFile);
  setString(L, "name", dataset.objectName);
  setNumber(L, "mass", dataset.objectMass);
  lua_setfield(L, -2, "object");
  lua_createtable(L, 0, 2);
  setString(L, "file", dataset.handFile);
  setString(L, "name", dataset.handName);
  lua_setfield(L, -2, "hand");
  setString(L, "engine_version", dataset.engineVersion);
  setString(L, "seed", std::to_string(dataset.seed));  // a 64-bit unsigned: exact as text
  lua_createtable(L, static_cast<int>(dataset.grasps.size()), 0);
  for (std::size_t i = 0; i < dataset.grasps.size(); ++i) {
    pushGrasp(L, dataset.grasps[i]);
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
  lua_setfield(L, -2, "grasps");
  return 1;
}

}  // namespace

void openDatasetFunctions(lua_State* L) {
  const luaL_Reg functions[] = {
      {"load_dataset", guarded<loadDataset>},
      {nullptr, nullptr},
  };
  luaL_setfuncs(L, functions, 0);
}

}  // namespace graspkit::lua
