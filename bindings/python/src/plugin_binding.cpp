// Plugins and what the registry holds: graspkit.plugins(), load_plugin() and the names of robot
// types, quality measures, search energies and planners.

#include "graspkit/plugin/plugin_loader.hpp"
#include "graspkit/plugin/registry.hpp"
#include "python_support.hpp"

namespace graspkit::python {
namespace {

py::dict toDict(const PluginInfo& info) {
  py::dict d;
  d["file"] = info.file.string();
  d["name"] = info.name;
  d["version"] = info.version;
  d["loaded"] = info.loaded;
  d["error"] = info.error;
  py::list provides;
  for (const auto& [kind, name] : info.provides)
    provides.append(py::make_tuple(nameOf(kind), name));
  d["provides"] = provides;
  return d;
}

// The registry's names and those the plugins on the search path would add, none of them loaded.
std::vector<std::string> names(FactoryKind kind) {
  std::vector<std::string> list = Registry::global().plugins().availableNames(kind);
  flushWarnings();
  return list;
}

}  // namespace

void bindPlugins(py::module_& m) {
  m.def(
      "plugins",
      [] {
        return withWarnings([] {
          py::list out;
          for (const PluginInfo& info : Registry::global().plugins().survey())
            out.append(toDict(info));
          return out;
        });
      },
      "Every plugin on the search path ($GRASPKIT_PLUGIN_PATH, then beside libgraspkit), as a "
      "child process found it (none is loaded into this one): "
      "[{'file', 'name', 'version', 'loaded', 'error', 'provides': [(kind, name), ...]}].");
  m.def(
      "load_plugin",
      [](const std::filesystem::path& file) {
        return withWarnings([&] {
          const PluginInfo& info = Registry::global().plugins().load(file);
          return toDict(info);
        });
      },
      py::arg("file"), "Loads one plugin file; graspkit.Error naming the file when it cannot.");
  m.def("robot_types", [] { return names(FactoryKind::RobotType); });
  m.def("quality_measures", [] { return names(FactoryKind::QualityMeasure); });
  m.def("energies", [] { return names(FactoryKind::SearchEnergy); });
  m.def("planners", [] { return names(FactoryKind::Planner); });
}

}  // namespace graspkit::python
