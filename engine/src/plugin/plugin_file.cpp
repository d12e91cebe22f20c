#include "plugin/plugin_file.hpp"

#include <dlfcn.h>

#include <set>

#include <fmt/format.h>

#include "graspkit/base/log.hpp"
#include "graspkit/base/utf8.hpp"
#include "graspkit/plugin/plugin.hpp"

namespace graspkit::plugin {

void StagingRegistrar::addRobotType(const std::string& name, RobotTypeFactory factory) {
  staged.push_back({FactoryKind::RobotType, name, std::move(factory), {}, {}, {}});
}
void StagingRegistrar::addQualityMeasure(const std::string& name, QualityMeasureFactory factory) {
  staged.push_back({FactoryKind::QualityMeasure, name, {}, std::move(factory), {}, {}});
}
void StagingRegistrar::addSearchEnergy(const std::string& name, SearchEnergyFactory factory) {
  staged.push_back({FactoryKind::SearchEnergy, name, {}, {}, std::move(factory), {}});
}
void StagingRegistrar::addPlanner(const std::string& name, PlannerFactory factory) {
  staged.push_back({FactoryKind::Planner, name, {}, {}, {}, std::move(factory)});
}

namespace {

std::string dlErrorText() {
  const char* text = dlerror();
  return text ? text : "unknown dlopen error";
}

}  // namespace

OpenedPlugin openPlugin(const std::filesystem::path& file) {
  OpenedPlugin opened;
  PluginInfo& info = opened.info;
  info.file = file;
  auto fail = [&](std::string why) {
    info.error = std::move(why);
    opened.staging.staged.clear();
    return std::move(opened);
  };

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
  return openDescriptor(file, descriptor);
}

OpenedPlugin openDescriptor(const std::filesystem::path& file,
                            const graspkit_plugin_descriptor* descriptor) {
  OpenedPlugin opened;
  PluginInfo& info = opened.info;
  info.file = file;
  auto fail = [&](std::string why) {
    info.error = std::move(why);
    opened.staging.staged.clear();
    return std::move(opened);
  };
  if (!descriptor) return fail(GRASPKIT_PLUGIN_SYMBOL " returned no descriptor");
  // Only the first two fields are read before both checks pass: they are the ABI's fixed part.
  if (descriptor->abi_version != GRASPKIT_PLUGIN_ABI_VERSION)
    return fail(fmt::format("built for plugin ABI {}, this engine loads ABI {}",
                            descriptor->abi_version, GRASPKIT_PLUGIN_ABI_VERSION));
  if (descriptor->descriptor_size != sizeof(graspkit_plugin_descriptor))
    return fail(fmt::format("descriptor size {} bytes, this engine expects {}",
                            descriptor->descriptor_size, sizeof(graspkit_plugin_descriptor)));
  if (!descriptor->name || !*descriptor->name) return fail("the descriptor has no plugin name");
  // Names are shown, listed in JSON and compared: they must be text.
  if (firstInvalidUtf8(descriptor->name) ||
      (descriptor->version && firstInvalidUtf8(descriptor->version)))
    return fail("the descriptor's plugin name or version is not UTF-8 text");
  info.name = descriptor->name;
  info.version = descriptor->version ? descriptor->version : "";
  if (!descriptor->register_factories) return fail("the descriptor has no register function");

  trace(fmt::format("calling the register function of plugin '{}' ({})", info.name, file.string()));
  try {
    descriptor->register_factories(opened.staging);
  } catch (const std::exception& e) {
    return fail(fmt::format("plugin '{}' threw while registering: {}", info.name, e.what()));
  } catch (...) {
    return fail(
        fmt::format("plugin '{}' threw a non-standard exception while registering", info.name));
  }
  for (const auto& item : opened.staging.staged) info.provides.emplace_back(item.kind, item.name);
  return opened;
}

PluginInfo commitPlugin(Registry& registry, OpenedPlugin opened,
                        const std::vector<PluginInfo>& loaded) {
  PluginInfo& info = opened.info;
  auto fail = [&](std::string why) {
    info.error = std::move(why);
    info.provides.clear();
    return info;
  };
  if (!info.error.empty()) return fail(info.error);
  info.provides.clear();
  for (const PluginInfo& other : loaded)
    if (other.loaded && other.name == info.name)
      return fail(fmt::format("a plugin named '{}' is already loaded from {}", info.name,
                              other.file.string()));

  // Check everything before committing anything.
  std::set<std::pair<FactoryKind, std::string>> names;
  for (const auto& item : opened.staging.staged) {
    const std::string_view kind = nameOf(item.kind);
    if (item.name.empty()) return fail(fmt::format("registers a {} with no name", kind));
    if (firstInvalidUtf8(item.name))
      return fail(fmt::format("registers a {} whose name is not UTF-8 text", kind));
    if (!item.hasFactory())
      return fail(fmt::format("registers {} '{}' with no factory", kind, item.name));
    if (!names.insert({item.kind, item.name}).second)
      return fail(fmt::format("registers {} '{}' twice", kind, item.name));
    if (auto owner = registry.provenance(item.kind, item.name))
      return fail(fmt::format("provides {} '{}', already provided by {}{}", kind, item.name,
                              owner->describe(),
                              owner->file.empty() ? "" : " (" + owner->file.string() + ")"));
  }
  const Provenance from{info.name, info.version, info.file};
  for (auto& item : opened.staging.staged) {
    switch (item.kind) {
      case FactoryKind::RobotType:
        registry.addRobotType(item.name, std::move(item.robotType), from);
        break;
      case FactoryKind::QualityMeasure:
        registry.addQualityMeasure(item.name, std::move(item.qualityMeasure), from);
        break;
      case FactoryKind::SearchEnergy:
        registry.addSearchEnergy(item.name, std::move(item.searchEnergy), from);
        break;
      case FactoryKind::Planner:
        registry.addPlanner(item.name, std::move(item.planner), from);
        break;
    }
    info.provides.emplace_back(item.kind, item.name);
  }
  info.loaded = true;
  return info;
}

}  // namespace graspkit::plugin
