// Behaves the first time it is loaded and crashes (SIGSEGV) every time after: it leaves a marker
// file (GRASPKIT_TEST_MARKER) on its first load. The probe's child loads it first, so a host that
// loads it again, only to list it, would crash.
#include <csignal>
#include <cstdlib>
#include <fstream>

#include <memory>
#include <string>

#include "graspkit/grasp/quality.hpp"
#include "graspkit/plugin/plugin.hpp"
#include "graspkit/plugin/registry.hpp"

namespace {

class Constant final : public graspkit::QualityMeasure {
 public:
  std::string name() const override { return "corpus_second_load"; }
  double evaluate(const graspkit::GraspWrenchSpace&) const override { return 2.0; }
};

void registerOnce(graspkit::Registrar& registrar) {
  const char* marker = std::getenv("GRASPKIT_TEST_MARKER");
  if (marker && std::ifstream(marker).good()) std::raise(SIGSEGV);
  if (marker) std::ofstream(marker) << "loaded once\n";
  registrar.addQualityMeasure("corpus_second_load", [] { return std::make_unique<Constant>(); });
}

}  // namespace

GRASPKIT_PLUGIN("corpus_second_load", "1.0", registerOnce)
