// A robot type whose name is not UTF-8 text (a Latin-1 byte): names are listed in JSON and shown,
// so the plugin is refused.
#include "corpus_plugin.hpp"
#include "graspkit/plugin/plugin.hpp"

namespace {
void registerLatin1(graspkit::Registrar& registrar) {
  registrar.addRobotType("Pr\xe9hension", corpus::palmIgnoresFirstLink());
}
}  // namespace

GRASPKIT_PLUGIN("not_utf8_names", "1.0", registerLatin1)
