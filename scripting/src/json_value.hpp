#pragma once
// Lua values as JSON (json_binding.cpp): tables with keys 1..n are arrays, other tables objects;
// NaN, infinities, functions and userdata are errors.

#include <lua.hpp>

#include <nlohmann/json.hpp>

namespace graspkit::lua {

// Throws graspkit::Error naming the offending field.
nlohmann::json luaToJson(lua_State* L, int index);

}  // namespace graspkit::lua
