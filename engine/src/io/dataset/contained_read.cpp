#include "io/dataset/contained_read.hpp"

#include <fcntl.h>
#include <poll.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <csignal>
#include <cstring>
#include <vector>

#include <fmt/format.h>

#include "graspkit/base/error.hpp"

#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define GRASPKIT_UNDER_ASAN 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__)
#define GRASPKIT_UNDER_ASAN 1
#endif

namespace graspkit {
namespace {

using Clock = std::chrono::steady_clock;

void writeAll(int fd, std::string_view text) {
  while (!text.empty()) {
    const ssize_t written = ::write(fd, text.data(), text.size());
    if (written < 0 && errno == EINTR) continue;
    if (written <= 0) ::_exit(121);  // the parent is gone
    text.remove_prefix(static_cast<std::size_t>(written));
  }
}

// The child's report: 'O' and the bytes, or 'E' and an Error's message.
[[noreturn]] void runChild(int fd, const std::function<std::string()>& read,
                           std::size_t memory_limit) {
  // A crash here is the reader's, and the parent reports it: the host's handlers (a fuzzer's
  // that saves the input, a crash reporter's) must not act on it as if the host had crashed.
  for (const int signal : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT}) std::signal(signal, SIG_DFL);
#ifndef GRASPKIT_UNDER_ASAN
  const rlimit limit{memory_limit, memory_limit};
  ::setrlimit(RLIMIT_AS, &limit);
#else
  (void)memory_limit;
#endif
  std::string report;
  try {
    const std::string bytes = read();
    report.reserve(bytes.size() + 1);
    report.push_back('O');
    report.append(bytes);
  } catch (const Error& e) {
    // The error's parts, NUL-separated, so that the parent throws the same located error.
    report = fmt::format("E{}{}{}{}{}{}{}", e.where().file, '\0', e.where().line, '\0',
                         e.where().element, '\0', e.message());
  } catch (const std::bad_alloc&) {
    ::_exit(122);
  }
  writeAll(fd, report);
  ::_exit(0);
}

// Reads until the child closes the pipe; false when `timeout` passed first.
bool readReport(int fd, std::chrono::seconds timeout, std::string& report) {
  const Clock::time_point deadline = Clock::now() + timeout;
  char chunk[1 << 16];
  for (;;) {
    const auto left =
        std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
    if (left <= 0) return false;
    pollfd p{fd, POLLIN, 0};
    const int ready = ::poll(&p, 1, static_cast<int>(std::min<long long>(left, 1 << 30)));
    if (ready < 0 && errno == EINTR) continue;
    if (ready == 0) return false;
    const ssize_t got = ::read(fd, chunk, sizeof chunk);
    if (got < 0 && errno == EINTR) continue;
    if (got <= 0) return true;
    report.append(chunk, static_cast<std::size_t>(got));
  }
}

std::string failure(int status, bool timed_out, std::chrono::seconds timeout) {
  if (timed_out) return fmt::format("reading it took longer than {} s (stopped)", timeout.count());
  if (WIFSIGNALED(status)) {
    const char* name = strsignal(WTERMSIG(status));
    return fmt::format("the reader crashed on it (signal {}, {}; contained in a child process)",
                       WTERMSIG(status), name ? name : "unknown");
  }
  if (WIFEXITED(status) && WEXITSTATUS(status) == 122) return "reading it ran out of memory";
  return fmt::format("the reader stopped on it (exit status {} in a child process)",
                     WIFEXITED(status) ? WEXITSTATUS(status) : -1);
}

}  // namespace

std::string readInChild(const std::function<std::string()>& read, const std::filesystem::path& file,
                        std::chrono::seconds timeout, std::size_t memoryLimit) {
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0)
    throw Error(SourceLocation{file.string()},
                fmt::format("cannot read: pipe: {}", std::strerror(errno)));
  const pid_t child = ::fork();
  if (child < 0) {
    const int error = errno;
    ::close(fds[0]);
    ::close(fds[1]);
    throw Error(SourceLocation{file.string()},
                fmt::format("cannot read: fork: {}", std::strerror(error)));
  }
  if (child == 0) {
    ::close(fds[0]);
    runChild(fds[1], read, memoryLimit);
  }
  ::close(fds[1]);
  std::string report;
  const bool finished = readReport(fds[0], timeout, report);
  ::close(fds[0]);
  if (!finished) ::kill(child, SIGKILL);
  int status = 0;
  while (::waitpid(child, &status, 0) < 0 && errno == EINTR) {
  }
  const bool clean = finished && WIFEXITED(status) && WEXITSTATUS(status) == 0;
  if (!clean || report.empty())
    throw Error(SourceLocation{file.string()}, failure(status, !finished, timeout));
  if (report[0] == 'E') {
    std::vector<std::string> parts;
    for (std::size_t at = 1;;) {
      const std::size_t end = report.find('\0', at);
      parts.push_back(report.substr(at, parts.size() < 3 ? end - at : std::string::npos));
      if (parts.size() == 4 || end == std::string::npos) break;
      at = end + 1;
    }
    parts.resize(4);
    int line = 0;
    std::from_chars(parts[1].data(), parts[1].data() + parts[1].size(), line);
    throw Error(SourceLocation{parts[0], line, parts[2]}, parts[3]);
  }
  return report.substr(1);
}

}  // namespace graspkit
