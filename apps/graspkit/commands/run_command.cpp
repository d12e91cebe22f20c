// graspkit run: run one Lua scenario script (see docs/lua.md).

#include <fmt/format.h>

#include <iostream>

#include "commands/run_command.hpp"
#include "graspkit/lua/script_host.hpp"
#include "support/argument_checks.hpp"
#include "support/progress_reporter.hpp"

namespace graspkit::cli {

void addRunCommand(CLI::App& app, RunOptions& options) {
  CLI::App* cmd =
      app.add_subcommand("run", "Run a Lua scenario script (arguments after -- go to arg)");
  cmd->add_option("script", options.script, "The .lua script")->required()->check(existingFile());
  cmd->add_option("args", options.args, "Arguments for the script, after --");
  cmd->add_flag("--json", options.json,
                "Print the value the script returns as JSON (print() then goes to stderr)");
  addScriptFlags(*cmd, options.flags);
}

int runRun(const RunOptions& options, bool quiet) {
  ProgressReporter progress(ProgressReporter::forStderr(quiet));
  lua::ScriptOptions script_options = scriptOptions(options.flags);
  script_options.progress = [&progress](double fraction, const std::string& text) {
    if (fraction >= 1.0)
      progress.finish(fraction, text);
    else
      progress.update(fraction, text);
  };
  script_options.args = options.args;
  script_options.printToStderr = options.json;  // stdout carries the JSON value only
  lua::ScriptHost host(options.script, std::move(script_options));
  std::cout.flush();
  const lua::ScriptOutcome outcome = host.run(options.json ? 1 : 0);
  std::fflush(stdout);  // Lua's print writes through C stdio
  if (outcome.ok) {
    if (options.json) std::cout << host.toJson(-1) << "\n";
    return 0;
  }
  if (!outcome.message.empty() && outcome.exitStatus != 0 &&
      !outcome.message.starts_with("os.exit")) {
    std::cerr << "graspkit: error: " << outcome.message << "\n";
  }
  return outcome.timedOut ? kTimedOutStatus : outcome.exitStatus;
}

}  // namespace graspkit::cli
