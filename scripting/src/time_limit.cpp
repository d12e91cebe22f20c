#include "time_limit.hpp"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>

#include "script_context.hpp"

namespace graspkit::lua {
namespace {

// How often (in VM instructions) the clock is read: cheap, and a tight loop still stops within
// milliseconds of the limit.
constexpr int kHookInterval = 10000;

// Registry key of the set (weak keys) of coroutines the limit stopped.
char stopped_threads_key;

void timeLimitHook(lua_State* L, lua_Debug*);

constexpr const char* kTimeLimitFormat = "time limit of %g s exceeded (--timeout %g)";

// Formatted into a plain array: no C++ object may be alive when pushing raises.
void pushTimeLimitMessage(lua_State* L) {
  const double seconds = *scriptContext(L).options.timeoutSeconds;
  char message[96];
  std::snprintf(message, sizeof message, kTimeLimitFormat, seconds, seconds);
  lua_pushstring(L, message);
}

void setHookInterval(lua_State* L, int instructions) {
  lua_sethook(L, timeLimitHook, LUA_MASKCOUNT, instructions);
}

// An error raised in a hook leaves hooks switched off in its thread until a pcall catches it. In
// a coroutine none may: then the coroutine's __close handlers, run when it is closed, would be
// beyond the limit's reach. So the coroutines the limit stops are remembered and never closed.
void markStopped(lua_State* L) {
  lua_rawgetp(L, LUA_REGISTRYINDEX, &stopped_threads_key);
  lua_pushthread(L);
  lua_pushboolean(L, 1);
  lua_rawset(L, -3);
  lua_pop(L, 1);
}

bool wasStopped(lua_State* L, int thread_index) {
  lua_rawgetp(L, LUA_REGISTRYINDEX, &stopped_threads_key);
  lua_pushvalue(L, thread_index);
  const bool stopped = lua_rawget(L, -2) != LUA_TNIL;
  lua_pop(L, 2);
  return stopped;
}

lua_State* mainThread(lua_State* L) {
  lua_rawgeti(L, LUA_REGISTRYINDEX, LUA_RIDX_MAINTHREAD);
  lua_State* main = lua_tothread(L, -1);
  lua_pop(L, 1);
  return main;
}

void timeLimitHook(lua_State* L, lua_Debug*) {
  ScriptContext& context = scriptContext(L);
  if (!context.deadline || std::chrono::steady_clock::now() < *context.deadline) {
    // A thread left checking every instruction by an earlier, stopped call goes back to normal.
    if (lua_gethookcount(L) != kHookInterval) setHookInterval(L, kHookInterval);
    return;
  }
  // From now on every instruction of this thread and of the main one raises, so neither a pcall
  // nor a coroutine.resume lets the script go on; the flag fails the call even if it ends.
  context.timeLimitReached = true;
  setHookInterval(L, 1);
  if (lua_State* main = mainThread(L); main != L) {
    setHookInterval(main, 1);
    markStopped(L);
  }
  luaL_where(L, 0);  // level 0 in a hook: the Lua function it interrupted
  pushTimeLimitMessage(L);
  lua_concat(L, 2);
  lua_error(L);
}

int passResults(lua_State* L, int, lua_KContext) {
  return lua_gettop(L);
}

// The message handler handed to the real xpcall. Once the limit is reached the script's handler
// is skipped: after an error the hook raised it would run with hooks switched off.
int limitedHandler(lua_State* L) {
  if (scriptContext(L).timeLimitReached) return 1;  // the error as it is
  lua_pushvalue(L, lua_upvalueindex(1));
  lua_insert(L, 1);
  lua_call(L, lua_gettop(L) - 1, 1);
  return 1;
}

// xpcall(f, handler, ...)
int limitedXpcall(lua_State* L) {
  luaL_checktype(L, 2, LUA_TFUNCTION);
  lua_pushvalue(L, 2);
  lua_pushcclosure(L, limitedHandler, 1);
  lua_replace(L, 2);
  lua_pushvalue(L, lua_upvalueindex(1));
  lua_insert(L, 1);
  lua_callk(L, lua_gettop(L) - 1, LUA_MULTRET, 0, passResults);  // still yieldable
  return lua_gettop(L);
}

// The function coroutine.wrap returns: resumes its coroutine, passing values both ways and
// errors up. Lua's own closes a coroutine that failed (its __close handlers run); not one the
// limit stopped.
int resumeWrapped(lua_State* L) {
  lua_State* co = lua_tothread(L, lua_upvalueindex(1));
  const int nargs = lua_gettop(L);
  if (lua_status(co) == LUA_OK && lua_gettop(co) == 0) {
    return luaL_error(L, "cannot resume dead coroutine");
  }
  if (!lua_checkstack(co, nargs)) return luaL_error(L, "too many arguments to resume");
  lua_xmove(L, co, nargs);
  int nresults = 0;
  const int status = lua_resume(co, L, nargs, &nresults);
  if (status == LUA_OK || status == LUA_YIELD) {
    if (!lua_checkstack(L, nresults + 1)) {
      lua_pop(co, nresults);
      return luaL_error(L, "too many results to resume");
    }
    lua_xmove(co, L, nresults);
    return nresults;
  }
  const int co_status = lua_status(co);
  if (co_status != LUA_OK && co_status != LUA_YIELD && !wasStopped(L, lua_upvalueindex(1))) {
    lua_resetthread(co);  // leaves the error on top
  }
  lua_xmove(co, L, 1);
  if (status != LUA_ERRMEM && lua_type(L, -1) == LUA_TSTRING) {
    luaL_where(L, 1);
    lua_insert(L, -2);
    lua_concat(L, 2);
  }
  return lua_error(L);
}

// coroutine.wrap(f)
int limitedWrap(lua_State* L) {
  luaL_checktype(L, 1, LUA_TFUNCTION);
  lua_State* co = lua_newthread(L);  // inherits this thread's hook
  lua_pushvalue(L, 1);
  lua_xmove(L, co, 1);
  lua_pushcclosure(L, resumeWrapped, 1);
  return 1;
}

// coroutine.close(co): a coroutine the limit stopped stays as it is, its __close handlers unrun.
int limitedClose(lua_State* L) {
  if (lua_type(L, 1) == LUA_TTHREAD && wasStopped(L, 1)) {
    lua_pushboolean(L, 0);
    pushTimeLimitMessage(L);
    return 2;
  }
  lua_pushvalue(L, lua_upvalueindex(1));
  lua_insert(L, 1);
  lua_call(L, lua_gettop(L) - 1, LUA_MULTRET);
  return lua_gettop(L);
}

}  // namespace

std::string timeLimitMessage(double seconds) {
  char message[96];
  std::snprintf(message, sizeof message, kTimeLimitFormat, seconds, seconds);
  return message;
}

void installTimeLimit(lua_State* L) {
  lua_newtable(L);
  lua_newtable(L);
  lua_pushliteral(L, "k");
  lua_setfield(L, -2, "__mode");
  lua_setmetatable(L, -2);
  lua_rawsetp(L, LUA_REGISTRYINDEX, &stopped_threads_key);

  lua_getglobal(L, "xpcall");
  lua_pushcclosure(L, limitedXpcall, 1);
  lua_setglobal(L, "xpcall");
  lua_getglobal(L, "coroutine");
  lua_pushcfunction(L, limitedWrap);
  lua_setfield(L, -2, "wrap");
  lua_getfield(L, -1, "close");
  lua_pushcclosure(L, limitedClose, 1);
  lua_setfield(L, -2, "close");
  lua_pop(L, 1);

  setHookInterval(L, kHookInterval);
}

void resetTimeLimitHook(lua_State* L) {
  setHookInterval(L, kHookInterval);
}

Watchdog::Watchdog(std::chrono::steady_clock::time_point deadline, double seconds)
    : thread_([this, deadline, seconds] {
        std::unique_lock lock(mutex_);
        if (stopped_.wait_until(lock, deadline + kWatchdogGrace, [this] { return done_; })) return;
        // The script's thread may hold stdio's locks (stuck writing to a full pipe): write(2).
        const std::string message =
            "graspkit: error: " + timeLimitMessage(seconds) +
            "; the script is stuck in a call that cannot be interrupted, ending the process\n";
        [[maybe_unused]] const ssize_t written = ::write(2, message.data(), message.size());
        std::_Exit(kTimedOutExitStatus);
      }) {}

Watchdog::~Watchdog() {
  {
    std::lock_guard lock(mutex_);
    done_ = true;
  }
  stopped_.notify_one();
  thread_.join();
}

}  // namespace graspkit::lua
