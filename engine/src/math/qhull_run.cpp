#include "math/qhull_run.hpp"

#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string_view>

extern "C" {
#include <libqhull_r/qhull_ra.h>
}

namespace graspkit::detail {
namespace {

// qhull writes errors and warnings to a FILE. A memory stream keeps them off the terminal and
// lets the first error line become the failure reason.
class MessageBuffer {
 public:
  MessageBuffer() : file_(open_memstream(&data_, &size_)) {}
  ~MessageBuffer() {
    if (file_) std::fclose(file_);
    std::free(data_);
  }
  MessageBuffer(const MessageBuffer&) = delete;
  MessageBuffer& operator=(const MessageBuffer&) = delete;

  FILE* file() const { return file_; }

  // The first line that names a qhull error (e.g. "QH6154 Qhull precision error: initial
  // simplex is flat ..."), else the first line.
  std::string firstError() {
    if (!file_) return {};
    std::fflush(file_);
    const std::string_view text(data_ ? data_ : "", size_);
    std::string_view first;
    std::size_t start = 0;
    while (start < text.size()) {
      std::size_t end = text.find('\n', start);
      if (end == std::string_view::npos) end = text.size();
      const std::string_view line = text.substr(start, end - start);
      if (first.empty() && !line.empty()) first = line;
      if (line.find("error") != std::string_view::npos) return std::string(line);
      start = end + 1;
    }
    return std::string(first);
  }

 private:
  char* data_ = nullptr;
  std::size_t size_ = 0;
  FILE* file_ = nullptr;
};

}  // namespace

std::optional<std::string> runQhull(std::vector<double>& coords, int dim, const char* options,
                                    const std::function<void(qhT* qh)>& read) {
  const int count = static_cast<int>(coords.size() / static_cast<std::size_t>(dim));
  MessageBuffer messages;
  // /dev/null would do if the memory stream failed; a null errfile would mean stderr.
  FILE* err = messages.file();
  std::unique_ptr<FILE, int (*)(FILE*)> null_file(nullptr, &std::fclose);
  if (!err) {
    null_file.reset(std::fopen("/dev/null", "w"));
    err = null_file.get();
  }
  if (!err) return "cannot open a stream for qhull's messages";

  // qhT holds all of qhull's state (a few kB): one per call makes calls thread-safe.
  auto qh_owner = std::make_unique<qhT>();
  qhT* qh = qh_owner.get();
  qh_zero(qh, err);
  std::string command = std::string("qhull ") + options;
  const int exitcode =
      qh_new_qhull(qh, dim, count, coords.data(), False, command.data(), nullptr, err);
  std::optional<std::string> failure;
  if (exitcode == 0) {
    read(qh);
  } else {
    std::string reason = messages.firstError();
    failure = reason.empty() ? "qhull failed with exit code " + std::to_string(exitcode)
                             : "qhull: " + reason;
  }
  qh->NOerrexit = True;
  qh_freeqhull(qh, !qh_ALL);
  int curlong = 0, totlong = 0;
  qh_memfreeshort(qh, &curlong, &totlong);
  return failure;
}

}  // namespace graspkit::detail
