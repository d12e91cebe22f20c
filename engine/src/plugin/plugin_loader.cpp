#include "graspkit/plugin/plugin_loader.hpp"

#include <dlfcn.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <set>
#include <sstream>

#include <fmt/format.h>

#include "graspkit/base/error.hpp"
#include "graspkit/base/log.hpp"
#include "graspkit/plugin/plugin.hpp"
#include "graspkit/plugin/registry.hpp"
#include "plugin/plugin_file.hpp"
#include "plugin/plugin_probe.hpp"

namespace fs = std::filesystem;

namespace graspkit {
namespace {

std::vector<fs::path> splitPathList(const char* text) {
  std::vector<fs::path> folders;
  if (!text) return folders;
  std::stringstream stream(text);
  std::string item;
  while (std::getline(stream, item, ':'))
    if (!item.empty()) folders.emplace_back(item);
  return folders;
}

// The folder of the shared object holding this function: libgraspkit's, wherever it lies.
fs::path engineLibraryFolder() {
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(&engineLibraryFolder), &info) == 0 || !info.dli_fname)
    return {};
  std::error_code ec;
  fs::path file = fs::canonical(info.dli_fname, ec);
  return ec ? fs::path{} : file.parent_path();
}

}  // namespace

std::string describeProvides(const PluginInfo& info) {
  std::string text;
  for (const auto& [kind, name] : info.provides)
    text += fmt::format("{}{} {}", text.empty() ? "" : ", ", nameOf(kind), name);
  return text;
}

PluginLoader::PluginLoader(Registry& registry) : registry_(registry) {}

std::vector<fs::path> PluginLoader::searchPath() const {
  if (search_path_) return *search_path_;
  std::vector<fs::path> folders = splitPathList(std::getenv("GRASPKIT_PLUGIN_PATH"));
  // Beside the library, <libdir>/graspkit/plugins: the plugins of the install (or build tree)
  // this libgraspkit belongs to, and no other's. A folder fixed when configuring would outlive
  // `cmake --install --prefix` and mix in another install's plugins.
  if (const fs::path lib = engineLibraryFolder(); !lib.empty())
    folders.push_back(lib / "graspkit" / "plugins");
  std::vector<fs::path> unique;
  for (fs::path& folder : folders)
    if (std::find(unique.begin(), unique.end(), folder) == unique.end())
      unique.push_back(std::move(folder));
  return unique;
}

void PluginLoader::setSearchPath(std::optional<std::vector<fs::path>> folders) {
  std::lock_guard lock(registry_.mutex_);
  search_path_ = std::move(folders);
}

std::string PluginLoader::describeSearchPath() const {
  std::string text;
  for (const fs::path& folder : searchPath()) {
    if (!text.empty()) text += ':';
    text += folder.string();
  }
  return text.empty() ? "(empty)" : text;
}

std::vector<fs::path> PluginLoader::candidateFiles() const {
  std::vector<fs::path> files;
  std::set<fs::path> seen;
  for (const fs::path& folder : searchPath()) {
    std::error_code ec;
    std::vector<fs::path> here;
    for (const fs::directory_entry& entry : fs::directory_iterator(folder, ec)) {
      if (entry.path().extension() != ".so" || !entry.is_regular_file(ec)) continue;
      here.push_back(entry.path());
    }
    std::sort(here.begin(), here.end());  // a stable order, whatever the file system gives
    for (fs::path& file : here) {
      fs::path canonical = fs::weakly_canonical(file, ec);
      if (seen.insert(ec ? file : canonical).second) files.push_back(std::move(file));
    }
  }
  return files;
}

namespace {

// While a plugin loads, what it prints goes to standard error: standard output belongs to the
// host (graspkit's --json output, a pipeline's data), and a plugin's constructor must not mix
// into it.
class StdoutToStderr {
 public:
  StdoutToStderr() {
    std::fflush(stdout);
    saved_ = ::dup(STDOUT_FILENO);
    if (saved_ >= 0) ::dup2(STDERR_FILENO, STDOUT_FILENO);
  }
  ~StdoutToStderr() {
    if (saved_ < 0) return;
    std::fflush(stdout);
    ::dup2(saved_, STDOUT_FILENO);
    ::close(saved_);
  }
  StdoutToStderr(const StdoutToStderr&) = delete;
  StdoutToStderr& operator=(const StdoutToStderr&) = delete;

 private:
  int saved_ = -1;
};

}  // namespace

PluginInfo PluginLoader::tryLoad(const fs::path& file) {
  std::vector<PluginInfo> loaded;
  for (const auto& [path, info] : probed_)
    if (info.loaded) loaded.push_back(info);
  plugin::OpenedPlugin opened = [&] {
    const StdoutToStderr redirect;
    return plugin::openPlugin(file);
  }();
  return plugin::commitPlugin(registry_, std::move(opened), loaded);
}

PluginProbe PluginLoader::probe() const {
  if (probe_) return *probe_;
  PluginProbe probe;
  if (const char* env = std::getenv("GRASPKIT_PLUGIN_PROBE");
      env && (std::string_view(env) == "0" || std::string_view(env) == "off"))
    probe.inChildProcess = false;
  return probe;
}

void PluginLoader::setProbe(std::optional<PluginProbe> probe) {
  std::lock_guard lock(registry_.mutex_);
  probe_ = probe;
}

fs::path PluginLoader::keyOf(const fs::path& file) {
  std::error_code ec;
  fs::path key = fs::weakly_canonical(file, ec);
  return ec ? file : key;
}

void PluginLoader::probeUnseen(const std::vector<fs::path>& files) {
  const PluginProbe settings = probe();
  if (!settings.inChildProcess) return;
  std::vector<fs::path> unseen;
  for (const fs::path& file : files) {
    const fs::path key = keyOf(file);
    if (!probed_.count(key) && !probes_.count(key)) unseen.push_back(file);
  }
  if (unseen.empty()) return;
  try {
    const std::vector<PluginInfo> results = plugin::probePlugins(unseen, settings.timeout);
    for (std::size_t i = 0; i < unseen.size(); ++i) probes_[keyOf(unseen[i])] = results[i];
  } catch (const Error& e) {
    // No child process (a process limit, say): plugins then load straight into this process.
    warn(WarningKind::Plugin, SourceLocation{},
         fmt::format("{}; loading plugins without probing them", e.what()));
    probe_ = PluginProbe{false, settings.timeout};
  }
}

const PluginInfo* PluginLoader::probeFailure(const fs::path& key) const {
  const auto it = probes_.find(key);
  return it != probes_.end() && !it->second.loaded ? &it->second : nullptr;
}

const PluginInfo& PluginLoader::settle(const fs::path& file) {
  const fs::path key = keyOf(file);
  if (auto it = probed_.find(key); it != probed_.end()) return it->second;
  probeUnseen({file});
  if (const PluginInfo* failed = probeFailure(key))
    return probed_.emplace(key, *failed).first->second;
  return probed_.emplace(key, tryLoad(file)).first->second;
}

const PluginInfo& PluginLoader::load(const fs::path& file) {
  std::lock_guard lock(registry_.mutex_);
  std::error_code ec;
  if (!probed_.count(keyOf(file)) && !fs::exists(file, ec))
    throw Error(fmt::format("plugin {}: no such file", file.string()));
  const PluginInfo& info = settle(file);
  if (!info.loaded)
    throw Error(fmt::format("plugin {}: {} (plugin search path: {})", file.string(), info.error,
                            describeSearchPath()));
  return info;
}

bool PluginLoader::loadProviding(FactoryKind kind, const std::string& name) {
  std::lock_guard lock(registry_.mutex_);
  const std::vector<fs::path> files = candidateFiles();
  probeUnseen(files);
  for (const fs::path& file : files) {
    const fs::path key = keyOf(file);
    if (probed_.count(key)) continue;
    if (const auto it = probes_.find(key); it != probes_.end() && it->second.loaded) {
      const auto& provides = it->second.provides;
      // Only the plugin that provides the name is loaded into this process.
      if (std::find(provides.begin(), provides.end(), std::pair(kind, name)) == provides.end())
        continue;
    }
    const PluginInfo& info = settle(file);
    if (!info.loaded) warn(WarningKind::Plugin, SourceLocation{file.string()}, info.error);
    if (registry_.contains(kind, name)) return true;
  }
  return registry_.contains(kind, name);
}

std::vector<PluginInfo> PluginLoader::loadAll() {
  std::lock_guard lock(registry_.mutex_);
  const std::vector<fs::path> files = candidateFiles();
  probeUnseen(files);
  std::vector<PluginInfo> found;
  for (const fs::path& file : files) found.push_back(settle(file));
  return found;
}

std::vector<PluginInfo> PluginLoader::survey() {
  std::lock_guard lock(registry_.mutex_);
  const std::vector<fs::path> files = candidateFiles();
  probeUnseen(files);
  if (!probe().inChildProcess) return loadAll();
  std::vector<PluginInfo> found;
  std::map<std::string, fs::path> plugin_names;  // of the plugins that would load, in path order
  std::map<std::pair<FactoryKind, std::string>, std::string> factories;  // and what they provide
  for (const auto& [path, info] : probed_)
    if (info.loaded) plugin_names.emplace(info.name, info.file);
  for (const fs::path& file : files) {
    const fs::path key = keyOf(file);
    if (const auto it = probed_.find(key); it != probed_.end()) {
      found.push_back(it->second);
      continue;
    }
    PluginInfo info = probes_.at(key);
    // The checks loading would make (plugin_file.cpp, commitPlugin), from the probe's report.
    auto refuse = [&](std::string why) {
      info.loaded = false;
      info.error = std::move(why);
      info.provides.clear();
    };
    if (info.loaded) {
      if (const auto other = plugin_names.find(info.name); other != plugin_names.end())
        refuse(fmt::format("a plugin named '{}' is already loaded from {}", info.name,
                           other->second.string()));
    }
    for (const auto& item : info.loaded ? info.provides : decltype(info.provides){}) {
      std::string owner;
      if (const auto here = registry_.provenance(item.first, item.second))
        owner = here->describe() + (here->file.empty() ? "" : " (" + here->file.string() + ")");
      else if (const auto other = factories.find(item); other != factories.end())
        owner = other->second;
      if (!owner.empty()) {
        refuse(fmt::format("provides {} '{}', already provided by {}", nameOf(item.first),
                           item.second, owner));
        break;
      }
    }
    if (info.loaded) {
      plugin_names.emplace(info.name, info.file);
      for (const auto& item : info.provides)
        factories.emplace(item, fmt::format("plugin '{}' ({})", info.name, info.file.string()));
    }
    found.push_back(std::move(info));
  }
  return found;
}

std::vector<std::string> PluginLoader::availableNames(FactoryKind kind) {
  std::lock_guard lock(registry_.mutex_);
  std::set<std::string> names;
  for (const std::string& name : registry_.names(kind)) names.insert(name);
  for (const PluginInfo& info : survey())
    for (const auto& [provided, name] : info.provides)
      if (info.loaded && provided == kind) names.insert(name);
  return {names.begin(), names.end()};
}

std::vector<PluginInfo> PluginLoader::loaded() const {
  std::lock_guard lock(registry_.mutex_);
  std::vector<PluginInfo> list;
  for (const auto& [path, info] : probed_)
    if (info.loaded) list.push_back(info);
  return list;
}

std::vector<PluginInfo> PluginLoader::failures() const {
  std::lock_guard lock(registry_.mutex_);
  std::vector<PluginInfo> list;
  for (const auto& [path, info] : probed_)
    if (!info.loaded) list.push_back(info);
  return list;
}

}  // namespace graspkit
