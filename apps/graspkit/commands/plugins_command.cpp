// `graspkit plugins`: what the plugin search path offers, plugin by plugin, and why any plugin
// failed to load.

#include <nlohmann/json.hpp>

#include "commands/plugins_command.hpp"
#include "graspkit/plugin/registry.hpp"

namespace graspkit::cli {
namespace {

using nlohmann::json;

constexpr FactoryKind kKinds[] = {FactoryKind::RobotType, FactoryKind::QualityMeasure,
                                  FactoryKind::SearchEnergy, FactoryKind::Planner};

const char* jsonKey(FactoryKind kind) {
  switch (kind) {
    case FactoryKind::RobotType:
      return "robot_types";
    case FactoryKind::QualityMeasure:
      return "quality_measures";
    case FactoryKind::SearchEnergy:
      return "search_energies";
    case FactoryKind::Planner:
      return "planners";
  }
  return "other";
}

// {"robot_types": [...], "quality_measures": [...], "search_energies": [...], "planners": [...]}
json providesJson(const std::vector<std::pair<FactoryKind, std::string>>& provides) {
  json j = json::object();
  for (FactoryKind kind : kKinds) j[jsonKey(kind)] = json::array();
  for (const auto& [kind, name] : provides) j[jsonKey(kind)].push_back(name);
  return j;
}

json pluginsJson(Registry& registry, const std::vector<PluginInfo>& plugins) {
  json j;
  j["search_path"] = json::array();
  for (const auto& folder : registry.plugins().searchPath()) j["search_path"].push_back(folder);
  std::vector<std::pair<FactoryKind, std::string>> builtin;
  for (FactoryKind kind : kKinds)
    for (const std::string& name : registry.names(kind))
      if (registry.provenance(kind, name)->plugin.empty()) builtin.emplace_back(kind, name);
  j["builtin"] = providesJson(builtin);
  j["plugins"] = json::array();
  for (const PluginInfo& info : plugins) {
    json p = {{"file", info.file}, {"loaded", info.loaded}};
    if (!info.name.empty()) p["name"] = info.name;
    if (!info.version.empty()) p["version"] = info.version;
    if (info.loaded)
      p["provides"] = providesJson(info.provides);
    else
      p["error"] = info.error;
    j["plugins"].push_back(p);
  }
  return j;
}

void printText(Registry& registry, const std::vector<PluginInfo>& plugins, std::ostream& out) {
  out << "plugin search path:\n";
  for (const auto& folder : registry.plugins().searchPath()) out << "  " << folder.string() << "\n";
  for (const PluginInfo& info : plugins) {
    if (info.loaded)
      out << info.name << " " << info.version << " (" << info.file.string()
          << "): " << describeProvides(info) << "\n";
    else
      out << "FAILED " << info.file.string() << ": " << info.error << "\n";
  }
}

}  // namespace

void addPluginsCommand(CLI::App& app, PluginsOptions& options) {
  CLI::App* cmd = app.add_subcommand(
      "plugins",
      "List the plugins on the search path (GRASPKIT_PLUGIN_PATH, then beside the "
      "engine, then the install folder) and what each provides");
  cmd->add_flag("--json", options.json, "Print one JSON object");
}

int runPlugins(const PluginsOptions& options, std::ostream& out) {
  Registry& registry = Registry::global();
  const std::vector<PluginInfo> plugins = registry.plugins().survey();
  if (options.json)
    // A plugin's error text is its own (an exception's what()): bytes JSON cannot hold are
    // replaced, not a failure of the listing.
    out << pluginsJson(registry, plugins).dump(2, ' ', false, json::error_handler_t::replace)
        << "\n";
  else
    printText(registry, plugins, out);
  for (const PluginInfo& info : plugins)
    if (!info.loaded) return 1;
  return 0;
}

}  // namespace graspkit::cli
