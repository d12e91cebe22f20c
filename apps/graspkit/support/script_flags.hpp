#pragma once
// The flags `graspkit run` and `graspkit test` share: the sandbox, the time limit, model roots.

#include <filesystem>
#include <optional>
#include <vector>

#include <CLI/CLI.hpp>

#include "support/load_flags.hpp"

#include "graspkit/lua/script_host.hpp"

namespace graspkit::cli {

struct ScriptFlags {
  std::vector<std::filesystem::path> allowRead;
  std::vector<std::filesystem::path> allowWrite;
  bool unsafe = false;
  std::optional<double> timeout;  // seconds
  // MiB of Lua heap (0: no limit); the default is ScriptOptions' 1 GiB.
  std::size_t memoryMiB = lua::ScriptOptions::kDefaultMemoryLimitBytes >> 20;
  LoadFlags load;
};

void addScriptFlags(CLI::App& command, ScriptFlags& flags);

// The host options for these flags (the caller connects the progress reporter).
lua::ScriptOptions scriptOptions(const ScriptFlags& flags);

// Exit status for a script that timed out, as timeout(1) uses.
inline constexpr int kTimedOutStatus = 124;

}  // namespace graspkit::cli
