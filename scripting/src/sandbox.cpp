#include "graspkit/lua/sandbox.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <optional>

#include <lua.hpp>

#include "graspkit/base/error.hpp"
#include "graspkit/base/input_file.hpp"
#include "lua_api.hpp"

namespace graspkit::lua {
namespace {

namespace fs = std::filesystem;

// ---------------------------------------------------------------------------------------------
// Paths

// Symbolic links followed before a path is given up as a loop (Linux's own limit is 40).
constexpr int kMaxSymlinks = 40;

// The path the operating system would reach for `file`: absolute, every symbolic link followed
// (the last component too, even when its target does not exist yet, since opening it for writing
// would create the target), `.` and `..` applied to the resolved folder. Empty for a link loop.
fs::path resolved(const fs::path& file) {
  std::error_code ec;
  const fs::path absolute = fs::absolute(file, ec);
  if (ec) return {};
  fs::path result = absolute.root_path();
  std::vector<fs::path> pending;  // components still to walk, the next one last
  for (const fs::path& part : absolute.relative_path()) pending.insert(pending.begin(), part);
  int links = 0;
  while (!pending.empty()) {
    const fs::path part = pending.back();
    pending.pop_back();
    if (part.empty() || part == ".") continue;
    if (part == "..") {
      result = result.parent_path();  // `result` holds no links, so this is the real parent
      continue;
    }
    const fs::path next = result / part;
    if (!fs::is_symlink(fs::symlink_status(next, ec))) {
      result = next;
      continue;
    }
    const fs::path target = fs::read_symlink(next, ec);
    if (ec || ++links > kMaxSymlinks) return {};
    if (target.is_absolute()) result = target.root_path();
    const fs::path relative = target.relative_path();
    for (auto it = relative.end(); it != relative.begin();) pending.push_back(*--it);
  }
  return result;
}

bool isBelow(const fs::path& file, const fs::path& folder) {
  auto f = file.begin();
  for (auto d = folder.begin(); d != folder.end(); ++d, ++f) {
    if (d->empty()) continue;  // a trailing separator
    if (f == file.end() || *f != *d) return false;
  }
  return true;
}

bool isBelowAny(const fs::path& file, const std::vector<fs::path>& folders) {
  const fs::path path = resolved(file);
  if (path.empty()) return false;
  for (const fs::path& folder : folders) {
    if (isBelow(path, folder)) return true;
  }
  return false;
}

void addFolder(std::vector<fs::path>& folders, const fs::path& folder) {
  if (std::find(folders.begin(), folders.end(), folder) == folders.end()) {
    folders.push_back(folder);
  }
}

std::vector<fs::path> resolvedFolders(const std::vector<fs::path>& folders) {
  std::vector<fs::path> result;
  for (const fs::path& folder : folders) {
    // An empty path would resolve to nothing and then contain everything.
    if (folder.empty()) continue;
    if (fs::path path = resolved(folder); !path.empty()) addFolder(result, path);
  }
  return result;
}

std::string listFolders(const std::vector<fs::path>& folders) {
  std::string list;
  for (const fs::path& folder : folders) list += (list.empty() ? "" : ", ") + folder.string();
  return list.empty() ? "none" : list;
}

// "" when `file` is what it looks like; otherwise that a symbolic link takes it elsewhere. The
// target itself is never named: it lies outside the script's folders, where a script may not look.
std::string resolvesTo(const fs::path& file) {
  std::error_code ec;
  const fs::path plain = fs::absolute(file, ec).lexically_normal();
  const fs::path real = resolved(file);
  if (real.empty()) return "; the path is a loop of symbolic links";
  return real == plain ? "" : "; a symbolic link on the path leads outside";
}

}  // namespace

PathPolicy::PathPolicy(std::vector<fs::path> readable, std::vector<fs::path> writable)
    : restricted_(true),
      readable_(resolvedFolders(readable)),
      writable_(resolvedFolders(writable)) {
  for (const fs::path& folder : writable_) addFolder(readable_, folder);
}

namespace {

void refuseNul(const fs::path& file) {
  if (!holdsNul(file)) return;
  std::string shown = file.string();
  std::replace(shown.begin(), shown.end(), '\0', '?');
  throw Error(SourceLocation{shown}, "sandbox: the path holds a NUL byte");
}

}  // namespace

// A path with a NUL byte is refused even unrestricted: the operating system would open only the
// part before the NUL, which is not the path that was checked.
bool PathPolicy::mayRead(const fs::path& file) const {
  return !holdsNul(file) && (!restricted_ || isBelowAny(file, readable_));
}

bool PathPolicy::mayWrite(const fs::path& file) const {
  return !holdsNul(file) && (!restricted_ || isBelowAny(file, writable_));
}

void PathPolicy::checkRead(const fs::path& file) const {
  refuseNul(file);
  if (mayRead(file)) return;
  throw Error(SourceLocation{file.string()},
              fmt::format("sandbox: reading is not allowed outside {} (use --allow-read DIR or "
                          "--unsafe){}",
                          listFolders(readable_), resolvesTo(file)));
}

void PathPolicy::checkWrite(const fs::path& file) const {
  refuseNul(file);
  if (mayWrite(file)) return;
  throw Error(SourceLocation{file.string()},
              fmt::format("sandbox: writing is not allowed outside {} (use --allow-write DIR or "
                          "--unsafe){}",
                          listFolders(writable_), resolvesTo(file)));
}

namespace {

// ---------------------------------------------------------------------------------------------
// The library functions that replace the standard ones. Each is a C closure with two upvalues:
// the PathPolicy (light userdata) and the standard function it guards, which it calls once the
// arguments pass. Lua errors longjmp, so C++ objects live only inside the checks, never across a
// call that may raise.

enum class Access { read, write };

const PathPolicy& policyOf(lua_State* L) {
  return *static_cast<const PathPolicy*>(lua_touserdata(L, lua_upvalueindex(1)));
}

// Calls the guarded standard function with this call's arguments; returns all its results.
int callStandard(lua_State* L) {
  lua_pushvalue(L, lua_upvalueindex(2));
  lua_insert(L, 1);
  lua_call(L, lua_gettop(L) - 1, LUA_MULTRET);
  return lua_gettop(L);
}

// The file name at `arg`, as the standard functions read it (a number counts); null for anything
// else, which the standard function then rejects with its own message.
const char* fileArgument(lua_State* L, int arg) {
  const int type = lua_type(L, arg);
  return type == LUA_TSTRING || type == LUA_TNUMBER ? lua_tostring(L, arg) : nullptr;
}

// True when the policy lets `function` touch `file`; otherwise pushes the refusal ("io.open:
// /etc/passwd: sandbox: reading is not allowed outside ...") for raiseError.
bool permitted(lua_State* L, const char* function, const char* file, Access access) {
  try {
    if (access == Access::read) {
      policyOf(L).checkRead(file);
    } else {
      policyOf(L).checkWrite(file);
    }
    return true;
  } catch (const std::exception& e) {
    lua_pushfstring(L, "%s: %s", function, e.what());
  }
  return false;
}

// Code read from standard input would bypass every check on files.
int refuseStandardInput(lua_State* L, const char* function) {
  lua_pushfstring(L,
                  "%s: sandbox: running code from standard input is not allowed (name a file, or "
                  "use --unsafe)",
                  function);
  return raiseError(L);
}

// Sets argument `mode_arg` of a load function to "t": a binary chunk is never checked by the
// loader and a crafted one can corrupt the VM's memory.
void forceTextMode(lua_State* L, int mode_arg) {
  if (lua_gettop(L) < mode_arg) lua_settop(L, mode_arg);
  lua_pushliteral(L, "t");
  lua_replace(L, mode_arg);
}

// io.open's mode: r, w or a, then an optional +, then any number of b (what C's fopen accepts
// portably, as Lua checks it).
bool isOpenMode(const char* mode) {
  if (*mode == '\0' || std::strchr("rwa", *mode) == nullptr) return false;
  ++mode;
  if (*mode == '+') ++mode;
  return std::strspn(mode, "b") == std::strlen(mode);
}

// The standard function, called from here, would name itself '?' in its argument errors; so
// the arguments of the functions below are checked here first.
int sandboxedOpen(lua_State* L) {
  const char* file = luaL_checkstring(L, 1);
  const char* mode = luaL_optstring(L, 2, "r");
  luaL_argcheck(L, isOpenMode(mode), 2, "invalid mode");
  const Access access = std::strpbrk(mode, "wa+") != nullptr ? Access::write : Access::read;
  if (!permitted(L, "io.open", file, access)) return raiseError(L);
  return callStandard(L);
}

int sandboxedLines(lua_State* L) {
  const char* file = fileArgument(L, 1);  // none: lines of the default input
  if (file != nullptr && !permitted(L, "io.lines", file, Access::read)) return raiseError(L);
  return callStandard(L);
}

int sandboxedInput(lua_State* L) {
  const char* file = fileArgument(L, 1);  // none or a file handle: nothing is opened
  if (file != nullptr && !permitted(L, "io.input", file, Access::read)) return raiseError(L);
  return callStandard(L);
}

int sandboxedOutput(lua_State* L) {
  const char* file = fileArgument(L, 1);
  if (file != nullptr && !permitted(L, "io.output", file, Access::write)) return raiseError(L);
  return callStandard(L);
}

int sandboxedRemove(lua_State* L) {
  const char* file = luaL_checkstring(L, 1);
  if (!permitted(L, "os.remove", file, Access::write)) return raiseError(L);
  return callStandard(L);
}

int sandboxedRename(lua_State* L) {
  const char* from = luaL_checkstring(L, 1);
  const char* to = luaL_checkstring(L, 2);
  for (const char* file : {from, to}) {
    if (!permitted(L, "os.rename", file, Access::write)) return raiseError(L);
  }
  return callStandard(L);
}

int sandboxedLoad(lua_State* L) {
  if (lua_type(L, 1) == LUA_TSTRING && lua_tostring(L, 1)[0] == LUA_SIGNATURE[0]) {
    luaL_pushfail(L);
    lua_pushliteral(L,
                    "load: sandbox: binary chunks are not allowed, only source text (use "
                    "--unsafe)");
    return 2;
  }
  forceTextMode(L, 3);  // a reader function may still hand over bytecode
  return callStandard(L);
}

int sandboxedLoadfile(lua_State* L) {
  const char* file = luaL_optstring(L, 1, nullptr);
  if (file == nullptr) return refuseStandardInput(L, "loadfile");
  if (!permitted(L, "loadfile", file, Access::read)) return raiseError(L);
  forceTextMode(L, 2);
  return callStandard(L);
}

int dofileContinuation(lua_State* L, int, lua_KContext) {
  return lua_gettop(L) - 1;  // everything the chunk returned, above the file name
}

int sandboxedDofile(lua_State* L) {
  const char* file = luaL_optstring(L, 1, nullptr);
  if (file == nullptr) return refuseStandardInput(L, "dofile");
  if (!permitted(L, "dofile", file, Access::read)) return raiseError(L);
  lua_settop(L, 1);
  if (luaL_loadfilex(L, file, "t") != LUA_OK) return lua_error(L);
  lua_callk(L, 0, LUA_MULTRET, 0, dofileContinuation);
  return dofileContinuation(L, LUA_OK, 0);
}

// A table's __gc runs with every hook switched off, so the --timeout limit could not stop it.
int sandboxedSetmetatable(lua_State* L) {
  if (lua_type(L, 2) == LUA_TTABLE) {
    lua_pushliteral(L, "__gc");
    if (lua_rawget(L, 2) != LUA_TNIL) {
      lua_pushliteral(L,
                      "setmetatable: sandbox: __gc metamethods are not allowed (a finalizer runs "
                      "outside the --timeout limit; use --unsafe)");
      return raiseError(L);
    }
    lua_pop(L, 1);
  }
  return callStandard(L);
}

// ---------------------------------------------------------------------------------------------
// Modules: the Lua-file searcher and package.searchpath, restricted to readable files.

struct ModuleSearch {
  std::string found;  // the first readable candidate; empty when none
  std::string tried;  // what was tried, in package.searchpath's wording
};

bool isReadableFile(const std::string& file) {
  std::FILE* stream = std::fopen(file.c_str(), "r");
  if (stream == nullptr) return false;
  std::fclose(stream);
  return true;
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  if (from.empty()) return text;
  for (std::size_t at = text.find(from); at != std::string::npos;
       at = text.find(from, at + to.size())) {
    text.replace(at, from.size(), to);
  }
  return text;
}

// Lua's search of `templates` ("a/?.lua;b/?.lua") for `name`, except that candidates outside the
// readable folders are not even tried, so a script cannot probe for files it may not read.
ModuleSearch searchPath(const PathPolicy& policy, const std::string& name,
                        const std::string& templates, const std::string& separator,
                        const std::string& directory_separator) {
  const std::string path_name = replaced(name, separator, directory_separator);
  ModuleSearch search;
  std::size_t begin = 0;
  while (begin <= templates.size()) {
    std::size_t end = templates.find(';', begin);
    if (end == std::string::npos) end = templates.size();
    const std::string candidate = replaced(templates.substr(begin, end - begin), "?", path_name);
    begin = end + 1;
    if (candidate.empty()) continue;
    if (!search.tried.empty()) search.tried += "\n\t";
    if (!policy.mayRead(candidate)) {
      search.tried += fmt::format("no file '{}' searched: sandbox: outside {}", candidate,
                                  listFolders(policy.readable()));
    } else if (isReadableFile(candidate)) {
      search.found = candidate;
      return search;
    } else {
      search.tried += fmt::format("no file '{}'", candidate);
    }
  }
  return search;
}

// Pushes the file found for module `name`, or the list of what was tried; true when found.
bool pushSearchResult(lua_State* L, const char* name, const char* templates, const char* separator,
                      const char* directory_separator) {
  const ModuleSearch search =
      searchPath(policyOf(L), name, templates, separator, directory_separator);
  lua_pushstring(L, search.found.empty() ? search.tried.c_str() : search.found.c_str());
  return !search.found.empty();
}

// package.searchpath(name, path [, sep [, rep]])
int sandboxedSearchpath(lua_State* L) {
  const char* name = luaL_checkstring(L, 1);
  const char* templates = luaL_checkstring(L, 2);
  const char* separator = luaL_optstring(L, 3, ".");
  const char* directory_separator = luaL_optstring(L, 4, LUA_DIRSEP);
  if (pushSearchResult(L, name, templates, separator, directory_separator)) return 1;
  luaL_pushfail(L);
  lua_insert(L, -2);
  return 2;
}

// package.searchers[2]: a Lua module from package.path, loaded as text. Upvalue 2 is the package
// table, so a script may still point package.path at other readable folders.
int searchLuaModule(lua_State* L) {
  const char* name = luaL_checkstring(L, 1);
  lua_getfield(L, lua_upvalueindex(2), "path");
  const char* templates = lua_tostring(L, -1);
  if (templates == nullptr) return luaL_error(L, "'package.path' must be a string");
  if (!pushSearchResult(L, name, templates, ".", LUA_DIRSEP)) return 1;
  const char* file = lua_tostring(L, -1);
  if (luaL_loadfilex(L, file, "t") != LUA_OK) {
    return luaL_error(L, "error loading module '%s' from file '%s':\n\t%s", name, file,
                      lua_tostring(L, -1));
  }
  lua_insert(L, -2);  // the loader, then the file name as its second argument
  return 2;
}

// ---------------------------------------------------------------------------------------------
// Installing

// Sets field `name` of the table on top to a closure over (policy, the field's current value).
void guardField(lua_State* L, const char* name, lua_CFunction function, const PathPolicy& policy) {
  lua_pushlightuserdata(L, const_cast<PathPolicy*>(&policy));
  lua_getfield(L, -2, name);
  lua_pushcclosure(L, function, 2);
  lua_setfield(L, -2, name);
}

void removeFields(lua_State* L, std::initializer_list<const char*> names) {
  for (const char* name : names) {
    lua_pushnil(L);
    lua_setfield(L, -2, name);
  }
}

void sandboxGlobals(lua_State* L, const PathPolicy& policy) {
  lua_pushglobaltable(L);
  removeFields(L, {"debug"});
  guardField(L, "load", sandboxedLoad, policy);
  guardField(L, "loadfile", sandboxedLoadfile, policy);
  guardField(L, "dofile", sandboxedDofile, policy);
  guardField(L, "setmetatable", sandboxedSetmetatable, policy);
  lua_pop(L, 1);
}

void sandboxIo(lua_State* L, const PathPolicy& policy) {
  lua_getglobal(L, "io");
  removeFields(L, {"popen", "tmpfile"});  // tmpfile: a file outside every allowed folder
  guardField(L, "open", sandboxedOpen, policy);
  guardField(L, "lines", sandboxedLines, policy);
  guardField(L, "input", sandboxedInput, policy);
  guardField(L, "output", sandboxedOutput, policy);
  lua_pop(L, 1);
}

void sandboxOs(lua_State* L, const PathPolicy& policy) {
  lua_getglobal(L, "os");
  removeFields(L, {"execute", "tmpname"});
  guardField(L, "remove", sandboxedRemove, policy);
  guardField(L, "rename", sandboxedRename, policy);
  lua_pop(L, 1);
}

std::string modulePath(const std::vector<fs::path>& module_folders) {
  std::string path;
  for (const fs::path& folder : module_folders) {
    for (const char* pattern : {"?.lua", "?/init.lua"}) {
      if (!path.empty()) path += ';';
      path += (folder / pattern).string();
    }
  }
  return path;
}

void sandboxPackage(lua_State* L, const PathPolicy& policy,
                    const std::vector<fs::path>& module_folders) {
  lua_getglobal(L, "package");
  removeFields(L, {"loadlib"});
  lua_getfield(L, -1, "loaded");
  removeFields(L, {"debug"});
  lua_pop(L, 1);

  lua_pushstring(L, modulePath(module_folders).c_str());
  lua_setfield(L, -2, "path");
  lua_pushliteral(L, "");
  lua_setfield(L, -2, "cpath");

  lua_pushlightuserdata(L, const_cast<PathPolicy*>(&policy));
  lua_pushnil(L);  // no standard function behind it
  lua_pushcclosure(L, sandboxedSearchpath, 2);
  lua_setfield(L, -2, "searchpath");

  // Searchers: package.preload stays; the Lua-file searcher is replaced; both C searchers go.
  lua_getfield(L, -1, "searchers");
  lua_pushlightuserdata(L, const_cast<PathPolicy*>(&policy));
  lua_pushvalue(L, -3);
  lua_pushcclosure(L, searchLuaModule, 2);
  lua_rawseti(L, -2, 2);
  for (lua_Integer i = static_cast<lua_Integer>(lua_rawlen(L, -1)); i > 2; --i) {
    lua_pushnil(L);
    lua_rawseti(L, -2, i);
  }
  lua_pop(L, 2);
}

}  // namespace

void applySandbox(lua_State* L, const PathPolicy& policy,
                  const std::vector<fs::path>& module_folders) {
  sandboxGlobals(L, policy);
  sandboxIo(L, policy);
  sandboxOs(L, policy);
  sandboxPackage(L, policy, module_folders);
}

}  // namespace graspkit::lua
