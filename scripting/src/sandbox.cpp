#include "graspkit/lua/sandbox.hpp"

#include <fmt/format.h>

#include <lua.hpp>

#include "graspkit/error.hpp"

namespace graspkit::lua {
namespace {

namespace fs = std::filesystem;

// `..` and symbolic links resolved in the part of the path that exists.
fs::path resolved(const fs::path& file) {
  std::error_code ec;
  fs::path path = fs::weakly_canonical(fs::absolute(file), ec);
  return ec ? fs::absolute(file).lexically_normal() : path;
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
  for (const fs::path& folder : folders) {
    if (isBelow(path, folder)) return true;
  }
  return false;
}

std::string listFolders(const std::vector<fs::path>& folders) {
  std::string list;
  for (const fs::path& folder : folders) list += (list.empty() ? "" : ", ") + folder.string();
  return list.empty() ? "none" : list;
}

}  // namespace

PathPolicy::PathPolicy(std::vector<fs::path> readable, std::vector<fs::path> writable)
    : restricted_(true) {
  for (const fs::path& folder : writable) writable_.push_back(resolved(folder));
  for (const fs::path& folder : readable) readable_.push_back(resolved(folder));
  readable_.insert(readable_.end(), writable_.begin(), writable_.end());
}

bool PathPolicy::mayRead(const fs::path& file) const {
  return !restricted_ || isBelowAny(file, readable_);
}

bool PathPolicy::mayWrite(const fs::path& file) const {
  return !restricted_ || isBelowAny(file, writable_);
}

void PathPolicy::checkRead(const fs::path& file) const {
  if (mayRead(file)) return;
  throw Error(SourceLocation{file.string()},
              fmt::format("sandbox: reading is not allowed outside {} (use --allow-read DIR or "
                          "--unsafe)",
                          listFolders(readable_)));
}

void PathPolicy::checkWrite(const fs::path& file) const {
  if (mayWrite(file)) return;
  throw Error(SourceLocation{file.string()},
              fmt::format("sandbox: writing is not allowed outside {} (use --allow-write DIR or "
                          "--unsafe)",
                          listFolders(writable_)));
}

void applySandbox(lua_State* L, const PathPolicy& policy,
                  const std::vector<fs::path>& module_folders) {
  (void)policy;
  (void)module_folders;
  lua_pushnil(L);
  lua_setglobal(L, "debug");
  lua_getglobal(L, "os");
  for (const char* name : {"execute", "remove", "rename", "tmpname"}) {
    lua_pushnil(L);
    lua_setfield(L, -2, name);
  }
  lua_pop(L, 1);
  lua_getglobal(L, "io");
  lua_pushnil(L);
  lua_setfield(L, -2, "popen");
  lua_pop(L, 1);
  lua_getglobal(L, "package");
  lua_pushnil(L);
  lua_setfield(L, -2, "loadlib");
  lua_pop(L, 1);
}

}  // namespace graspkit::lua
