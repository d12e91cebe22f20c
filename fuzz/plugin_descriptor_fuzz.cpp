// libFuzzer target for the plugin descriptor and what a register function hands the loader: any
// ABI version and size, null or odd names and versions, a register function that registers any
// mix of kinds and names (empty, repeated, already registered, with no factory) and then returns
// or throws. The loader's promise under test: a plugin is committed whole or not at all (the
// registry then holds exactly its names, or exactly what it held before), every refusal says why,
// and nothing crashes. The code path is the loader's own (openDescriptor, commitPlugin); only
// dlopen is left out.

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

#include "graspkit/grasp/quality.hpp"
#include "graspkit/grasp/robot_type.hpp"
#include "graspkit/planning/planner.hpp"
#include "graspkit/planning/search_energy.hpp"
#include "graspkit/plugin/registry.hpp"
#include "plugin/plugin_file.hpp"

namespace {

using graspkit::FactoryKind;

class Input {
 public:
  Input(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}
  std::uint8_t byte() { return at_ < size_ ? data_[at_++] : 0; }
  std::uint32_t word() {
    std::uint32_t value = 0;
    for (int i = 0; i < 4; ++i) value = value << 8 | byte();
    return value;
  }
  std::string text() {
    std::string out;
    for (int n = byte() % 12; n > 0; --n) out += static_cast<char>(byte());
    return out;
  }

 private:
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t at_ = 0;
};

class NoType final : public graspkit::RobotType {};

// The register function reads what to do from the input of the current run.
Input* current = nullptr;

void registerFromInput(graspkit::Registrar& registrar) {
  Input& in = *current;
  for (int n = in.byte() % 6; n > 0; --n) {
    const std::uint8_t what = in.byte();
    // Names from a small set, so that repeats and clashes with the engine's own names happen.
    static const char* const kNames[] = {"",     "Hand",  "Robot",          "epsilon", "volume",
                                         "mine", "mine2", "CONTACT_ENERGY", "simann"};
    std::string name = kNames[in.byte() % 9];
    if (what & 0x80) name = in.text();
    const bool empty = what & 0x40;
    switch (what % 4) {
      case 0: {
        graspkit::RobotTypeFactory factory;
        if (!empty) factory = [] { return std::make_shared<const NoType>(); };
        registrar.addRobotType(name, factory);
        break;
      }
      case 1: {
        graspkit::QualityMeasureFactory factory;
        if (!empty) factory = [] { return std::unique_ptr<graspkit::QualityMeasure>{}; };
        registrar.addQualityMeasure(name, factory);
        break;
      }
      case 2: {
        graspkit::SearchEnergyFactory factory;
        if (!empty) factory = [] { return std::unique_ptr<graspkit::SearchEnergy>{}; };
        registrar.addSearchEnergy(name, factory);
        break;
      }
      default: {
        graspkit::PlannerFactory factory;
        if (!empty)
          factory = [](const graspkit::PlanningRequest&) {
            return std::unique_ptr<graspkit::Planner>{};
          };
        registrar.addPlanner(name, factory);
        break;
      }
    }
  }
  switch (in.byte() % 8) {
    case 0:
      throw std::runtime_error("register failed");
    case 1:
      throw 7;
    default:
      break;
  }
}

std::vector<std::pair<FactoryKind, std::string>> everything(const graspkit::Registry& registry) {
  std::vector<std::pair<FactoryKind, std::string>> all;
  for (FactoryKind kind : {FactoryKind::RobotType, FactoryKind::QualityMeasure,
                           FactoryKind::SearchEnergy, FactoryKind::Planner})
    for (const std::string& name : registry.names(kind)) all.emplace_back(kind, name);
  return all;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  Input in(data, size);
  current = &in;
  graspkit::Registry registry;
  registry.plugins().setSearchPath(std::vector<std::filesystem::path>{});  // nothing to load
  const auto before = everything(registry);

  const std::uint8_t shape = in.byte();
  graspkit_plugin_descriptor descriptor{};
  descriptor.abi_version = shape & 1 ? in.word() : GRASPKIT_PLUGIN_ABI_VERSION;
  descriptor.descriptor_size = shape & 2 ? in.word() : sizeof(graspkit_plugin_descriptor);
  const std::string name = in.text(), version = in.text();
  descriptor.name = shape & 4 ? nullptr : name.c_str();
  descriptor.version = shape & 8 ? nullptr : version.c_str();
  descriptor.register_factories = shape & 16 ? nullptr : registerFromInput;
  std::vector<graspkit::PluginInfo> loaded;
  if (shape & 32) {  // a plugin of that name is loaded already
    loaded.emplace_back();
    loaded.back().name = name;
    loaded.back().loaded = true;
  }

  const graspkit::PluginInfo info = graspkit::plugin::commitPlugin(
      registry, graspkit::plugin::openDescriptor("fuzz.so", shape & 64 ? nullptr : &descriptor),
      loaded);
  const auto after = everything(registry);
  if (!info.loaded) {
    if (info.error.empty() || after != before || !info.provides.empty()) std::abort();
  } else {
    if (!info.error.empty() || after.size() != before.size() + info.provides.size()) std::abort();
    for (const auto& item : info.provides)
      if (!registry.contains(item.first, item.second)) std::abort();
  }
  current = nullptr;
  return 0;
}
