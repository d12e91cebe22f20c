#include "support/warning_reporter.hpp"

#include <fmt/format.h>

namespace graspkit::cli {

WarningReporter::WarningReporter(Settings settings, std::ostream& out)
    : settings_(std::move(settings)), out_(out) {}

void WarningReporter::report(const Warning& warning) {
  if (settings_.quiet || settings_.silenced.contains(warning.kind)) return;
  std::lock_guard lock(mutex_);
  const int count = ++seen_[{warning.kind, warning.message}];
  if (settings_.shownRepeats > 0 && count > settings_.shownRepeats) return;
  out_ << "graspkit: warning: " << describe(warning) << "\n";
}

void WarningReporter::summarize() {
  std::lock_guard lock(mutex_);
  if (settings_.shownRepeats <= 0) return;
  for (const auto& [key, count] : seen_) {
    if (count <= settings_.shownRepeats) continue;
    const auto& [kind, message] = key;
    out_ << fmt::format(
        "graspkit: warning: {} more like '{}' (-v shows them, --no-warn {} hides the kind)\n",
        count - settings_.shownRepeats, message, nameOf(kind));
  }
  out_.flush();
}

}  // namespace graspkit::cli
