#include "graspkit/base/input_file.hpp"

#include <fstream>

#include <fmt/format.h>

#include "graspkit/base/error.hpp"
#include "graspkit/base/utf8.hpp"

namespace graspkit {

namespace fs = std::filesystem;

namespace {

ReadGuard& threadGuard() {
  thread_local ReadGuard guard;
  return guard;
}

}  // namespace

ScopedReadGuard::ScopedReadGuard(ReadGuard guard) : previous_(std::move(threadGuard())) {
  threadGuard() = std::move(guard);
}

ScopedReadGuard::~ScopedReadGuard() {
  threadGuard() = std::move(previous_);
}

bool holdsNul(const fs::path& file) {
  return file.native().find('\0') != fs::path::string_type::npos;
}

void checkInputFile(const fs::path& file) {
  if (holdsNul(file)) {
    std::string shown = file.string();
    for (char& c : shown)
      if (c == '\0') c = '?';
    throw Error(SourceLocation{shown}, "the path holds a NUL byte");
  }
  // Paths end up in saved worlds, plans and datasets (XML, JSON, HDF5 strings), which hold UTF-8
  // text: a file whose path is not UTF-8 would be saved into a file that cannot be read back.
  if (firstInvalidUtf8(file.native()))
    throw Error(SourceLocation{file.string()}, "the path is not UTF-8 text");
  // The guard comes before any look at the file, so that a refused path tells nothing, not even
  // whether it exists.
  if (const ReadGuard& guard = threadGuard()) guard(file);
  std::error_code ec;
  const fs::file_status status = fs::status(file, ec);
  // A loop of symbolic links or a folder without permission is not "not found": say which.
  if (ec && ec != std::errc::no_such_file_or_directory)
    throw Error(SourceLocation{file.string()}, fmt::format("cannot be read: {}", ec.message()));
  if (!fs::exists(status)) throw Error(SourceLocation{file.string()}, "file not found");
  if (!fs::is_regular_file(status)) {
    throw Error(SourceLocation{file.string()},
                "not a regular file (a folder, a FIFO or a device is never read)");
  }
  const std::uintmax_t size = fs::file_size(file, ec);
  if (!ec && size > kMaxInputFileBytes) {
    throw Error(SourceLocation{file.string()},
                fmt::format("the file is {} bytes, more than the {} bytes an input file may hold",
                            size, kMaxInputFileBytes));
  }
}

bool inputFileRefused(const fs::path& file) {
  if (const ReadGuard& guard = threadGuard()) {
    try {
      guard(file);
    } catch (const Error&) {
      return true;
    }
  }
  return false;
}

bool inputFileFound(const fs::path& file) {
  if (holdsNul(file) || inputFileRefused(file)) return false;  // never looked at
  std::error_code ec;
  const fs::file_status status = fs::status(file, ec);
  return fs::exists(status) || (ec && ec != std::errc::no_such_file_or_directory);
}

std::string readInputFile(const fs::path& file) {
  checkInputFile(file);
  std::ifstream in(file, std::ios::binary);
  if (!in) throw Error(SourceLocation{file.string()}, "cannot open the file for reading");
  std::string text;
  char buffer[1 << 16];
  // Read to the end rather than trust the size seen before: the file may have grown since.
  while (in.read(buffer, sizeof buffer) || in.gcount() > 0) {
    text.append(buffer, static_cast<std::size_t>(in.gcount()));
    if (text.size() > kMaxInputFileBytes) {
      throw Error(SourceLocation{file.string()},
                  fmt::format("the file holds more than the {} bytes an input file may hold",
                              kMaxInputFileBytes));
    }
  }
  if (in.bad()) throw Error(SourceLocation{file.string()}, "read error");
  return text;
}

}  // namespace graspkit
