// Lua scenarios, run as `graspkit run` runs them (same module, same sandbox).

#include <cmath>

#include <fmt/format.h>

#include "c_api_support.hpp"
#include "graspkit/lua/script_host.hpp"

using namespace graspkit;
using namespace graspkit::c_api;

extern "C" {

graspkit_status graspkit_run_script(const char* path, const graspkit_script_options* options,
                                    int* exit_status) {
  return guarded([&] {
    require(path, "path");
    require(exit_status, "exit_status");
    lua::ScriptOptions script;
    if (options) {
      if (options->root_count > 0) require(options->roots, "options->roots");
      for (std::size_t i = 0; i < options->root_count; ++i)
        script.load.roots.emplace_back(require(options->roots[i], "options->roots[i]"));
      if (options->arg_count > 0) require(options->args, "options->args");
      for (std::size_t i = 0; i < options->arg_count; ++i)
        script.args.emplace_back(require(options->args[i], "options->args[i]"));
      if (std::isnan(options->timeout_seconds) || options->timeout_seconds < 0)
        throw Error(fmt::format("timeout_seconds {} is not a duration", options->timeout_seconds));
      if (options->timeout_seconds > 0) script.timeoutSeconds = options->timeout_seconds;
      script.sandbox.unsafe = options->unsafe != 0;
    }
    // A host decides for itself whether a stuck script may end its process: never here.
    script.exitProcessWhenStuck = false;
    lua::ScriptHost host(path, std::move(script));
    const lua::ScriptOutcome outcome = host.run();
    const bool exited = outcome.message.starts_with("os.exit");
    if (outcome.ok || (exited && !outcome.timedOut)) {
      *exit_status = outcome.ok ? 0 : outcome.exitStatus;
      return;
    }
    *exit_status = outcome.timedOut ? 124 : outcome.exitStatus;
    throw Failure{GRASPKIT_ERROR_SCRIPT, outcome.message};
  });
}

}  // extern "C"
