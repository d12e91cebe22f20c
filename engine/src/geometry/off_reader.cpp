// The OFF reader (Geomview's Object File Format as used by the Princeton Shape Benchmark):
//
//   OFF                 optional header keyword (COFF, NOFF, STOFF... accepted too)
//   nv nf ne            counts; ne is ignored and may be left out
//   x y z [extra...]    nv vertex lines; colours or normals after x y z are ignored
//   n i0 ... [colour]   nf faces, each a polygon triangulated as a fan from i0
//
// '#' starts a comment. The reader is line-oriented and treats the text as hostile (it is
// fuzzed): it never trusts a count for an allocation and reports every problem with its line.

#include <charconv>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>

#include "geometry/mesh_readers.hpp"
#include "graspkit/base/error.hpp"
#include "graspkit/base/input_file.hpp"
#include "graspkit/geometry/mesh_loader.hpp"

namespace graspkit {
namespace {

// The shortest text a vertex line ("0 0 0\n") or a face line ("3 0 1 2\n") can take; used to
// bound reservations by what the remaining text could possibly hold.
constexpr std::size_t kMinVertexLineBytes = 6;
constexpr std::size_t kMinFaceLineBytes = 8;

bool isBlank(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

// Quotes a token for a message, cut short so a megabyte of garbage stays out of the error.
std::string quoted(std::string_view token) {
  constexpr std::size_t kMaxShown = 32;
  if (token.size() > kMaxShown) return fmt::format("'{}...'", token.substr(0, kMaxShown));
  return fmt::format("'{}'", token);
}

bool parseInteger(std::string_view token, long long& out) {
  if (token.size() > 1 && token.front() == '+' && token[1] != '-') token.remove_prefix(1);
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), out);
  return ec == std::errc() && end == token.data() + token.size();
}

enum class NumberStatus { Ok, NotANumber, NotFinite };

NumberStatus parseCoordinate(std::string_view token, double& out) {
  if (token.size() > 1 && token.front() == '+' && token[1] != '-') token.remove_prefix(1);
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), out);
  if (end != token.data() + token.size()) return NumberStatus::NotANumber;
  if (ec == std::errc::result_out_of_range) return NumberStatus::NotFinite;
  if (ec != std::errc()) return NumberStatus::NotANumber;
  return std::isfinite(out) ? NumberStatus::Ok : NumberStatus::NotFinite;
}

struct OffCounts {
  std::uint32_t vertices = 0;
  std::uint32_t faces = 0;
};

class OffParser {
 public:
  OffParser(std::string_view text, const std::string& file) : text_(text), file_(file) {}

  TriangleMesh parse() {
    const OffCounts counts = readHeader();
    TriangleMesh mesh;
    readVertices(counts.vertices, mesh);
    readFaces(counts, mesh);
    return mesh;
  }

 private:
  [[noreturn]] void fail(const std::string& message) const {
    throw Error(detail::locationIn(file_, line_number_), message);
  }

  // Moves to the next line that holds a token after comments are removed and splits it into
  // tokens_. Returns false at the end of the text.
  bool nextLine() {
    while (pos_ < text_.size()) {
      std::size_t end = text_.find('\n', pos_);
      if (end == std::string_view::npos) end = text_.size();
      std::string_view line = text_.substr(pos_, end - pos_);
      pos_ = end + 1;
      ++line_number_;
      if (const std::size_t hash = line.find('#'); hash != std::string_view::npos) {
        line = line.substr(0, hash);
      }
      splitTokens(line);
      if (!tokens_.empty()) return true;
    }
    return false;
  }

  void splitTokens(std::string_view line) {
    tokens_.clear();  // keeps its capacity: no allocation per line once warmed up
    std::size_t i = 0;
    while (i < line.size()) {
      while (i < line.size() && isBlank(line[i])) ++i;
      const std::size_t start = i;
      while (i < line.size() && !isBlank(line[i])) ++i;
      if (i > start) tokens_.push_back(line.substr(start, i - start));
    }
  }

  std::size_t remainingBytes() const { return pos_ < text_.size() ? text_.size() - pos_ : 0; }

  OffCounts readHeader() {
    if (!nextLine()) fail("empty file: expected the 'OFF' header");
    std::vector<std::string_view> counts_tokens;
    long long ignored = 0;
    if (parseInteger(tokens_.front(), ignored)) {
      // No keyword: the Princeton Shape Benchmark allows a file to start with the counts.
      counts_tokens = tokens_;
    } else {
      counts_tokens = tokensAfterKeyword();
      if (counts_tokens.empty()) {
        if (!nextLine()) fail("file ends after the header: expected 'vertices faces edges'");
        counts_tokens = tokens_;
      }
    }
    return parseCounts(counts_tokens);
  }

  // Checks the header keyword and returns whatever follows it on the same line: some writers
  // (ModelNet among them) put the counts there, even glued to the keyword as in "OFF490 518 0".
  std::vector<std::string_view> tokensAfterKeyword() {
    const std::string_view keyword = tokens_.front();
    const std::size_t off = keyword.find("OFF");
    if (off == std::string_view::npos) {
      fail(fmt::format("expected the 'OFF' header or the counts 'vertices faces edges', found {}",
                       quoted(keyword)));
    }
    const std::string_view prefix = keyword.substr(0, off);
    if (prefix.find_first_of("4n") != std::string_view::npos) {
      fail(fmt::format("{} is a 4-D or n-D OFF variant; only 3-D OFF is supported",
                       quoted(keyword)));
    }
    if (prefix.find_first_not_of("STCN") != std::string_view::npos) {
      fail(fmt::format("unknown OFF header {}", quoted(keyword)));
    }
    std::vector<std::string_view> rest;
    if (keyword.size() > off + 3) rest.push_back(keyword.substr(off + 3));
    rest.insert(rest.end(), tokens_.begin() + 1, tokens_.end());
    if (!rest.empty() && rest.front() == "BINARY") fail("binary OFF is not supported");
    return rest;
  }

  OffCounts parseCounts(const std::vector<std::string_view>& tokens) {
    if (tokens.size() < 2 || tokens.size() > 3) {
      fail(fmt::format("expected the counts 'vertices faces edges', found {} numbers",
                       tokens.size()));
    }
    OffCounts counts;
    counts.vertices = parseCount(tokens[0], "vertex");
    counts.faces = parseCount(tokens[1], "face");
    if (tokens.size() == 3) parseCount(tokens[2], "edge");
    return counts;
  }

  std::uint32_t parseCount(std::string_view token, const char* what) {
    long long value = 0;
    if (!parseInteger(token, value)) {
      fail(fmt::format("{} count {} is not an integer", what, quoted(token)));
    }
    // Indices are 32-bit; a larger count cannot describe a mesh we could hold.
    if (value < 0 || value > std::numeric_limits<std::uint32_t>::max()) {
      fail(fmt::format("{} count {} is out of range", what, value));
    }
    return static_cast<std::uint32_t>(value);
  }

  void readVertices(std::uint32_t count, TriangleMesh& mesh) {
    mesh.vertices.reserve(std::min<std::size_t>(count, remainingBytes() / kMinVertexLineBytes));
    for (std::uint32_t i = 0; i < count; ++i) {
      if (!nextLine()) fail(fmt::format("file ends after {} of {} vertices", i, count));
      if (tokens_.size() < 3) {
        fail(fmt::format("vertex {} has {} coordinates, needs x y z", i, tokens_.size()));
      }
      Vector3 p;
      for (int axis = 0; axis < 3; ++axis) p[axis] = parseVertexCoordinate(i, tokens_[axis]);
      mesh.vertices.push_back(p);
    }
  }

  double parseVertexCoordinate(std::uint32_t vertex, std::string_view token) {
    double value = 0.0;
    switch (parseCoordinate(token, value)) {
      case NumberStatus::Ok:
        return value;
      case NumberStatus::NotFinite:
        fail(fmt::format("vertex {} has a non-finite coordinate {}", vertex, quoted(token)));
      case NumberStatus::NotANumber:
        break;
    }
    fail(fmt::format("vertex {} has coordinate {}, which is not a number", vertex, quoted(token)));
  }

  void readFaces(const OffCounts& counts, TriangleMesh& mesh) {
    mesh.triangles.reserve(
        std::min<std::size_t>(counts.faces, remainingBytes() / kMinFaceLineBytes));
    for (std::uint32_t face = 0; face < counts.faces; ++face) {
      if (!nextLine()) fail(fmt::format("file ends after {} of {} faces", face, counts.faces));
      readFace(face, counts.vertices, mesh);
    }
  }

  void readFace(std::uint32_t face, std::uint32_t vertex_count, TriangleMesh& mesh) {
    long long corners = 0;
    if (!parseInteger(tokens_.front(), corners)) {
      fail(fmt::format("face {} starts with {}, expected its vertex count", face,
                       quoted(tokens_.front())));
    }
    if (corners < 3) fail(fmt::format("face {} has {} vertices, needs at least 3", face, corners));
    if (static_cast<unsigned long long>(corners) > tokens_.size() - 1) {
      fail(fmt::format("face {} lists {} vertices but the line holds only {} indices", face,
                       corners, tokens_.size() - 1));
    }
    const std::uint32_t first = faceIndex(face, 1, vertex_count);
    std::uint32_t previous = faceIndex(face, 2, vertex_count);
    for (long long k = 3; k <= corners; ++k) {
      const std::uint32_t current = faceIndex(face, static_cast<std::size_t>(k), vertex_count);
      mesh.triangles.push_back({first, previous, current});
      previous = current;
    }
  }

  std::uint32_t faceIndex(std::uint32_t face, std::size_t token, std::uint32_t vertex_count) {
    long long index = 0;
    if (!parseInteger(tokens_[token], index)) {
      fail(fmt::format("face {} has vertex index {}, which is not an integer", face,
                       quoted(tokens_[token])));
    }
    if (index < 0 || index >= vertex_count) {
      fail(fmt::format("face {} has vertex index {}, the file has {} vertices", face, index,
                       vertex_count));
    }
    return static_cast<std::uint32_t>(index);
  }

  std::string_view text_;
  const std::string& file_;
  std::size_t pos_ = 0;
  int line_number_ = 0;
  std::vector<std::string_view> tokens_;
};

}  // namespace

TriangleMesh parseOff(std::string_view text, const std::string& file) {
  return OffParser(text, file).parse();
}

namespace detail {

TriangleMesh readOff(const std::filesystem::path& path) {
  const std::string content = readInputFile(path);
  return parseOff(content, path.string());
}

}  // namespace detail
}  // namespace graspkit
