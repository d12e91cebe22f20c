// Prints to standard output while it loads (a static constructor and its register function), and
// is otherwise well-formed: graspkit's own standard output (--json) must stay clean of it.
#include <cstdio>

#include <memory>
#include <string>

#include "graspkit/grasp/quality.hpp"
#include "graspkit/plugin/plugin.hpp"
#include "graspkit/plugin/registry.hpp"

namespace {

class Constant final : public graspkit::QualityMeasure {
 public:
  std::string name() const override { return "corpus_noisy"; }
  double evaluate(const graspkit::GraspWrenchSpace&) const override { return 1.0; }
};

const int printed_at_load = std::printf("NOISE from a static constructor\n");

void registerNoisy(graspkit::Registrar& registrar) {
  std::printf("NOISE from the register function {\"not\": \"json\"\n");
  std::fflush(stdout);
  registrar.addQualityMeasure("corpus_noisy", [] { return std::make_unique<Constant>(); });
}

}  // namespace

GRASPKIT_PLUGIN("corpus_prints", "1.0", registerNoisy)
