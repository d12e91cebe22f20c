#include "support/script_flags.hpp"

#include <unistd.h>

namespace graspkit::cli {

void addScriptFlags(CLI::App& command, ScriptFlags& flags) {
  command
      .add_option("--allow-read", flags.allowRead,
                  "Folder the script may also read below (repeatable)")
      ->check(CLI::ExistingDirectory)
      ->allow_extra_args(false);  // one folder per flag, so the script is not taken for one
  command
      .add_option("--allow-write", flags.allowWrite,
                  "Folder the script may also write (and read) below (repeatable)")
      ->check(CLI::ExistingDirectory)
      ->allow_extra_args(false);
  command.add_flag("--unsafe", flags.unsafe,
                   "No sandbox: full io and os libraries, C modules, any file");
  command.add_option("--timeout", flags.timeout, "Stop a script after this many seconds")
      ->check(CLI::PositiveNumber);
  command
      .add_option("--memory", flags.memoryMiB,
                  "Most memory the script's Lua heap may hold, MiB (0: no limit)")
      ->capture_default_str()
      ->check(CLI::Range(0, 1 << 22));
  addLoadFlags(command, flags.load);
}

lua::ScriptOptions scriptOptions(const ScriptFlags& flags) {
  lua::ScriptOptions options;
  options.sandbox.unsafe = flags.unsafe;
  options.sandbox.allowRead = flags.allowRead;
  options.sandbox.allowWrite = flags.allowWrite;
  options.timeoutSeconds = flags.timeout;
  options.memoryLimitBytes = static_cast<std::size_t>(flags.memoryMiB) << 20;
  options.exitProcessWhenStuck = true;  // --timeout is a promise to the user: keep it
  options.load = flags.load.options();
  return options;
}

}  // namespace graspkit::cli
