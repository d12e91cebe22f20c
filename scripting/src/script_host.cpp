#include "graspkit/lua/script_host.hpp"

#include <fmt/format.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <optional>

#include "graspkit/base/error.hpp"
#include "graspkit/base/input_file.hpp"
#include "json_value.hpp"
#include "lua_api.hpp"
#include "module.hpp"
#include "script_context.hpp"
#include "time_limit.hpp"

namespace graspkit::lua {
namespace {

namespace fs = std::filesystem;

// The error value os.exit raises: a unique address, so no script value can be mistaken for it.
char exit_sentinel;

// print() writing to stderr, for --json (stdout carries the result).
int printToStderr(lua_State* L) {
  const int count = lua_gettop(L);
  for (int i = 1; i <= count; ++i) {
    std::size_t length = 0;
    const char* text = luaL_tolstring(L, i, &length);
    if (i > 1) std::fputc('\t', stderr);
    std::fwrite(text, 1, length, stderr);
    lua_pop(L, 1);
  }
  std::fputc('\n', stderr);
  std::fflush(stderr);
  return 0;
}

int exitScript(lua_State* L) {
  int status = 0;
  if (lua_isboolean(L, 1)) {
    status = lua_toboolean(L, 1) ? 0 : 1;
  } else if (!lua_isnoneornil(L, 1)) {
    const lua_Integer n = luaL_checkinteger(L, 1);
    // A process exit status is one byte: 256 would exit 0, a failure reported as success.
    luaL_argcheck(L, n >= 0 && n <= 255, 1, "exit status must be 0..255");
    status = static_cast<int>(n);
  }
  scriptContext(L).exitStatus = status;
  lua_pushlightuserdata(L, &exit_sentinel);
  return lua_error(L);
}

int traceback(lua_State* L) {
  if (lua_touserdata(L, 1) == &exit_sentinel) return 1;
  const char* message = lua_tostring(L, 1);
  if (message == nullptr) {
    message = luaL_tolstring(L, 1, nullptr);  // an error value that is not a string
  }
  luaL_traceback(L, L, message, 1);
  return 1;
}

std::vector<fs::path> modelRoots(const LoadOptions& load) {
  std::vector<fs::path> roots = load.roots;
  if (load.useEnvironment) {
    for (const char* name : {"GRASPKIT_ROOT", "GRASPIT"}) {
      if (const char* value = std::getenv(name); value != nullptr && *value != '\0') {
        roots.emplace_back(value);
      }
    }
  }
  for (fs::path& root : roots) root = fs::absolute(root);
  return roots;
}

PathPolicy makePolicy(const ScriptContext& context) {
  const SandboxOptions& sandbox = context.options.sandbox;
  if (sandbox.unsafe) return PathPolicy::unrestricted();
  std::vector<fs::path> readable = {context.scriptFolder};
  readable.insert(readable.end(), sandbox.allowRead.begin(), sandbox.allowRead.end());
  readable.insert(readable.end(), context.modelRoots.begin(), context.modelRoots.end());
  std::vector<fs::path> writable = {context.scriptFolder};
  writable.insert(writable.end(), sandbox.allowWrite.begin(), sandbox.allowWrite.end());
  return PathPolicy(std::move(readable), std::move(writable));
}

void setArgTable(lua_State* L, const ScriptContext& context) {
  lua_createtable(L, static_cast<int>(context.options.args.size()), 1);
  lua_pushstring(L, context.script.string().c_str());
  lua_rawseti(L, -2, 0);
  for (std::size_t i = 0; i < context.options.args.size(); ++i) {
    lua_pushstring(L, context.options.args[i].c_str());
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
  lua_setglobal(L, "arg");
}

void loadModule(lua_State* L) {
  // require("graspkit") and the global `graspkit` are the same table.
  luaL_requiref(L, "graspkit", openGraspkitModule, 1);
  lua_pop(L, 1);
}

}  // namespace

struct ScriptHost::Context : ScriptContext {};

ScriptContext& scriptContext(lua_State* L) {
  return **static_cast<ScriptContext**>(lua_getextraspace(L));
}

fs::path ScriptContext::inputPath(const std::string& name) const {
  fs::path file(name);
  if (file.is_relative()) {
    std::vector<fs::path> candidates = {fs::current_path() / file, scriptFolder / file};
    for (const fs::path& root : modelRoots) candidates.push_back(root / file);
    file = candidates.front();
    for (const fs::path& candidate : candidates) {
      // A place the script may not read is passed over unlooked-at: whether a file exists
      // outside its folders is not the script's to learn.
      std::error_code ec;
      if (paths.mayRead(candidate) && fs::exists(candidate, ec)) {
        file = candidate;
        break;
      }
    }
  }
  paths.checkRead(file);
  return file;
}

fs::path ScriptContext::outputPath(const std::string& name) const {
  fs::path file = fs::absolute(fs::path(name));
  paths.checkWrite(file);
  return file;
}

ScriptHost::ScriptHost(const fs::path& script, ScriptOptions options)
    : context_(std::make_unique<Context>()) {
  std::error_code ec;
  if (!fs::is_regular_file(script, ec)) {
    throw Error(SourceLocation{script.string()}, "no such script file");
  }
  context_->options = std::move(options);
  context_->script = fs::absolute(script);
  context_->scriptFolder = context_->script.parent_path();
  context_->modelRoots = modelRoots(context_->options.load);
  context_->paths = makePolicy(*context_);

  context_->memory.limit = context_->options.memoryLimitBytes.value_or(0);
  L_ = lua_newstate(limitedAllocate, &context_->memory);
  if (L_ == nullptr) throw Error("cannot create a Lua state (out of memory)");
  *static_cast<ScriptContext**>(lua_getextraspace(L_)) = context_.get();
  luaL_openlibs(L_);
  if (context_->options.timeoutSeconds) installTimeLimit(L_);  // before any coroutine exists
  if (context_->options.sandbox.unsafe) {
    // Lua modules beside the script are found with or without the sandbox.
    lua_getglobal(L_, "package");
    lua_pushstring(L_, (context_->scriptFolder / "?.lua").c_str());
    lua_pushstring(L_, ";");
    lua_getfield(L_, -3, "path");
    lua_concat(L_, 3);
    lua_setfield(L_, -2, "path");
    lua_pop(L_, 1);
  } else {
    applySandbox(L_, context_->paths, {context_->scriptFolder});
  }
  if (context_->options.printToStderr) {
    lua_pushcfunction(L_, printToStderr);
    lua_setglobal(L_, "print");
  }
  lua_getglobal(L_, "os");
  lua_pushcfunction(L_, exitScript);
  lua_setfield(L_, -2, "exit");
  lua_pop(L_, 1);
  loadModule(L_);
  setArgTable(L_, *context_);
}

ScriptHost::~ScriptHost() {
  if (L_ != nullptr) lua_close(L_);
}

const fs::path& ScriptHost::script() const {
  return context_->script;
}

const PathPolicy& ScriptHost::pathPolicy() const {
  return context_->paths;
}

ScriptOutcome ScriptHost::protectedCall(int nargs, int nresults) {
  const int function = lua_gettop(L_) - nargs;
  lua_pushcfunction(L_, traceback);
  lua_insert(L_, function);
  // A call made from inside another keeps the earlier of the two deadlines.
  const auto outer_deadline = context_->deadline;
  const bool outer_reached = context_->timeLimitReached;
  std::optional<Watchdog> watchdog;  // for a library call no hook can interrupt
  if (const auto& limit = context_->options.timeoutSeconds) {
    auto deadline = std::chrono::steady_clock::now() +
                    std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                        std::chrono::duration<double>(*limit));
    if (outer_deadline && *outer_deadline < deadline) deadline = *outer_deadline;
    context_->deadline = deadline;
    if (context_->options.exitProcessWhenStuck) watchdog.emplace(deadline, *limit);
  }
  context_->timeLimitReached = false;
  context_->exitStatus.reset();
  context_->memory.refused = false;
  // Whatever the engine reads for the script (the geometry a model file names, a planner's
  // state file) is subject to the script's read policy, not only the file the script named.
  std::optional<ScopedReadGuard> readGuard;
  if (context_->paths.restricted())
    readGuard.emplace([&paths = context_->paths](const fs::path& file) { paths.checkRead(file); });
  int status = lua_pcall(L_, nargs, nresults, function);
  readGuard.reset();
  watchdog.reset();
  const bool timed_out =
      context_->timeLimitReached || (status != LUA_OK && context_->deadline &&
                                     std::chrono::steady_clock::now() >= *context_->deadline);
  context_->timeLimitReached = outer_reached || context_->timeLimitReached;
  context_->deadline = outer_deadline;
  if (context_->options.timeoutSeconds) resetTimeLimitHook(L_);
  if (timed_out && status == LUA_OK) {
    // The script caught the limit's error (coroutine.resume does) and finished: still a timeout.
    lua_settop(L_, function);
    lua_pushliteral(L_, "the script caught the time limit's error");
    status = LUA_ERRRUN;
  }
  lua_remove(L_, function);

  ScriptOutcome outcome;
  if (status == LUA_OK) return outcome;
  if (!timed_out && lua_touserdata(L_, -1) == &exit_sentinel) {
    lua_pop(L_, 1);
    outcome.exitStatus = context_->exitStatus.value_or(0);
    outcome.ok = outcome.exitStatus == 0;
    if (!outcome.ok) outcome.message = fmt::format("os.exit({})", outcome.exitStatus);
    return outcome;
  }
  outcome.ok = false;
  outcome.exitStatus = 1;
  outcome.timedOut = timed_out;
  const char* message = lua_tostring(L_, -1);
  outcome.message = message != nullptr ? message : "(error object is not a string)";
  lua_pop(L_, 1);
  if (status == LUA_ERRMEM && context_->memory.refused) {
    outcome.message +=
        fmt::format(" (the script's memory limit is {} MiB; --memory raises it, 0 lifts it)",
                    context_->memory.limit >> 20);
  }
  if (timed_out && outcome.message.find("--timeout") == std::string::npos) {
    // The script caught the limit's error, or the limit struck inside a library call.
    outcome.message = timeLimitMessage(*context_->options.timeoutSeconds) + "\n" + outcome.message;
  }
  return outcome;
}

ScriptOutcome ScriptHost::run(int nresults) {
  const std::string name = context_->script.string();
  if (luaL_loadfilex(L_, name.c_str(), "t") != LUA_OK) {
    ScriptOutcome outcome{false, 1, false, lua_tostring(L_, -1)};
    lua_pop(L_, 1);
    return outcome;
  }
  return protectedCall(0, nresults);
}

std::string ScriptHost::toJson(int index, int indent) {
  try {
    return luaToJson(L_, index).dump(indent);
  } catch (const Error& e) {  // named after the script: the run is over, its lines are not
    throw Error(SourceLocation{context_->script.string()},
                fmt::format("the value the script returns: {}", e.what()));
  }
}

ScriptOutcome ScriptHost::runString(const std::string& source, const std::string& chunk_name) {
  const std::string chunk = "=" + chunk_name;
  if (luaL_loadbufferx(L_, source.data(), source.size(), chunk.c_str(), "t") != LUA_OK) {
    ScriptOutcome outcome{false, 1, false, lua_tostring(L_, -1)};
    lua_pop(L_, 1);
    return outcome;
  }
  return protectedCall(0, 0);
}

}  // namespace graspkit::lua
