#pragma once
// The --timeout limit of a script's calls. A count hook checks the clock every few thousand VM
// instructions and, past the deadline, raises an error at every instruction of the thread, so
// no loop, pcall or coroutine outlives it. Lua runs some code with hooks switched off: an xpcall
// message handler or a coroutine's __close after an error the hook raised; wrappers of xpcall,
// coroutine.wrap and coroutine.close keep such code from running once the limit is reached. A
// library call that never returns to the VM (a pathological string pattern) is beyond any hook:
// a watchdog thread ends the process when a call outlives its deadline by kWatchdogGrace.

#include <chrono>
#include <condition_variable>
#include <mutex>
#include <string>
#include <thread>

#include <lua.hpp>

namespace graspkit::lua {

// The exit status of a process the watchdog ends: timeout(1)'s, and `graspkit run`'s on timeout.
inline constexpr int kTimedOutExitStatus = 124;
inline constexpr std::chrono::milliseconds kWatchdogGrace{1000};

// "time limit of 2 s exceeded (--timeout 2)"
std::string timeLimitMessage(double seconds);

// Installs the hook and the wrappers on a fresh state, before any coroutine exists: every thread
// inherits the hook of the thread that creates it, so all carry it. The state's ScriptContext
// holds the deadline the hook checks (none: the hook returns at once).
void installTimeLimit(lua_State* L);

// After a call: puts the main thread's hook back to its usual interval.
void resetTimeLimitHook(lua_State* L);

// Ends the process with kTimedOutExitStatus and a message on stderr unless destroyed before
// `deadline` + kWatchdogGrace.
class Watchdog {
 public:
  Watchdog(std::chrono::steady_clock::time_point deadline, double seconds);
  ~Watchdog();
  Watchdog(const Watchdog&) = delete;
  Watchdog& operator=(const Watchdog&) = delete;

 private:
  std::mutex mutex_;
  std::condition_variable stopped_;
  bool done_ = false;
  std::thread thread_;
};

}  // namespace graspkit::lua
