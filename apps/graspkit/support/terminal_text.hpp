#pragma once
// Text for a terminal. Names read from files (bodies, links, DOFs, objects) reach the screen in
// messages and reports; a name holding escape sequences could retitle the window, move the cursor
// to hide or fake lines, or worse on some terminals. Everything the program prints on its own
// behalf passes through here: control characters other than newline and tab, DEL, the C1
// controls and bytes that are not UTF-8 are written as visible escapes (\x1b, \u009b, \xff).

#include <streambuf>
#include <string>
#include <string_view>

namespace graspkit::cli {

// `text` with every unsafe character written as an escape.
std::string terminalSafe(std::string_view text);

// A stream buffer that passes what it is given to `target` through terminalSafe(), a line at a
// time (so a multi-byte character is never split). Installed on std::cout and std::cerr by
// TerminalSafeStreams.
class TerminalSafeBuffer : public std::streambuf {
 public:
  explicit TerminalSafeBuffer(std::streambuf* target) : target_(target) {}
  ~TerminalSafeBuffer() override;
  std::streambuf* target() const { return target_; }

 protected:
  int_type overflow(int_type c) override;
  std::streamsize xsputn(const char* text, std::streamsize count) override;
  int sync() override;

 private:
  // Writes out the complete lines (all of it when `everything`); false when the target failed.
  bool pass(bool everything);
  std::streambuf* target_;
  std::string pending_;
};

// For its lifetime, std::cout (when `output` is true) and std::cerr print through
// TerminalSafeBuffer. Scripts (run, test) print their own output as they please: the program
// then leaves std::cout alone.
class TerminalSafeStreams {
 public:
  explicit TerminalSafeStreams(bool output);
  ~TerminalSafeStreams();
  TerminalSafeStreams(const TerminalSafeStreams&) = delete;
  TerminalSafeStreams& operator=(const TerminalSafeStreams&) = delete;

 private:
  TerminalSafeBuffer error_;
  TerminalSafeBuffer output_;
  bool output_installed_;
};

}  // namespace graspkit::cli
