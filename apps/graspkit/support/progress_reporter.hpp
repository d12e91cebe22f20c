#pragma once
// How every long command shows progress on stderr (`plan`, `test`, and a script's
// graspkit.progress() and planner:run): on a terminal, one line redrawn in place, at most a few
// times a second; otherwise (a CI log, a pipe) a plain line every few seconds and one at the end;
// with --quiet, nothing. stdout is never touched, so --json output stays clean.

#include <chrono>
#include <mutex>
#include <string>
#include <string_view>

namespace graspkit::cli {

// "m:ss" or "h:mm:ss"; "--:--" for a negative or huge (unknown) time.
std::string clockTime(double seconds);

class ProgressReporter {
 public:
  struct Settings {
    bool enabled = true;        // false with --quiet
    bool terminal = false;      // stderr is a terminal: redraw one line
    double redrawEvery = 0.25;  // seconds, on a terminal
    double printEvery = 5.0;    // seconds, elsewhere
  };

  // Progress on stderr unless quiet; a terminal gets the redrawn line.
  static Settings forStderr(bool quiet);

  explicit ProgressReporter(Settings settings);
  ~ProgressReporter();
  ProgressReporter(const ProgressReporter&) = delete;
  ProgressReporter& operator=(const ProgressReporter&) = delete;

  // `fraction` of the work done (0..1; negative when unknown) and what is being done. Calls
  // closer together than the redraw (or print) interval are dropped, except the first on a
  // terminal; elsewhere the first line comes one interval after the start.
  void update(double fraction, std::string_view text);
  // The last state, always shown (a plain line, or the redrawn line ended by a newline).
  void finish(double fraction, std::string_view text);
  // Erases the redrawn line, so that other output (a result, a warning) starts on a clean line.
  void clear();

 private:
  void show(double fraction, std::string_view text, bool last);

  Settings settings_;
  std::mutex mutex_;
  std::chrono::steady_clock::time_point last_shown_;
  bool line_drawn_ = false;
  bool anything_shown_ = false;
};

}  // namespace graspkit::cli
