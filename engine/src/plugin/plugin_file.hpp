#pragma once
// Opening one plugin file (internal to the plugin module): dlopen, the descriptor's checks and the
// register function run into a staging registrar, so nothing reaches a Registry until the loader
// has checked it all. The child-process probe and the in-process load open plugins the same way,
// so a probe reports exactly the error a load would.

#include <filesystem>
#include <string>
#include <vector>

#include "graspkit/plugin/plugin.hpp"
#include "graspkit/plugin/plugin_loader.hpp"
#include "graspkit/plugin/registry.hpp"

namespace graspkit::plugin {

// A plugin's factories as its register function added them, to be checked and committed together.
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

  void addRobotType(const std::string& name, RobotTypeFactory factory) override;
  void addQualityMeasure(const std::string& name, QualityMeasureFactory factory) override;
  void addSearchEnergy(const std::string& name, SearchEnergyFactory factory) override;
  void addPlanner(const std::string& name, PlannerFactory factory) override;
};

struct OpenedPlugin {
  PluginInfo info;  // file, name, version; error set when the file is no usable plugin
  StagingRegistrar staging;
};

// dlopens `file` (never closed: its code may have run), finds its descriptor and opens it as
// openDescriptor does. Exceptions from the plugin become info.error; a crash or a hang is the
// caller's to contain (see probePlugins).
OpenedPlugin openPlugin(const std::filesystem::path& file);

// Checks a descriptor that `file` returned (ABI version and size first, then name and register
// function) and runs its register function into the staging registrar.
OpenedPlugin openDescriptor(const std::filesystem::path& file,
                            const graspkit_plugin_descriptor* descriptor);

// Commits an opened plugin's factories to `registry`, all or none: refused (info.error set,
// nothing registered) when it failed to open, when a plugin of its name is among `loaded`, or
// when a staged factory has no name, no function, a name staged twice or a name the registry
// already has. Returns the plugin's outcome, with `provides` filled when it was committed.
PluginInfo commitPlugin(Registry& registry, OpenedPlugin opened,
                        const std::vector<PluginInfo>& loaded);

}  // namespace graspkit::plugin
