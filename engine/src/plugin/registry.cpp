#include "graspkit/plugin/registry.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "graspkit/base/error.hpp"

namespace graspkit {

std::string Provenance::describe() const {
  if (plugin.empty()) return "built in";
  return version.empty() ? plugin : plugin + " " + version;
}

// The built-ins are registered here, by the registry itself: the modules below only say what
// they provide, so none of them depends on the registry.
Registry::Registry() : loader_(*this) {
  // "Robot" (an arm, no hand behaviour) and "Hand" differ only in RobotModel::isHand, which the
  // robot file reader sets from the type name; both behave generically.
  auto generic = [] { return std::make_shared<const RobotType>(); };
  addRobotType("Robot", generic);
  addRobotType("Hand", generic);
  for (auto& [name, factory] : builtinQualityMeasures()) addQualityMeasure(name, factory);
  for (auto& [name, factory] : builtinSearchEnergies()) addSearchEnergy(name, factory);
}

Registry& Registry::global() {
  static Registry instance;
  return instance;
}

void Registry::add(FactoryKind kind, const std::string& name, Entry entry) {
  if (name.empty()) throw Error(fmt::format("a {} needs a name", nameOf(kind)));
  std::lock_guard lock(mutex_);
  auto [it, inserted] = entries_.try_emplace(Key{kind, name}, std::move(entry));
  if (!inserted)
    throw Error(fmt::format("{} '{}' is already provided by {}", nameOf(kind), name,
                            it->second.from.describe()));
}

void Registry::addRobotType(const std::string& name, RobotTypeFactory factory, Provenance from) {
  if (!factory) throw Error(fmt::format("robot type '{}' has no factory", name));
  Entry entry;
  entry.robotType = std::move(factory);
  entry.from = std::move(from);
  add(FactoryKind::RobotType, name, std::move(entry));
}

void Registry::addQualityMeasure(const std::string& name, QualityMeasureFactory factory,
                                 Provenance from) {
  if (!factory) throw Error(fmt::format("quality measure '{}' has no factory", name));
  Entry entry;
  entry.qualityMeasure = std::move(factory);
  entry.from = std::move(from);
  add(FactoryKind::QualityMeasure, name, std::move(entry));
}

void Registry::addSearchEnergy(const std::string& name, SearchEnergyFactory factory,
                               Provenance from) {
  if (!factory) throw Error(fmt::format("search energy '{}' has no factory", name));
  Entry entry;
  entry.searchEnergy = std::move(factory);
  entry.from = std::move(from);
  add(FactoryKind::SearchEnergy, name, std::move(entry));
}

void Registry::addPlanner(const std::string& name, PlannerFactory factory, Provenance from) {
  if (!factory) throw Error(fmt::format("planner '{}' has no factory", name));
  Entry entry;
  entry.planner = std::move(factory);
  entry.from = std::move(from);
  add(FactoryKind::Planner, name, std::move(entry));
}

bool Registry::contains(FactoryKind kind, const std::string& name) const {
  std::lock_guard lock(mutex_);
  return entries_.count(Key{kind, name}) > 0;
}

std::vector<std::string> Registry::names(FactoryKind kind) const {
  std::lock_guard lock(mutex_);
  std::vector<std::string> names;
  for (const auto& [key, entry] : entries_)
    if (key.first == kind) names.push_back(key.second);
  return names;  // the map orders by (kind, name)
}

std::optional<Provenance> Registry::provenance(FactoryKind kind, const std::string& name) const {
  std::lock_guard lock(mutex_);
  auto it = entries_.find(Key{kind, name});
  if (it == entries_.end()) return std::nullopt;
  return it->second.from;
}

namespace {

// Calls a factory, which may be a plugin's code: whatever it throws becomes a graspkit::Error
// naming what was made and the plugin it came from, so no exception of a plugin's own type
// reaches the host (where nothing would catch it) and every failure says whose it is.
template <class Factory>
auto callFactory(std::string_view what, const Provenance& from, Factory&& factory) {
  const auto fail = [&](std::string_view reason) {
    return Error(fmt::format("{} ({}): {}", what, from.describe(), reason));
  };
  try {
    return factory();
  } catch (const std::exception& e) {  // graspkit::Error too, its location included
    throw fail(e.what());
  } catch (...) {
    throw fail("it threw something that is not a std::exception");
  }
}

}  // namespace

std::span<const EnumName<FactoryKind>> enumNames(std::type_identity<FactoryKind>) {
  static constexpr EnumName<FactoryKind> kNames[] = {
      {FactoryKind::RobotType, "robot type"},
      {FactoryKind::QualityMeasure, "quality measure"},
      {FactoryKind::SearchEnergy, "search energy"},
      {FactoryKind::Planner, "planner"}};
  return kNames;
}

std::optional<Registry::Entry> Registry::find(FactoryKind kind, const std::string& name) {
  std::lock_guard lock(mutex_);
  auto it = entries_.find(Key{kind, name});
  if (it == entries_.end() && loader_.loadProviding(kind, name))
    it = entries_.find(Key{kind, name});
  if (it == entries_.end()) return std::nullopt;
  return it->second;
}

void Registry::throwUnknown(FactoryKind kind, const std::string& name) {
  loader_.loadAll();  // so the message lists everything the path offers
  std::string message =
      fmt::format("unknown {} '{}'; available: {}; plugin search path: {}", nameOf(kind), name,
                  fmt::join(names(kind), ", "), loader_.describeSearchPath());
  for (const PluginInfo& failed : loader_.failures())
    message += fmt::format("; plugin {} failed to load: {}", failed.file.string(), failed.error);
  throw Error(message);
}

std::shared_ptr<const RobotType> Registry::robotType(const std::string& name) {
  std::lock_guard lock(mutex_);
  if (!find(FactoryKind::RobotType, name)) throwUnknown(FactoryKind::RobotType, name);
  Entry& entry = entries_.at(Key{FactoryKind::RobotType, name});
  if (!entry.robotTypeInstance) {
    entry.robotTypeInstance =
        callFactory(fmt::format("robot type '{}'", name), entry.from, entry.robotType);
    if (!entry.robotTypeInstance)
      throw Error(fmt::format("the factory of robot type '{}' ({}) made nothing", name,
                              entry.from.describe()));
  }
  return entry.robotTypeInstance;
}

std::unique_ptr<QualityMeasure> Registry::makeQualityMeasure(const std::string& name) {
  std::optional<Entry> entry = find(FactoryKind::QualityMeasure, name);
  if (!entry) throwUnknown(FactoryKind::QualityMeasure, name);
  std::unique_ptr<QualityMeasure> measure =
      callFactory(fmt::format("quality measure '{}'", name), entry->from, entry->qualityMeasure);
  if (!measure)
    throw Error(fmt::format("the factory of quality measure '{}' ({}) made nothing", name,
                            entry->from.describe()));
  return measure;
}

std::unique_ptr<SearchEnergy> Registry::makeSearchEnergy(const std::string& name) {
  const std::string canonical = canonicalEnergyName(name);
  std::optional<Entry> entry = find(FactoryKind::SearchEnergy, canonical);
  if (!entry) throwUnknown(FactoryKind::SearchEnergy, name);
  std::unique_ptr<SearchEnergy> energy =
      callFactory(fmt::format("search energy '{}'", canonical), entry->from, entry->searchEnergy);
  if (!energy)
    throw Error(fmt::format("the factory of search energy '{}' ({}) made nothing", canonical,
                            entry->from.describe()));
  return energy;
}

std::unique_ptr<Planner> Registry::makePlanner(const std::string& name,
                                               const PlanningRequest& request) {
  std::optional<Entry> entry = find(FactoryKind::Planner, name);
  if (!entry) throwUnknown(FactoryKind::Planner, name);
  PlanningRequest resolved = request;
  if (!resolved.energyByName)
    resolved.energyByName = [this](const std::string& energy) { return makeSearchEnergy(energy); };
  std::unique_ptr<Planner> planner = callFactory(fmt::format("planner '{}'", name), entry->from,
                                                 [&] { return entry->planner(resolved); });
  if (!planner)
    throw Error(
        fmt::format("the factory of planner '{}' ({}) made nothing", name, entry->from.describe()));
  return planner;
}

void registerQualityMeasure(const std::string& name, QualityMeasureFactory factory) {
  Registry::global().addQualityMeasure(name, std::move(factory));
}

std::unique_ptr<QualityMeasure> makeQualityMeasure(const std::string& name) {
  return Registry::global().makeQualityMeasure(name);
}

std::vector<std::string> qualityMeasureNames() {
  return Registry::global().names(FactoryKind::QualityMeasure);
}

}  // namespace graspkit
