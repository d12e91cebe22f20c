#include "support/process_runs.hpp"

#include <fmt/format.h>
#include <signal.h>

#include <cerrno>
#include <fstream>
#include <string>

namespace graspkit::cli {

bool processRuns(pid_t pid) {
  if (pid <= 0) return false;
  std::ifstream stat(fmt::format("/proc/{}/stat", pid));
  if (!stat) return ::kill(pid, 0) == 0 || errno != ESRCH;
  std::string line;
  std::getline(stat, line);
  const auto close = line.rfind(')');  // the state follows the command name in parentheses
  return close == std::string::npos || close + 2 >= line.size() || line[close + 2] != 'Z';
}

}  // namespace graspkit::cli
