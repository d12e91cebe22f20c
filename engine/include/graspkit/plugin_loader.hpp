#pragma once
// The plugin loader: finds plugin files on the search path, dlopens them, checks their
// descriptor and commits their factories to its Registry whole or not at all. Loaded plugins
// stay loaded for the life of the process (their code backs the factories).
//
// Search path, in order:
//   1. GRASPKIT_PLUGIN_PATH (colon-separated folders);
//   2. the plugin folder beside the engine library (<libdir>/graspkit/plugins) and beside the
//      running program (<bindir>/../lib/graspkit/plugins), so a build tree and an install both
//      work with no environment variable;
//   3. the folder recorded when the engine was installed.
// A plugin file is any regular `*.so` file in those folders (not their subfolders).

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace graspkit {

class Registry;
enum class FactoryKind;

struct PluginInfo {
  std::filesystem::path file;
  std::string name;  // from the descriptor; empty when it could not be read
  std::string version;
  bool loaded = false;  // false: `error` says why
  std::string error;
  std::vector<std::pair<FactoryKind, std::string>> provides;
};

class PluginLoader {
 public:
  explicit PluginLoader(Registry& registry);

  // The folders searched, in order (the environment is read on each call unless overridden).
  std::vector<std::filesystem::path> searchPath() const;
  // Replaces the whole search path (tests, hosts that want control); nullopt restores the default.
  void setSearchPath(std::optional<std::vector<std::filesystem::path>> folders);
  std::string describeSearchPath() const;  // "a:b:c"

  // Loads one plugin file. Throws graspkit::Error naming the file for: a file that is not a
  // loadable shared object, a missing graspkit_plugin_v1 symbol, an ABI or descriptor-size
  // mismatch, a plugin name already loaded from another file, a register function that throws,
  // a factory name already provided. Loading the same file twice returns the first result.
  const PluginInfo& load(const std::filesystem::path& file);

  // Loads the plugins on the search path, in order, until one provides `name`. Plugins that fail
  // are remembered (see failures()) and skipped. Returns whether the name is now registered.
  bool loadProviding(FactoryKind kind, const std::string& name);

  // Loads every plugin on the search path; returns one entry per plugin file found, loaded or not.
  std::vector<PluginInfo> loadAll();

  std::vector<PluginInfo> loaded() const;
  std::vector<PluginInfo> failures() const;

 private:
  std::vector<std::filesystem::path> candidateFiles() const;
  PluginInfo tryLoad(const std::filesystem::path& file);

  Registry& registry_;
  std::optional<std::vector<std::filesystem::path>> search_path_;
  std::map<std::filesystem::path, PluginInfo> probed_;  // by canonical path
};

// Text form of a plugin's provided names: "robot type Barrett, quality measure foo".
std::string describeProvides(const PluginInfo& info);

}  // namespace graspkit
