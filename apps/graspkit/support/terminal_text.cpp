#include "support/terminal_text.hpp"

#include <fmt/format.h>

#include <iostream>

#include "graspkit/base/utf8.hpp"

namespace graspkit::cli {

std::string terminalSafe(std::string_view text) {
  std::string safe;
  safe.reserve(text.size());
  for (std::size_t at = 0; at < text.size();) {
    const auto byte = static_cast<unsigned char>(text[at]);
    const std::size_t length = utf8SequenceLength(text.substr(at));
    if (length == 0) {
      safe += fmt::format("\\x{:02x}", byte);  // not UTF-8
      at += 1;
    } else if (length == 1 && ((byte < 0x20 && byte != '\n' && byte != '\t') || byte == 0x7F)) {
      safe += fmt::format("\\x{:02x}", byte);
      at += 1;
    } else if (length == 2 && byte == 0xC2 && static_cast<unsigned char>(text[at + 1]) < 0xA0) {
      safe += fmt::format("\\u{:04x}", static_cast<unsigned char>(text[at + 1]));  // C1 control
      at += 2;
    } else {
      safe.append(text.substr(at, length));
      at += length;
    }
  }
  return safe;
}

TerminalSafeBuffer::~TerminalSafeBuffer() {
  pass(true);
}

TerminalSafeBuffer::int_type TerminalSafeBuffer::overflow(int_type c) {
  if (traits_type::eq_int_type(c, traits_type::eof())) return traits_type::not_eof(c);
  pending_ += traits_type::to_char_type(c);
  if (c == '\n' && !pass(false)) return traits_type::eof();
  return c;
}

std::streamsize TerminalSafeBuffer::xsputn(const char* text, std::streamsize count) {
  pending_.append(text, static_cast<std::size_t>(count));
  return pass(false) ? count : 0;
}

int TerminalSafeBuffer::sync() {
  const bool passed = pass(true);
  return target_->pubsync() == 0 && passed ? 0 : -1;
}

bool TerminalSafeBuffer::pass(bool everything) {
  // rfind gives npos without a newline, and npos + 1 is 0: nothing complete to pass yet.
  const std::size_t end = everything ? pending_.size() : pending_.rfind('\n') + 1;
  if (end == 0) return true;
  const std::string safe = terminalSafe(std::string_view(pending_).substr(0, end));
  pending_.erase(0, end);
  const auto size = static_cast<std::streamsize>(safe.size());
  return target_->sputn(safe.data(), size) == size;
}

TerminalSafeStreams::TerminalSafeStreams(bool output)
    : error_(std::cerr.rdbuf()), output_(std::cout.rdbuf()), output_installed_(output) {
  std::cerr.rdbuf(&error_);
  if (output_installed_) std::cout.rdbuf(&output_);
}

TerminalSafeStreams::~TerminalSafeStreams() {
  std::cout.flush();
  std::cerr.flush();
  std::cerr.rdbuf(error_.target());
  if (output_installed_) std::cout.rdbuf(output_.target());
}

}  // namespace graspkit::cli
