#include "graspkit/plugin_loader.hpp"

#include <dlfcn.h>

#include <algorithm>
#include <cstdlib>
#include <set>
#include <sstream>

#include <fmt/format.h>

#include "graspkit/error.hpp"
#include "graspkit/log.hpp"
#include "graspkit/plugin.hpp"
#include "graspkit/registry.hpp"

namespace fs = std::filesystem;

namespace graspkit {
namespace {

// Collects a plugin's factories so they can be checked and committed together.
class StagingRegistrar final : public Registrar {
 public:
  struct Staged {
    FactoryKind kind;
    std::string name;
    RobotTypeFactory robotType;
    QualityMeasureFactory qualityMeasure;
    SearchEnergyFactory searchEnergy;
    PlannerFactory planner;
    bool hasFactory() const { return robotType || qualityMeasure || searchEnergy || planner; }
  };
  std::vector<Staged> staged;

  void addRobotType(const std::string& name, RobotTypeFactory factory) override {
    staged.push_back({FactoryKind::RobotType, name, std::move(factory), {}, {}, {}});
  }
  void addQualityMeasure(const std::string& name, QualityMeasureFactory factory) override {
    staged.push_back({FactoryKind::QualityMeasure, name, {}, std::move(factory), {}, {}});
  }
  void addSearchEnergy(const std::string& name, SearchEnergyFactory factory) override {
    staged.push_back({FactoryKind::SearchEnergy, name, {}, {}, std::move(factory), {}});
  }
  void addPlanner(const std::string& name, PlannerFactory factory) override {
    staged.push_back({FactoryKind::Planner, name, {}, {}, {}, std::move(factory)});
  }
};

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

fs::path programFolder() {
  std::error_code ec;
  fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  return ec ? fs::path{} : exe.parent_path();
}

std::string dlErrorText() {
  const char* text = dlerror();
  return text ? text : "unknown dlopen error";
}

}  // namespace

std::string describeProvides(const PluginInfo& info) {
  std::string text;
  for (const auto& [kind, name] : info.provides)
    text += fmt::format("{}{} {}", text.empty() ? "" : ", ", toString(kind), name);
  return text;
}

PluginLoader::PluginLoader(Registry& registry) : registry_(registry) {}

std::vector<fs::path> PluginLoader::searchPath() const {
  if (search_path_) return *search_path_;
  std::vector<fs::path> folders = splitPathList(std::getenv("GRASPKIT_PLUGIN_PATH"));
  // Beside the library: <libdir>/graspkit/plugins. Beside the program: <bindir>/../lib/...
  if (const fs::path lib = engineLibraryFolder(); !lib.empty())
    folders.push_back(lib / "graspkit" / "plugins");
  if (const fs::path bin = programFolder(); !bin.empty())
    folders.push_back((bin / ".." / "lib" / "graspkit" / "plugins").lexically_normal());
#ifdef GRASPKIT_INSTALLED_PLUGIN_DIR
  folders.emplace_back(GRASPKIT_INSTALLED_PLUGIN_DIR);
#endif
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
  for (const fs::path& folder : searchPath()) text += (text.empty() ? "" : ":") + folder.string();
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

PluginInfo PluginLoader::tryLoad(const fs::path& file) {
  PluginInfo info;
  info.file = file;
  auto fail = [&](std::string why) {
    info.error = std::move(why);
    return info;
  };

  // Never dlclose: a plugin's code may have run (static constructors, its register function),
  // and unloading it could leave dangling pointers behind in the process.
  trace(fmt::format("loading plugin {} (its static constructors run now)", file.string()));
  void* handle = dlopen(file.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle) return fail("cannot load: " + dlErrorText());
  dlerror();
  void* symbol = dlsym(handle, GRASPKIT_PLUGIN_SYMBOL);
  if (!symbol) return fail("not a graspkit plugin: no symbol " GRASPKIT_PLUGIN_SYMBOL);
  auto entry = reinterpret_cast<graspkit_plugin_entry>(symbol);
  const graspkit_plugin_descriptor* descriptor = nullptr;
  try {
    descriptor = entry();
  } catch (const std::exception& e) {
    return fail(fmt::format("{} threw: {}", GRASPKIT_PLUGIN_SYMBOL, e.what()));
  } catch (...) {
    return fail(GRASPKIT_PLUGIN_SYMBOL " threw a non-standard exception");
  }
  if (!descriptor) return fail(GRASPKIT_PLUGIN_SYMBOL " returned no descriptor");
  // Only the first two fields are read before both checks pass: they are the ABI's fixed part.
  if (descriptor->abi_version != GRASPKIT_PLUGIN_ABI_VERSION)
    return fail(fmt::format("built for plugin ABI {}, this engine loads ABI {}",
                            descriptor->abi_version, GRASPKIT_PLUGIN_ABI_VERSION));
  if (descriptor->descriptor_size != sizeof(graspkit_plugin_descriptor))
    return fail(fmt::format("descriptor size {} bytes, this engine expects {}",
                            descriptor->descriptor_size, sizeof(graspkit_plugin_descriptor)));
  if (!descriptor->name || !*descriptor->name) return fail("the descriptor has no plugin name");
  info.name = descriptor->name;
  info.version = descriptor->version ? descriptor->version : "";
  if (!descriptor->register_factories) return fail("the descriptor has no register function");
  for (const auto& [path, other] : probed_)
    if (other.loaded && other.name == info.name)
      return fail(fmt::format("a plugin named '{}' is already loaded from {}", info.name,
                              other.file.string()));

  StagingRegistrar staging;
  trace(fmt::format("calling the register function of plugin '{}' ({})", info.name, file.string()));
  try {
    descriptor->register_factories(staging);
  } catch (const std::exception& e) {
    return fail(fmt::format("plugin '{}' threw while registering: {}", info.name, e.what()));
  } catch (...) {
    return fail(
        fmt::format("plugin '{}' threw a non-standard exception while registering", info.name));
  }

  // Check everything before committing anything.
  std::set<std::pair<FactoryKind, std::string>> names;
  for (const auto& item : staging.staged) {
    const char* kind = toString(item.kind);
    if (item.name.empty()) return fail(fmt::format("registers a {} with no name", kind));
    if (!item.hasFactory())
      return fail(fmt::format("registers {} '{}' with no factory", kind, item.name));
    if (!names.insert({item.kind, item.name}).second)
      return fail(fmt::format("registers {} '{}' twice", kind, item.name));
    if (auto owner = registry_.provenance(item.kind, item.name))
      return fail(fmt::format("provides {} '{}', already provided by {}{}", kind, item.name,
                              owner->describe(),
                              owner->file.empty() ? "" : " (" + owner->file.string() + ")"));
  }
  const Provenance from{info.name, info.version, file};
  for (auto& item : staging.staged) {
    switch (item.kind) {
      case FactoryKind::RobotType:
        registry_.addRobotType(item.name, std::move(item.robotType), from);
        break;
      case FactoryKind::QualityMeasure:
        registry_.addQualityMeasure(item.name, std::move(item.qualityMeasure), from);
        break;
      case FactoryKind::SearchEnergy:
        registry_.addSearchEnergy(item.name, std::move(item.searchEnergy), from);
        break;
      case FactoryKind::Planner:
        registry_.addPlanner(item.name, std::move(item.planner), from);
        break;
    }
    info.provides.emplace_back(item.kind, item.name);
  }
  info.loaded = true;
  return info;
}

const PluginInfo& PluginLoader::load(const fs::path& file) {
  std::lock_guard lock(registry_.mutex_);
  std::error_code ec;
  const fs::path key = fs::weakly_canonical(file, ec);
  auto it = probed_.find(ec ? file : key);
  if (it == probed_.end()) {
    if (!fs::exists(file, ec)) throw Error(fmt::format("plugin {}: no such file", file.string()));
    it = probed_.emplace(ec ? file : key, tryLoad(file)).first;
  }
  if (!it->second.loaded)
    throw Error(fmt::format("plugin {}: {} (plugin search path: {})", file.string(),
                            it->second.error, describeSearchPath()));
  return it->second;
}

bool PluginLoader::loadProviding(FactoryKind kind, const std::string& name) {
  std::lock_guard lock(registry_.mutex_);
  for (const fs::path& file : candidateFiles()) {
    std::error_code ec;
    const fs::path key = fs::weakly_canonical(file, ec);
    if (probed_.count(ec ? file : key)) continue;
    const PluginInfo& info = probed_.emplace(ec ? file : key, tryLoad(file)).first->second;
    if (!info.loaded) warn(SourceLocation{file.string()}, info.error);
    if (registry_.contains(kind, name)) return true;
  }
  return registry_.contains(kind, name);
}

std::vector<PluginInfo> PluginLoader::loadAll() {
  std::lock_guard lock(registry_.mutex_);
  std::vector<PluginInfo> found;
  for (const fs::path& file : candidateFiles()) {
    std::error_code ec;
    const fs::path key = fs::weakly_canonical(file, ec);
    auto it = probed_.find(ec ? file : key);
    if (it == probed_.end()) it = probed_.emplace(ec ? file : key, tryLoad(file)).first;
    found.push_back(it->second);
  }
  return found;
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
