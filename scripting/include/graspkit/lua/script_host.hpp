#pragma once
// A Lua 5.4 state that runs one graspkit scenario: the `graspkit` module loaded (a global, and
// through require), the sandbox applied, `arg` filled, and an optional time limit. A host
// program makes one ScriptHost per script; `graspkit run` and `graspkit test` are two such hosts.

#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "graspkit/io/common/load_options.hpp"
#include "graspkit/lua/sandbox.hpp"

struct lua_State;

namespace graspkit::lua {

struct ScriptOptions {
  SandboxOptions sandbox;
  // Wall-clock limit for run() and for each protectedCall(); none when empty.
  std::optional<double> timeoutSeconds;
  // A call into a library function that never returns to Lua (a pathological string pattern,
  // a long engine computation) cannot be stopped by the time limit's hook. With this set, a
  // watchdog thread ends the whole process (status 124, the time-limit message on stderr) one
  // second past the deadline. The command-line program sets it; a host embedding graspkit
  // decides for itself.
  bool exitProcessWhenStuck = false;
  // The most memory the script's Lua heap may hold (tables, strings, closures; engine objects
  // such as worlds live outside it). Past it an allocation fails with Lua's "not enough memory"
  // error. Empty or 0: no limit.
  static constexpr std::size_t kDefaultMemoryLimitBytes = std::size_t{1} << 30;  // 1 GiB
  std::optional<std::size_t> memoryLimitBytes = kDefaultMemoryLimitBytes;
  // Model roots (--root) and the generic robot fallback. The roots are readable in the sandbox
  // and searched for relative model paths.
  LoadOptions load;
  std::vector<std::string> args;  // arg[1], arg[2], ...; arg[0] is the script
  // Where graspkit.progress() and planner:run report: the fraction done (0..1) and a line of
  // text. The host decides how to show it (the command line's ProgressReporter); empty: nowhere.
  std::function<void(double fraction, const std::string& text)> progress;
  // print() writes to stderr, so that stdout carries only a JSON result (`--json`).
  bool printToStderr = false;
};

// How a run ended.
struct ScriptOutcome {
  bool ok = true;
  int exitStatus = 0;     // os.exit(n) sets it; 1 after an error
  bool timedOut = false;  // the time limit ended it
  std::string message;    // the error with its Lua traceback; empty when ok
};

class ScriptHost {
 public:
  // Throws graspkit::Error when the script file does not exist.
  ScriptHost(const std::filesystem::path& script, ScriptOptions options);
  ~ScriptHost();
  ScriptHost(const ScriptHost&) = delete;
  ScriptHost& operator=(const ScriptHost&) = delete;

  // Loads the script and runs it to its end. With nresults > 0, that many of the values the
  // script returns are left on the stack (nil for missing ones) when ok.
  ScriptOutcome run(int nresults = 0);

  // The Lua value at `index` as JSON text (graspkit.json_encode's rules). Throws graspkit::Error
  // for values JSON cannot hold.
  std::string toJson(int index, int indent = 2);

  // Calls the function below its `nargs` arguments on top of the stack, with a traceback on error
  // and the time limit counted from now. Results are left on the stack when ok.
  ScriptOutcome protectedCall(int nargs, int nresults);

  // Runs a chunk of Lua source as if it were part of the script (tests, hosts).
  ScriptOutcome runString(const std::string& source, const std::string& chunk_name);

  lua_State* state() const { return L_; }
  const std::filesystem::path& script() const;
  const PathPolicy& pathPolicy() const;

 private:
  struct Context;
  std::unique_ptr<Context> context_;
  lua_State* L_ = nullptr;
};

}  // namespace graspkit::lua
