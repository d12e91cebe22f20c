#include "graspkit/io/legacy/legacy_files.hpp"

#include <charconv>
#include <cmath>
#include <string_view>
#include <vector>

#include <fmt/format.h>

#include "graspkit/base/error.hpp"
#include "graspkit/base/input_file.hpp"
#include "graspkit/base/log.hpp"

namespace graspkit {
namespace {

namespace fs = std::filesystem;

// Whitespace-separated tokens with their lines.
class Tokens {
 public:
  Tokens(const fs::path& file) : file_(file.string()) {
    const std::string text = readInputFile(file);
    int line = 1;
    std::size_t at = 0;
    while (at < text.size()) {
      const char c = text[at];
      if (c == '\n') ++line;
      if (c == ' ' || c == '\t' || c == '\r' || c == '\n') {
        ++at;
        continue;
      }
      const std::size_t end = text.find_first_of(" \t\r\n", at);
      tokens_.push_back({text.substr(at, end - at), line});
      at = end == std::string::npos ? text.size() : end;
    }
  }

  bool done() const { return next_ >= tokens_.size(); }
  const std::string& peek() const { return tokens_.at(next_).text; }
  int line() const {
    return done() ? (tokens_.empty() ? 1 : tokens_.back().line) : tokens_[next_].line;
  }

  [[noreturn]] void fail(const std::string& why) const {
    throw Error(SourceLocation{file_, line()}, why);
  }

  std::string word(const char* what) {
    if (done()) fail(fmt::format("the file ends where {} should be", what));
    return tokens_[next_++].text;
  }

  // A finite number, kept as written.
  std::string number(const char* what) {
    const std::string text = word(what);
    double value = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(value)) {
      --next_;
      fail(fmt::format("{} must be a finite number, found '{}'", what, text));
    }
    return text;
  }

  int count(const char* what, int most, int least = 0) {
    const std::string text = word(what);
    int value = least - 1;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || end != text.data() + text.size() || value < least || value > most) {
      --next_;
      fail(fmt::format("{} must be a whole number from {} to {}, found '{}'", what, least, most,
                       text));
    }
    return value;
  }

  std::vector<std::string> numbers(int n, const char* what) {
    std::vector<std::string> out;
    for (int i = 0; i < n; ++i) out.push_back(number(what));
    return out;
  }

  const std::string& file() const { return file_; }

 private:
  struct Token {
    std::string text;
    int line;
  };
  std::string file_;
  std::vector<Token> tokens_;
  std::size_t next_ = 0;
};

std::string joined(const std::vector<std::string>& values) {
  std::string out;
  for (const std::string& v : values) out += (out.empty() ? "" : " ") + v;
  return out;
}

}  // namespace

std::string eigengraspXmlFromEgr(const fs::path& egr) {
  Tokens in(egr);
  if (in.done() || in.peek() != "DIMENSIONS") in.fail("an .egr file starts with DIMENSIONS n");
  in.word("DIMENSIONS");
  const int n = in.count("DIMENSIONS", 1024);
  if (n == 0) in.fail("DIMENSIONS must be at least 1");
  std::string xml = fmt::format("<?xml version=\"1.0\" ?>\n<EigenGrasps dimensions=\"{}\">\n", n);
  int eigengrasps = 0;
  while (!in.done()) {
    const std::string block = in.peek();
    if (block != "EG" && block != "ORIGIN" && block != "NORM") {
      warn(WarningKind::Eigengrasp, SourceLocation{in.file(), in.line()},
           fmt::format("'{}' and what follows belong to no EG, ORIGIN or NORM block; left out",
                       block));
      break;
    }
    in.word("a block name");
    const std::string value = in.number("the eigenvalue");
    const std::vector<std::string> dims = in.numbers(n, "an eigengrasp value");
    xml += fmt::format("\t<{}>\n\t\t<EigenValue value=\"{}\"/>\n\t\t<DimVals", block, value);
    for (int d = 0; d < n; ++d) xml += fmt::format(" d{}=\"{}\"", d, dims[d]);
    xml += fmt::format("/>\n\t</{}>\n", block);
    if (block == "EG") ++eigengrasps;
  }
  if (eigengrasps == 0) in.fail("no EG block: an eigengrasp file needs at least one");
  return xml + "</EigenGrasps>\n";
}

std::string virtualContactXmlFromVgr(const fs::path& vgr) {
  Tokens in(vgr);
  const std::string robot = in.word("the robot's name");
  const int contacts = in.count("the contact count", 100000);
  std::string xml = fmt::format(
      "<?xml version=\"1.0\" ?>\n<virtual_contacts>\n  <robot_name>{}</robot_name>\n"
      "  <num_contacts>{}</num_contacts>\n",
      robot, contacts);
  for (int c = 0; c < contacts; ++c) {
    const int finger = in.count("the finger (chain) number, -1 for the palm", 1 << 20, -1);
    const int link = in.count("the link number", 1 << 20);
    const int edges = in.count("the friction-edge count", 1000);
    xml += fmt::format(
        "  <virtual_contact>\n    <finger_number>{}</finger_number>\n"
        "    <link_number>{}</link_number>\n    <num_friction_edges>{}</num_friction_edges>\n"
        "    <friction_edges>\n",
        finger, link, edges);
    for (int e = 0; e < edges; ++e)
      xml += fmt::format("      <friction_edge>{}</friction_edge>\n",
                         joined(in.numbers(6, "a friction edge value")));
    xml += "    </friction_edges>\n";
    xml += fmt::format("    <location>{}</location>\n", joined(in.numbers(3, "the location")));
    xml += fmt::format("    <!--w, x, y, z -->\n    <rotation>{}</rotation>\n",
                       joined(in.numbers(4, "the rotation")));
    xml += fmt::format("    <!--x, y, z -->\n    <translation>{}</translation>\n",
                       joined(in.numbers(3, "the translation")));
    xml += fmt::format("    <!--x, y, z -->\n    <normal>{}</normal>\n",
                       joined(in.numbers(3, "the normal")));
    xml += fmt::format("    <sCof>{}</sCof>\n  </virtual_contact>\n",
                       in.number("the friction coefficient"));
  }
  if (!in.done())
    warn(WarningKind::VirtualContact, SourceLocation{in.file(), in.line()},
         fmt::format("text after the {} contacts the file declares; left out", contacts));
  return xml + "  </virtual_contacts>";
}

}  // namespace graspkit
