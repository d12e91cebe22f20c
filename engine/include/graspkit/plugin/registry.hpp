#pragma once
// The Registry: named factories for everything a plugin can add (robot types, quality measures,
// search energies, grasp planners),
// each remembered with the plugin that provided it. A name missing from the registry makes its
// PluginLoader look for a plugin providing it (see plugin_loader.hpp).
//
// Registry::global() is the one the engine's loaders use. Tests and hosts that want isolation
// make their own.

#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "graspkit/base/enum_names.hpp"
#include "graspkit/grasp/quality.hpp"
#include "graspkit/grasp/robot_type.hpp"
#include "graspkit/planning/planner.hpp"
#include "graspkit/planning/search_energy.hpp"
#include "graspkit/plugin/plugin_loader.hpp"

namespace graspkit {

using RobotTypeFactory = std::function<std::shared_ptr<const RobotType>()>;

// What a plugin's register function receives. Names are checked (empty, duplicate within the
// plugin, already provided) when the loader commits, so a plugin is registered whole or not at
// all.
class Registrar {
 public:
  virtual ~Registrar() = default;
  virtual void addRobotType(const std::string& name, RobotTypeFactory factory) = 0;
  virtual void addQualityMeasure(const std::string& name, QualityMeasureFactory factory) = 0;
  virtual void addSearchEnergy(const std::string& name, SearchEnergyFactory factory) = 0;
  virtual void addPlanner(const std::string& name, PlannerFactory factory) = 0;
};

enum class FactoryKind { RobotType, QualityMeasure, SearchEnergy, Planner };
// "robot type", "quality measure", "search energy", "planner" (base/enum_names.hpp: nameOf,
// valueNamed, parseNamed).
std::span<const EnumName<FactoryKind>> enumNames(std::type_identity<FactoryKind>);

// Who provided a name: a plugin (name, version, file), or the engine itself (plugin empty).
struct Provenance {
  std::string plugin;
  std::string version;
  std::filesystem::path file;
  std::string describe() const;  // "barrett 1.0.0" or "built in"
};

class Registry {
 public:
  // With the engine's built-ins: robot types Robot and Hand, quality measures epsilon and
  // volume, and GraspIt!'s search energies (search_energy.hpp).
  Registry();
  Registry(const Registry&) = delete;
  Registry& operator=(const Registry&) = delete;

  static Registry& global();

  PluginLoader& plugins() { return loader_; }

  // The robot type called `name`, loading the plugin that provides it when needed. Throws
  // graspkit::Error listing the available types and the plugin search path when none does.
  std::shared_ptr<const RobotType> robotType(const std::string& name);
  std::unique_ptr<QualityMeasure> makeQualityMeasure(const std::string& name);
  // A new search energy; GraspIt!'s names (CONTACT_ENERGY, ...) are accepted too.
  std::unique_ptr<SearchEnergy> makeSearchEnergy(const std::string& name);
  // A new planner for `request`; the plugin providing `name` is loaded when needed.
  std::unique_ptr<Planner> makePlanner(const std::string& name, const PlanningRequest& request);

  bool contains(FactoryKind kind, const std::string& name) const;
  // Registered names of one kind, sorted (without loading anything).
  std::vector<std::string> names(FactoryKind kind) const;
  std::optional<Provenance> provenance(FactoryKind kind, const std::string& name) const;

  // Adds one factory. Throws graspkit::Error for an empty name, an empty factory or a name
  // already registered (naming who provided it).
  void addRobotType(const std::string& name, RobotTypeFactory factory, Provenance from = {});
  void addQualityMeasure(const std::string& name, QualityMeasureFactory factory,
                         Provenance from = {});
  void addSearchEnergy(const std::string& name, SearchEnergyFactory factory, Provenance from = {});
  void addPlanner(const std::string& name, PlannerFactory factory, Provenance from = {});

 private:
  struct Entry {
    RobotTypeFactory robotType;
    QualityMeasureFactory qualityMeasure;
    SearchEnergyFactory searchEnergy;
    PlannerFactory planner;
    std::shared_ptr<const RobotType> robotTypeInstance;  // made once, on first use
    Provenance from;
  };
  using Key = std::pair<FactoryKind, std::string>;

  void add(FactoryKind kind, const std::string& name, Entry entry);
  std::optional<Entry> find(FactoryKind kind, const std::string& name);
  [[noreturn]] void throwUnknown(FactoryKind kind, const std::string& name);

  friend class PluginLoader;  // commits a plugin's factories under the registry's lock
  mutable std::recursive_mutex mutex_;
  std::map<Key, Entry> entries_;
  PluginLoader loader_;
};

// Shorthands for Registry::global()'s quality measures.
// Adds a measure under `name`. Throws graspkit::Error for an empty name, a name already taken
// or an empty factory. Safe to call from several threads (plugins register while loading).
void registerQualityMeasure(const std::string& name, QualityMeasureFactory factory);
// A new instance of the measure called `name`; throws graspkit::Error naming it (and the known
// names) when no measure has that name.
std::unique_ptr<QualityMeasure> makeQualityMeasure(const std::string& name);
// Every registered name, sorted; the built-ins "epsilon" and "volume" are always there.
std::vector<std::string> qualityMeasureNames();

}  // namespace graspkit
