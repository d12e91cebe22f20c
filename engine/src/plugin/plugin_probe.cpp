#include "plugin/plugin_probe.hpp"

#include <fcntl.h>
#include <poll.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <csignal>
#include <cstring>
#include <optional>
#include <string_view>

#include <fmt/format.h>

#include "graspkit/base/error.hpp"
#include "plugin/plugin_file.hpp"

namespace graspkit::plugin {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

// The child's report, one line per fact, fields separated by tabs:
//   begin <i> | name <name> <version> | provides <kind> <name> | error <text> | end <i>
// Text from the plugin has its tabs and newlines turned into spaces.
std::string field(std::string_view text) {
  std::string out(text);
  for (char& c : out)
    if (c == '\t' || c == '\n') c = ' ';
  return out;
}

void writeAll(int fd, std::string_view text) {
  while (!text.empty()) {
    const ssize_t written = ::write(fd, text.data(), text.size());
    if (written < 0 && errno == EINTR) continue;
    if (written <= 0) ::_exit(120);  // the parent is gone
    text.remove_prefix(static_cast<std::size_t>(written));
  }
}

// In the child: open each file from `first` on, reporting as it goes, then end the process
// without running the host's exit handlers or destructors.
[[noreturn]] void runChild(int fd, const std::vector<fs::path>& files, std::size_t first) {
  // What a plugin prints while it loads here must not reach the host's standard output, which
  // may be carrying JSON: it is thrown away (its standard error is kept, for its crash reports).
  if (const int null = ::open("/dev/null", O_WRONLY | O_CLOEXEC); null >= 0) {
    ::dup2(null, STDOUT_FILENO);
    ::close(null);
  }
  for (std::size_t i = first; i < files.size(); ++i) {
    writeAll(fd, fmt::format("begin\t{}\n", i));
    const OpenedPlugin opened = openPlugin(files[i]);
    const PluginInfo& info = opened.info;
    std::string report;
    if (!info.name.empty())
      report += fmt::format("name\t{}\t{}\n", field(info.name), field(info.version));
    for (const auto& [kind, name] : info.provides)
      report += fmt::format("provides\t{}\t{}\n", static_cast<int>(kind), field(name));
    if (!info.error.empty()) report += fmt::format("error\t{}\n", field(info.error));
    report += fmt::format("end\t{}\n", i);
    writeAll(fd, report);
  }
  ::_exit(0);
}

std::vector<std::string_view> split(std::string_view line) {
  std::vector<std::string_view> parts;
  for (std::size_t start = 0;;) {
    const std::size_t tab = line.find('\t', start);
    parts.push_back(line.substr(start, tab == std::string_view::npos ? line.npos : tab - start));
    if (tab == std::string_view::npos) return parts;
    start = tab + 1;
  }
}

// Why a child stopped before finishing the plugin it had begun.
std::string stopReason(int status, bool timed_out, std::chrono::milliseconds timeout) {
  if (timed_out)
    return fmt::format("did not finish loading within {} s (probed in a child process, killed)",
                       timeout.count() / 1000.0);
  if (WIFSIGNALED(status)) {
    const int signal = WTERMSIG(status);
    const char* name = strsignal(signal);
    return fmt::format("crashed while loading: signal {} ({}) in a child process", signal,
                       name ? name : "unknown");
  }
  if (WIFEXITED(status))
    return fmt::format("ended the process while loading (exit status {}) in a child process",
                       WEXITSTATUS(status));
  return "stopped the process while loading (in a child process)";
}

class ChildRun {
 public:
  ChildRun(const std::vector<fs::path>& files, std::vector<PluginInfo>& results,
           std::chrono::milliseconds timeout)
      : files_(files), results_(results), timeout_(timeout) {}

  // Probes files from `first` on in one child; returns the index after the last file settled.
  std::size_t run(std::size_t first) {
    int fds[2];
    if (::pipe2(fds, O_CLOEXEC) != 0)
      throw Error(fmt::format("cannot probe plugins: pipe: {}", std::strerror(errno)));
    const pid_t child = ::fork();
    if (child < 0) {
      const int error = errno;
      ::close(fds[0]);
      ::close(fds[1]);
      throw Error(fmt::format("cannot probe plugins: fork: {}", std::strerror(error)));
    }
    if (child == 0) {
      ::close(fds[0]);
      runChild(fds[1], files_, first);
    }
    ::close(fds[1]);
    next_ = first;
    const bool timed_out = readReports(fds[0]);
    ::close(fds[0]);
    if (timed_out) ::kill(child, SIGKILL);
    int status = 0;
    while (::waitpid(child, &status, 0) < 0 && errno == EINTR) {
    }
    if (current_) {  // begun, never ended: this plugin stopped the child
      PluginInfo& info = results_[*current_];
      info = PluginInfo{};
      info.file = files_[*current_];
      info.error = stopReason(status, timed_out, timeout_);
      return *current_ + 1;
    }
    if (next_ == first && first < files_.size()) {  // the child died before its first report
      results_[first].file = files_[first];
      results_[first].error = stopReason(status, timed_out, timeout_);
      return first + 1;
    }
    return next_;
  }

 private:
  // Reads the child's lines until it closes the pipe; true when a plugin overran the timeout.
  bool readReports(int fd) {
    std::string buffer;
    Clock::time_point deadline = Clock::now() + timeout_;
    char chunk[4096];
    for (;;) {
      const auto left =
          std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
      if (left <= 0) return true;
      pollfd p{fd, POLLIN, 0};
      const int ready = ::poll(&p, 1, static_cast<int>(std::min<long long>(left, 1 << 30)));
      if (ready < 0 && errno == EINTR) continue;
      if (ready == 0) return true;
      const ssize_t got = ::read(fd, chunk, sizeof chunk);
      if (got < 0 && errno == EINTR) continue;
      if (got <= 0) return false;
      buffer.append(chunk, static_cast<std::size_t>(got));
      for (std::size_t end; (end = buffer.find('\n')) != std::string::npos;) {
        if (handle(std::string_view(buffer).substr(0, end))) deadline = Clock::now() + timeout_;
        buffer.erase(0, end + 1);
      }
    }
  }

  // One report line; true when it begins a plugin (its own time limit starts).
  bool handle(std::string_view line) {
    const std::vector<std::string_view> parts = split(line);
    const std::string_view tag = parts[0];
    if (tag == "begin" && parts.size() == 2) {
      std::size_t index = 0;
      const auto [end, error] =
          std::from_chars(parts[1].data(), parts[1].data() + parts[1].size(), index);
      if (error != std::errc{} || end != parts[1].data() + parts[1].size() ||
          index >= files_.size())
        return false;  // not the child's line (a plugin may write to any descriptor)
      current_ = index;
      results_[*current_] = PluginInfo{};
      results_[*current_].file = files_[*current_];
      return true;
    }
    if (!current_) return false;
    PluginInfo& info = results_[*current_];
    if (tag == "name" && parts.size() == 3) {
      info.name = parts[1];
      info.version = parts[2];
    } else if (tag == "provides" && parts.size() == 3 && parts[1].size() == 1 &&
               parts[1][0] >= '0' && parts[1][0] <= '3') {
      info.provides.emplace_back(static_cast<FactoryKind>(parts[1][0] - '0'),
                                 std::string(parts[2]));
    } else if (tag == "error" && parts.size() == 2) {
      info.error = parts[1];
    } else if (tag == "end") {
      info.loaded = info.error.empty();  // here: opened cleanly in the child
      next_ = *current_ + 1;
      current_.reset();
    }
    return false;
  }

  const std::vector<fs::path>& files_;
  std::vector<PluginInfo>& results_;
  std::chrono::milliseconds timeout_;
  std::optional<std::size_t> current_;
  std::size_t next_ = 0;
};

}  // namespace

std::vector<PluginInfo> probePlugins(const std::vector<fs::path>& files,
                                     std::chrono::milliseconds timeout) {
  std::vector<PluginInfo> results(files.size());
  ChildRun run(files, results, timeout);
  for (std::size_t next = 0; next < files.size();) next = run.run(next);
  return results;
}

}  // namespace graspkit::plugin
