#pragma once
// How the command line shows the engine's warnings on stderr: every kind but those silenced
// (--no-warn KIND), none with -q, and a message that repeats (the same unknown tag on 300 lines
// of a file) shown a few times, then counted once at the end. -v shows every repeat.

#include <map>
#include <mutex>
#include <ostream>
#include <set>
#include <string>
#include <utility>

#include "graspkit/base/log.hpp"

namespace graspkit::cli {

class WarningReporter {
 public:
  struct Settings {
    bool quiet = false;
    std::set<WarningKind> silenced;
    int shownRepeats = 3;  // of one message; 0 shows them all
  };

  WarningReporter(Settings settings, std::ostream& out);

  void report(const Warning& warning);
  // One line per message that repeated past what was shown; call once, before exiting.
  void summarize();

 private:
  Settings settings_;
  std::ostream& out_;
  std::mutex mutex_;  // planner threads may warn at once
  std::map<std::pair<WarningKind, std::string>, int> seen_;
};

}  // namespace graspkit::cli
