#include "io/common/xml_attribute_count.hpp"

#include <fmt/format.h>

#include "graspkit/base/error.hpp"

namespace graspkit::xml {
namespace {

class TagScanner {
 public:
  explicit TagScanner(std::string_view text) : text_(text) {}

  bool done() const { return at_ >= text_.size(); }
  int line() const { return line_; }
  bool startsWith(std::string_view prefix) const {
    return text_.substr(at_, prefix.size()) == prefix;
  }
  char peek(std::size_t ahead = 0) const {
    return at_ + ahead < text_.size() ? text_[at_ + ahead] : '\0';
  }
  void advance(std::size_t count = 1) {
    for (; count > 0 && at_ < text_.size(); --count)
      if (text_[at_++] == '\n') ++line_;
  }
  // Moves past the next `end` (or to the end of the text).
  void skipPast(std::string_view end) {
    const std::size_t found = text_.find(end, at_);
    advance(found == std::string_view::npos ? text_.size() - at_ : found - at_ + end.size());
  }
  std::string_view name() const {
    std::size_t end = at_;
    while (end < text_.size() && !isBreak(text_[end])) ++end;
    return text_.substr(at_, std::min<std::size_t>(end - at_, 64));
  }

 private:
  static bool isBreak(char c) {
    return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '>' || c == '/' || c == '=';
  }
  std::string_view text_;
  std::size_t at_ = 0;
  int line_ = 1;
};

// At the first character after '<' of a start tag: counts the '=' outside quoted values up to the
// tag's closing '>' (one per attribute) and throws once the bound is passed.
void checkStartTag(const std::filesystem::path& file, TagScanner& scan) {
  const int line = scan.line();
  const std::string element(scan.name());
  int attributes = 0;
  char quote = '\0';
  for (; !scan.done(); scan.advance()) {
    const char c = scan.peek();
    if (quote) {
      if (c == quote) quote = '\0';
    } else if (c == '"' || c == '\'') {
      quote = c;
    } else if (c == '>') {
      scan.advance();
      return;
    } else if (c == '=' && ++attributes > kMaxAttributesPerElement) {
      throw Error(SourceLocation{file.string(), line, element},
                  fmt::format("more than {} attributes on one element", kMaxAttributesPerElement));
    }
  }
}

}  // namespace

void checkAttributeCounts(const std::filesystem::path& file, std::string_view text) {
  TagScanner scan(text);
  while (!scan.done()) {
    if (scan.peek() != '<') {
      scan.advance();
    } else if (scan.startsWith("<!--")) {
      scan.skipPast("-->");
    } else if (scan.startsWith("<![CDATA[")) {
      scan.skipPast("]]>");
    } else if (scan.startsWith("<?")) {
      scan.skipPast("?>");
    } else if (scan.startsWith("<!") || scan.startsWith("</")) {
      scan.skipPast(">");
    } else {
      scan.advance();
      checkStartTag(file, scan);
    }
  }
}

}  // namespace graspkit::xml
