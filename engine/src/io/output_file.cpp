#include "graspkit/io/output_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include <fmt/format.h>

#include "graspkit/error.hpp"

namespace graspkit {

namespace fs = std::filesystem;

namespace {

// Room for ".tmp" and a process id within the 255 bytes most file systems allow a name.
constexpr std::size_t kLongestExtendableName = 230;

fs::path temporaryFor(const fs::path& file) {
  const std::string suffix = fmt::format(".tmp{}", ::getpid());
  if (file.filename().native().size() <= kLongestExtendableName) return file.string() + suffix;
  return file.parent_path() / (".graspkit" + suffix);
}

[[noreturn]] void fail(const fs::path& file, const std::string& what, int error) {
  throw Error(SourceLocation{file.string()}, fmt::format("{}: {}", what, std::strerror(error)));
}

// Writes all of `text` to the open descriptor and flushes it to the disk; errno on failure.
int writeAll(int fd, std::string_view text) {
  while (!text.empty()) {
    const ssize_t written = ::write(fd, text.data(), text.size());
    if (written < 0) {
      if (errno == EINTR) continue;
      return errno;
    }
    text.remove_prefix(static_cast<std::size_t>(written));
  }
  return ::fsync(fd) == 0 ? 0 : errno;
}

}  // namespace

void writeFileAtomically(const fs::path& file, std::string_view text) {
  std::error_code ec;
  const fs::file_status target = fs::status(file, ec);
  if (fs::is_regular_file(target) &&
      (target.permissions() & fs::perms::owner_write) == fs::perms::none) {
    throw Error(SourceLocation{file.string()},
                "the file is read-only; make it writable to replace it");
  }
  const fs::path temporary = temporaryFor(file);
  const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) fail(file, "cannot create a temporary file beside it to save", errno);
  const int written = writeAll(fd, text);
  const int closed = ::close(fd) == 0 ? 0 : errno;
  if (written != 0 || closed != 0) {
    fs::remove(temporary, ec);
    fail(file, "writing failed", written != 0 ? written : closed);
  }
  if (::rename(temporary.c_str(), file.c_str()) != 0) {
    const int error = errno;
    fs::remove(temporary, ec);
    fail(file, "cannot replace the file", error);
  }
  // The rename is durable once the folder is flushed too.
  const fs::path folder = file.parent_path().empty() ? fs::path(".") : file.parent_path();
  if (const int dir = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC); dir >= 0) {
    ::fsync(dir);
    ::close(dir);
  }
}

}  // namespace graspkit
