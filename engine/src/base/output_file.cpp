#include "graspkit/base/output_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include <fmt/format.h>

#include "graspkit/base/error.hpp"
#include "graspkit/base/utf8.hpp"

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

// An unnamed file in `folder` (Linux O_TMPFILE): a process killed while it writes leaves
// nothing behind. -1 where the file system cannot make one (then a named temporary is used).
int openUnnamed(const fs::path& folder) {
#ifdef O_TMPFILE
  return ::open(folder.c_str(), O_TMPFILE | O_WRONLY | O_CLOEXEC, 0644);
#else
  (void)folder;
  errno = EOPNOTSUPP;
  return -1;
#endif
}

// Gives the written, flushed unnamed file `fd` the name `temporary` (so it can be renamed over
// the target); errno on failure.
int nameUnnamed(int fd, const fs::path& temporary) {
  const std::string self = fmt::format("/proc/self/fd/{}", fd);
  if (::linkat(AT_FDCWD, self.c_str(), AT_FDCWD, temporary.c_str(), AT_SYMLINK_FOLLOW) == 0)
    return 0;
  if (errno != EEXIST) return errno;
  // A temporary left by an earlier process with this pid, killed between naming and renaming.
  ::unlink(temporary.c_str());
  return ::linkat(AT_FDCWD, self.c_str(), AT_FDCWD, temporary.c_str(), AT_SYMLINK_FOLLOW) == 0
             ? 0
             : errno;
}

}  // namespace

void checkReplaceable(const fs::path& file) {
  // What graspkit writes, it must be able to read back: the read gate takes UTF-8 paths only.
  if (firstInvalidUtf8(file.native()))
    throw Error(SourceLocation{file.string()}, "the path is not UTF-8 text");
  std::error_code ec;
  const fs::file_status target = fs::status(file, ec);  // through symlinks: what would be lost
  if (fs::exists(target) && !fs::is_regular_file(target)) {
    throw Error(SourceLocation{file.string()},
                fmt::format("not a regular file ({}); graspkit replaces only regular files",
                            fs::is_directory(target) ? "a folder"
                            : fs::is_fifo(target)    ? "a FIFO"
                            : fs::is_character_file(target) || fs::is_block_file(target)
                                ? "a device"
                                : "a special file"));
  }
  if (fs::is_regular_file(target) &&
      (target.permissions() & fs::perms::owner_write) == fs::perms::none) {
    throw Error(SourceLocation{file.string()},
                "the file is read-only; make it writable to replace it");
  }
}

void createOutputFolder(const fs::path& folder) {
  std::error_code ec;
  fs::create_directories(folder, ec);
  if (ec || !fs::is_directory(folder)) {
    throw Error(SourceLocation{folder.string()},
                fmt::format("cannot create the output folder: {}",
                            ec ? ec.message() : std::string("something else stands there")));
  }
}

void writeFileAtomically(const fs::path& file, std::string_view text) {
  std::error_code ec;
  checkReplaceable(file);
  const fs::path folder = file.parent_path().empty() ? fs::path(".") : file.parent_path();
  const fs::path temporary = temporaryFor(file);
  bool named = false;  // whether `temporary` exists and must be removed on failure
  int fd = openUnnamed(folder);
  if (fd < 0 && (errno == ENOENT || errno == ENOTDIR || errno == EACCES || errno == EROFS))
    fail(file, "cannot create a file in its folder to save", errno);
  if (fd < 0) {
    fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd < 0) fail(file, "cannot create a temporary file beside it to save", errno);
    named = true;
  }
  int error = writeAll(fd, text);
  if (error == 0 && !named) {
    error = nameUnnamed(fd, temporary);
    named = error == 0;
  }
  const int closed = ::close(fd) == 0 ? 0 : errno;
  if (error != 0 || closed != 0) {
    if (named) fs::remove(temporary, ec);
    fail(file, "writing failed", error != 0 ? error : closed);
  }
  if (::rename(temporary.c_str(), file.c_str()) != 0) {
    error = errno;
    fs::remove(temporary, ec);
    fail(file, "cannot replace the file", error);
  }
  // The rename is durable once the folder is flushed too.
  if (const int dir = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC); dir >= 0) {
    ::fsync(dir);
    ::close(dir);
  }
}

}  // namespace graspkit
