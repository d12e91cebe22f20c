#include "support/progress_reporter.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <fmt/format.h>

#include "support/terminal_text.hpp"

namespace graspkit::cli {
namespace {

std::string progressLine(double fraction, std::string_view text) {
  if (fraction < 0) return std::string(text);
  constexpr int kWidth = 20;
  const double f = std::clamp(fraction, 0.0, 1.0);
  const int filled = static_cast<int>(std::lround(f * kWidth));
  return fmt::format("[{:<{}}] {:3.0f}%  {}", std::string(filled, '#'), kWidth, 100.0 * f, text);
}

}  // namespace

ProgressReporter::Settings ProgressReporter::forStderr(bool quiet) {
  return {.enabled = !quiet, .terminal = isatty(STDERR_FILENO) != 0};
}

// Elsewhere than a terminal the first line waits one interval too: a short run prints nothing.
ProgressReporter::ProgressReporter(Settings settings)
    : settings_(settings), last_shown_(std::chrono::steady_clock::now()) {}

ProgressReporter::~ProgressReporter() {
  clear();
}

void ProgressReporter::update(double fraction, std::string_view text) {
  if (!settings_.enabled) return;
  std::lock_guard lock(mutex_);
  const double every = settings_.terminal ? settings_.redrawEvery : settings_.printEvery;
  const auto now = std::chrono::steady_clock::now();
  const bool due = std::chrono::duration<double>(now - last_shown_).count() >= every;
  if (!due && (anything_shown_ || !settings_.terminal)) return;
  show(fraction, text, false);
}

void ProgressReporter::finish(double fraction, std::string_view text) {
  if (!settings_.enabled) return;
  std::lock_guard lock(mutex_);
  show(fraction, text, true);
}

void ProgressReporter::clear() {
  std::lock_guard lock(mutex_);
  if (!line_drawn_) return;
  std::fputs("\r\033[K", stderr);
  std::fflush(stderr);
  line_drawn_ = false;
}

void ProgressReporter::show(double fraction, std::string_view text, bool last) {
  // The text may hold an object's name: printed with fputs, it bypasses the safe std::cerr.
  const std::string line = terminalSafe(progressLine(fraction, text));
  if (settings_.terminal) {
    std::fprintf(stderr, "\r\033[K%s%s", line.c_str(), last ? "\n" : "");
    line_drawn_ = !last;
  } else {
    std::fprintf(stderr, "graspkit: progress: %s\n", line.c_str());
  }
  std::fflush(stderr);
  last_shown_ = std::chrono::steady_clock::now();
  anything_shown_ = true;
}

std::string clockTime(double seconds) {
  if (!(seconds >= 0) || seconds > 359999) return "--:--";
  const int s = static_cast<int>(std::lround(seconds));
  return s >= 3600 ? fmt::format("{}:{:02}:{:02}", s / 3600, s / 60 % 60, s % 60)
                   : fmt::format("{}:{:02}", s / 60, s % 60);
}

}  // namespace graspkit::cli
