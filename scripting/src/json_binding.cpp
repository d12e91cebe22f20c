// graspkit.json_encode and graspkit.json_decode: scripts read configuration and reference
// figures, and write results for other tools, without a C module.

#include <fmt/format.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "graspkit/base/error.hpp"
#include "json_value.hpp"
#include "lua_api.hpp"
#include "module.hpp"

namespace graspkit::lua {

using nlohmann::json;

namespace {

constexpr int kMaxDepth = 64;  // deeper is a cycle or a mistake

// A table whose keys are exactly 1..n (n > 0) is an array; any other table is an object.
bool isArray(lua_State* L, int index, lua_Integer* length) {
  lua_Integer count = 0;
  lua_pushnil(L);
  while (lua_next(L, index) != 0) {
    lua_pop(L, 1);
    if (!lua_isinteger(L, -1)) {
      lua_pop(L, 1);
      return false;
    }
    ++count;
  }
  *length = count;
  return count > 0 && static_cast<lua_Integer>(lua_rawlen(L, index)) == count;
}

json toJson(lua_State* L, int index, int depth, const std::string& path) {
  index = lua_absindex(L, index);
  if (depth > kMaxDepth)
    throw Error(fmt::format("json_encode: {} nests too deep (a cycle?)", path));
  // A C function may only use the stack space it asks for; each level takes three slots.
  if (!lua_checkstack(L, 8)) throw Error("json_encode: out of Lua stack");
  switch (lua_type(L, index)) {
    case LUA_TNIL:
      return nullptr;
    case LUA_TBOOLEAN:
      return lua_toboolean(L, index) != 0;
    case LUA_TNUMBER: {
      if (lua_isinteger(L, index)) return static_cast<std::int64_t>(lua_tointeger(L, index));
      const double value = lua_tonumber(L, index);
      if (!std::isfinite(value)) {
        throw Error(fmt::format("json_encode: {} is {}, which JSON cannot hold", path,
                                std::isnan(value) ? "NaN"
                                : value > 0       ? "inf"
                                                  : "-inf"));
      }
      return value;
    }
    case LUA_TSTRING:
      return std::string(lua_tostring(L, index));
    case LUA_TTABLE: {
      lua_Integer length = 0;
      if (isArray(L, index, &length)) {
        json array = json::array();
        for (lua_Integer i = 1; i <= length; ++i) {
          lua_rawgeti(L, index, i);
          array.push_back(toJson(L, -1, depth + 1, fmt::format("{}[{}]", path, i)));
          lua_pop(L, 1);
        }
        return array;
      }
      json object = json::object();
      lua_pushnil(L);
      while (lua_next(L, index) != 0) {
        std::string key;
        if (lua_type(L, -2) == LUA_TSTRING) {
          key = lua_tostring(L, -2);
        } else if (lua_type(L, -2) == LUA_TNUMBER) {
          lua_pushvalue(L, -2);
          key = lua_tostring(L, -1);  // converts the copy, not the key lua_next needs
          lua_pop(L, 1);
        } else {
          throw Error(fmt::format("json_encode: {} has a {} key", path, luaL_typename(L, -2)));
        }
        object[key] = toJson(L, -1, depth + 1, path + "." + key);
        lua_pop(L, 1);
      }
      return object;
    }
    default:
      throw Error(fmt::format("json_encode: {} is a {}, which JSON cannot hold", path,
                              luaL_typename(L, index)));
  }
}

void pushJson(lua_State* L, const json& value, int depth) {
  if (depth > kMaxDepth) throw Error(fmt::format("json_decode: nested deeper than {}", kMaxDepth));
  if (!lua_checkstack(L, 8)) throw Error("json_decode: out of Lua stack");
  switch (value.type()) {
    case json::value_t::null:
    case json::value_t::discarded:
      lua_pushnil(L);
      return;
    case json::value_t::boolean:
      lua_pushboolean(L, value.get<bool>());
      return;
    case json::value_t::number_integer:
    case json::value_t::number_unsigned:
      lua_pushinteger(L, value.get<std::int64_t>());
      return;
    case json::value_t::number_float:
      lua_pushnumber(L, value.get<double>());
      return;
    case json::value_t::string: {
      const auto& text = value.get_ref<const std::string&>();
      lua_pushlstring(L, text.data(), text.size());
      return;
    }
    case json::value_t::array: {
      lua_createtable(L, static_cast<int>(value.size()), 0);
      lua_Integer i = 0;
      for (const json& item : value) {
        pushJson(L, item, depth + 1);
        lua_rawseti(L, -2, ++i);
      }
      return;
    }
    case json::value_t::object:
    case json::value_t::binary:
      lua_createtable(L, 0, static_cast<int>(value.size()));
      for (const auto& [key, item] : value.items()) {
        pushJson(L, item, depth + 1);
        lua_setfield(L, -2, key.c_str());
      }
      return;
  }
}

constexpr int kMaxIndent = 16;

// graspkit.json_encode(value [, {indent = n}]) -> text
int encode(lua_State* L) {
  const OptionsTable options(L, 2, {"indent"});
  const int indent = options.integer("indent", -1);
  // Each nesting level repeats the indent: a large one multiplies the text beyond any memory.
  if (indent < -1 || indent > kMaxIndent) {
    throw ArgumentError(
        L, 2,
        fmt::format("option 'indent' must be -1 (one line) .. {}, got {}", kMaxIndent, indent));
  }
  std::string text;
  try {
    text = toJson(L, 1, 0, "value").dump(indent);
  } catch (const json::type_error&) {
    // The one way dump fails: a string whose bytes are not UTF-8, which JSON cannot hold.
    throw ArgumentError(L, 1, "a string in the value is not UTF-8 text, which JSON cannot hold");
  }
  lua_pushlstring(L, text.data(), text.size());
  return 1;
}

// graspkit.json_decode(text) -> value (JSON null becomes nil)
int decode(lua_State* L) {
  const std::string text = toString(L, 1);
  json value;
  try {
    value = json::parse(text);
  } catch (const json::parse_error& e) {
    throw Error(fmt::format("json_decode: {}", e.what()));
  }
  pushJson(L, value, 0);  // null becomes nil
  return 1;
}

}  // namespace

json luaToJson(lua_State* L, int index) {
  return toJson(L, index, 0, "value");
}

void openJsonFunctions(lua_State* L) {
  const luaL_Reg functions[] = {
      {"json_encode", guarded<encode>},
      {"json_decode", guarded<decode>},
      {nullptr, nullptr},
  };
  luaL_setfuncs(L, functions, 0);
}

}  // namespace graspkit::lua
