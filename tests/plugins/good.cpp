// A well-formed plugin: one robot type and one quality measure.
#include "corpus_plugin.hpp"
#include "graspkit/plugin/plugin.hpp"

namespace {

class Constant final : public graspkit::QualityMeasure {
 public:
  std::string name() const override { return "corpus_constant"; }
  double evaluate(const graspkit::GraspWrenchSpace&) const override { return 42.0; }
};

void registerGood(graspkit::Registrar& registrar) {
  registrar.addRobotType("CorpusGripper", corpus::palmIgnoresFirstLink());
  registrar.addQualityMeasure("corpus_constant", [] { return std::make_unique<Constant>(); });
}

}  // namespace

GRASPKIT_PLUGIN("corpus_good", "2.3.4", registerGood)
