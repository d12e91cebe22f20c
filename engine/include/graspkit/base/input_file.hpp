#pragma once
// The one gate for every file the engine reads: model XML, geometry, eigengrasp and
// virtual-contact files, and the files plugins read for a request (the list planner's states).
//
// readInputFile() refuses, with an error naming the file:
//   - a path holding a NUL byte (the operating system would open only the part before it, which
//     is not the file any check saw);
//   - whatever the thread's read guard refuses (a sandboxed script's folders: a model file a
//     script wrote cannot name a file outside them as its geometry);
//   - anything but a regular file (a folder, a FIFO or a device could block the reader forever);
//   - a file larger than kMaxInputFileBytes.
// Files are read whole: no reader trusts a size written inside the file.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>

namespace graspkit {

inline constexpr std::uintmax_t kMaxInputFileBytes = std::uintmax_t{1} << 30;  // 1 GiB

// Throws graspkit::Error when `file` may not be read.
using ReadGuard = std::function<void(const std::filesystem::path& file)>;

// Installs `guard` on the calling thread for the scope's lifetime (the one it replaces comes
// back when the scope ends). Models load on the thread that asks for them, so a host that runs
// untrusted scripts installs its policy around each call into them.
class ScopedReadGuard {
 public:
  explicit ScopedReadGuard(ReadGuard guard);
  ~ScopedReadGuard();
  ScopedReadGuard(const ScopedReadGuard&) = delete;
  ScopedReadGuard& operator=(const ScopedReadGuard&) = delete;

 private:
  ReadGuard previous_;
};

// Whether a path holds a NUL byte.
bool holdsNul(const std::filesystem::path& file);

// The checks above, without reading. Throws graspkit::Error naming the file.
void checkInputFile(const std::filesystem::path& file);

// For a reader that looks for a file in several places: whether `file` is there, asking the read
// guard first. A path the guard refuses is never looked at and counts as not there, so that a
// search tells nothing about files outside a script's folders. A path whose status cannot be read
// (a loop of symbolic links, no permission) counts as there, so that reading it names the reason.
// A reader with one place to look calls checkInputFile() instead, which gives the refusal.
bool inputFileFound(const std::filesystem::path& file);

// Whether the thread's read guard refuses `file` (without looking at the file).
bool inputFileRefused(const std::filesystem::path& file);

// The whole content of `file`, after checkInputFile(). Throws graspkit::Error naming the file.
std::string readInputFile(const std::filesystem::path& file);

}  // namespace graspkit
