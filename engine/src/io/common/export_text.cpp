#include "io/common/export_text.hpp"

#include <fmt/format.h>

#include <cctype>

namespace graspkit::io {

namespace {

bool forbiddenControl(unsigned char c) {
  return (c < 0x20 && c != '\t' && c != '\n' && c != '\r') || c == 0x7f;
}

}  // namespace

std::string xmlEscaped(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      case '\t':
        out += "&#9;";
        break;  // kept as itself: an attribute would fold it to a space
      case '\n':
        out += "&#10;";
        break;
      case '\r':
        out += "&#13;";
        break;
      default:
        out += forbiddenControl(static_cast<unsigned char>(c)) ? '?' : c;
    }
  }
  return out;
}

std::string xmlCommentText(std::string_view text) {
  std::string out;
  for (const char c : text) {
    if (c == '-' && !out.empty() && out.back() == '-') out += ' ';
    out += forbiddenControl(static_cast<unsigned char>(c)) ? '?' : c;
  }
  if (!out.empty() && out.back() == '-') out += ' ';
  return out;
}

std::string fileStem(std::string_view name, std::string_view fallback) {
  constexpr std::size_t kLongest = 100;
  std::string out;
  for (const char c : name) {
    if (out.size() == kLongest) break;
    const bool kept = std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' ||
                      (c == '.' && !out.empty());
    if (c == '.' && out.empty()) continue;
    out += kept ? c : '_';
  }
  return out.empty() ? std::string(fallback) : out;
}

std::string exactNumber(double value) {
  return fmt::format("{:.17g}", value);
}

}  // namespace graspkit::io
