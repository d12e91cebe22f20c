// A plugin that loads, but whose factories and robot type throw when used: one a standard
// exception, one an int (no std::exception at all). The host must turn each into an error that
// names the plugin, and never terminate.
#include <stdexcept>

#include "graspkit/model/robot.hpp"
#include "graspkit/plugin/plugin.hpp"
#include "graspkit/plugin/registry.hpp"

namespace {

class ConfigureThrowsInt final : public graspkit::RobotType {
 public:
  void configure(graspkit::RobotModel& /*model*/) const override { throw 42; }
};

void registerThrowing(graspkit::Registrar& registrar) {
  registrar.addQualityMeasure("corpus_throws_std",
                              []() -> std::unique_ptr<graspkit::QualityMeasure> {
                                throw std::runtime_error("calibration table missing");
                              });
  registrar.addQualityMeasure("corpus_throws_int",
                              []() -> std::unique_ptr<graspkit::QualityMeasure> { throw 7; });
  registrar.addRobotType("CorpusConfigureThrows",
                         [] { return std::make_shared<const ConfigureThrowsInt>(); });
}

}  // namespace

GRASPKIT_PLUGIN("corpus_throwing", "0.1", registerThrowing)
