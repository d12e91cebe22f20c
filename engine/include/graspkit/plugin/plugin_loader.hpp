#pragma once
// The plugin loader: finds plugin files on the search path, dlopens them, checks their
// descriptor and commits their factories to its Registry whole or not at all. Loaded plugins
// stay loaded for the life of the process (their code backs the factories).
//
// Search path, in order:
//   1. GRASPKIT_PLUGIN_PATH (colon-separated folders);
//   2. the plugin folder beside the engine library (<libdir>/graspkit/plugins), so a build tree
//      and an install (wherever its prefix) both work with no environment variable, and an
//      install never picks up another install's plugins.
// A plugin file is any regular `*.so` file in those folders (not their subfolders).
//
// Plugins are native code that runs as it loads. Before a plugin the loader has not seen enters
// the process, a forked child opens it (and every other unseen plugin on the path, in one child)
// and reports its name and what it provides: a plugin that crashes, hangs or exits while loading
// is then only an error naming it, and of the healthy ones only the plugin that provides a needed
// name is loaded into the process. GRASPKIT_PLUGIN_PROBE=0 (or setProbe) turns the child off, to
// debug a plugin's loading in place.

#include <chrono>
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

// How the loader opens plugins it has not seen.
struct PluginProbe {
  bool inChildProcess = true;                 // probe in a forked child first
  std::chrono::milliseconds timeout{10'000};  // a plugin still loading after this is killed
};

class PluginLoader {
 public:
  explicit PluginLoader(Registry& registry);

  // The folders searched, in order (the environment is read on each call unless overridden).
  std::vector<std::filesystem::path> searchPath() const;
  // Replaces the whole search path (tests, hosts that want control); nullopt restores the default.
  void setSearchPath(std::optional<std::vector<std::filesystem::path>> folders);
  std::string describeSearchPath() const;  // "a:b:c"

  // The probe settings: setProbe's, else the default with GRASPKIT_PLUGIN_PROBE=0 or "off"
  // turning the child off. nullopt restores the default.
  PluginProbe probe() const;
  void setProbe(std::optional<PluginProbe> probe);

  // Loads one plugin file. Throws graspkit::Error naming the file for: a file that is not a
  // loadable shared object, a missing graspkit_plugin_v1 symbol, an ABI or descriptor-size
  // mismatch, a plugin name already loaded from another file, a register function that throws,
  // a factory name already provided. Loading the same file twice returns the first result.
  const PluginInfo& load(const std::filesystem::path& file);

  // Loads the plugin on the search path that provides `name`: the first, in path order, whose
  // probe lists it (without probing, each plugin in order until one provides it). Plugins that
  // fail before it are remembered (see failures()), warned about and skipped; the others are
  // not loaded. Returns whether the name is now registered.
  bool loadProviding(FactoryKind kind, const std::string& name);

  // Loads every plugin on the search path; returns one entry per plugin file found, loaded or not.
  std::vector<PluginInfo> loadAll();
  // Every plugin on the search path, one entry per file, as far as can be told without loading
  // any into this process: the child's report of each (a plugin already loaded here as it is),
  // with the name clashes loading would find. A plugin that behaves in the child and crashes
  // when loaded a second time cannot take a listing down. Without the child, loadAll().
  std::vector<PluginInfo> survey();
  // The registry's names of `kind` and those the plugins on the search path would add (as
  // survey() finds them), sorted: what a file or a script may name.
  std::vector<std::string> availableNames(FactoryKind kind);

  std::vector<PluginInfo> loaded() const;
  std::vector<PluginInfo> failures() const;

 private:
  static std::filesystem::path keyOf(const std::filesystem::path& file);  // canonical path
  std::vector<std::filesystem::path> candidateFiles() const;
  // Probes, in one child, the files neither loaded nor probed yet (when probing is on).
  void probeUnseen(const std::vector<std::filesystem::path>& files);
  const PluginInfo* probeFailure(const std::filesystem::path& key) const;
  // The file's outcome in this process: its probe's failure, or an in-process load.
  const PluginInfo& settle(const std::filesystem::path& file);
  PluginInfo tryLoad(const std::filesystem::path& file);

  Registry& registry_;
  std::optional<std::vector<std::filesystem::path>> search_path_;
  std::optional<PluginProbe> probe_;
  std::map<std::filesystem::path, PluginInfo> probed_;  // loaded or failed here, by canonical path
  std::map<std::filesystem::path, PluginInfo> probes_;  // what the child found, by canonical path
};

// Text form of a plugin's provided names: "robot type Barrett, quality measure foo".
std::string describeProvides(const PluginInfo& info);

}  // namespace graspkit
