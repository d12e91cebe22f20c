#include "geometry/ply_header.hpp"

#include <array>
#include <charconv>
#include <cstdint>
#include <string>
#include <vector>

#include <fmt/format.h>

namespace graspkit::detail {
namespace {

// PLY's scalar types and their sizes in bytes.
int typeSize(std::string_view type) {
  static constexpr std::array<std::pair<std::string_view, int>, 16> kTypes = {{
      {"char", 1},
      {"uchar", 1},
      {"int8", 1},
      {"uint8", 1},
      {"short", 2},
      {"ushort", 2},
      {"int16", 2},
      {"uint16", 2},
      {"int", 4},
      {"uint", 4},
      {"int32", 4},
      {"uint32", 4},
      {"float", 4},
      {"float32", 4},
      {"double", 8},
      {"float64", 8},
  }};
  for (const auto& [name, size] : kTypes)
    if (name == type) return size;
  return 0;
}

std::vector<std::string_view> words(std::string_view line) {
  std::vector<std::string_view> out;
  std::size_t pos = 0;
  while ((pos = line.find_first_not_of(" \t\r", pos)) != std::string_view::npos) {
    const std::size_t end = std::min(line.find_first_of(" \t\r", pos), line.size());
    out.push_back(line.substr(pos, end - pos));
    pos = end;
  }
  return out;
}

struct Element {
  std::uint64_t count = 0;
  std::uint64_t leastBytes = 0;  // per instance: binary sizes, or 2 characters per ASCII value
};

}  // namespace

void checkPlyHeader(std::string_view bytes, const SourceLocation& where) {
  int lineNumber = 0;
  const auto fail = [&](const std::string& why) {
    SourceLocation at = where;
    at.line = lineNumber;
    return Error(at, "PLY header: " + why);
  };
  constexpr std::size_t kMaxHeader = 1 << 16;
  std::size_t pos = 0;
  bool ascii = false, formatSeen = false, ended = false;
  std::vector<Element> elements;
  while (!ended) {
    const std::size_t end = bytes.find('\n', pos);
    if (end == std::string_view::npos || end > kMaxHeader)
      throw fail("no end_header within the first 64 KiB");
    const std::string_view line = bytes.substr(pos, end - pos);
    pos = end + 1;
    ++lineNumber;
    const auto w = words(line);
    if (lineNumber == 1) {
      if (w.size() != 1 || w[0] != "ply") throw fail("the first line must be 'ply'");
      continue;
    }
    if (w.empty() || w[0] == "comment" || w[0] == "obj_info") continue;
    if (w[0] == "format") {
      if (w.size() != 3) throw fail("expected 'format TYPE VERSION'");
      if (w[1] == "ascii")
        ascii = true;
      else if (w[1] != "binary_little_endian" && w[1] != "binary_big_endian")
        throw fail(fmt::format("unknown format '{}'", w[1]));
      formatSeen = true;
    } else if (w[0] == "element") {
      std::uint64_t count = 0;
      if (w.size() != 3 ||
          std::from_chars(w[2].data(), w[2].data() + w[2].size(), count).ec != std::errc())
        throw fail("expected 'element NAME COUNT'");
      elements.push_back({count, 0});
    } else if (w[0] == "property") {
      if (elements.empty()) throw fail("a property before any element");
      int size = 0;
      if (w.size() == 5 && w[1] == "list") {
        if (typeSize(w[2]) == 0 || typeSize(w[3]) == 0)
          throw fail(fmt::format("unknown list types '{}' '{}'", w[2], w[3]));
        size = typeSize(w[2]);  // an empty list holds its count only
      } else if (w.size() == 3) {
        size = typeSize(w[1]);
        if (size == 0) throw fail(fmt::format("unknown property type '{}'", w[1]));
      } else {
        throw fail("expected 'property TYPE NAME' or 'property list COUNT_TYPE TYPE NAME'");
      }
      elements.back().leastBytes += ascii ? 2 : static_cast<std::uint64_t>(size);
    } else if (w[0] == "end_header") {
      ended = true;
    } else {
      throw fail(fmt::format("unknown keyword '{}'", w[0]));
    }
  }
  if (!formatSeen) throw fail("no format line");
  // The least data the header promises, against what follows it.
  const std::uint64_t available = bytes.size() - pos;
  std::uint64_t promised = 0;
  for (const Element& e : elements) {
    if (e.leastBytes != 0 && e.count > (available + 1) / e.leastBytes + 1)
      throw fail(
          fmt::format("an element of {} instances needs at least {} bytes each; the file "
                      "holds {} bytes of data",
                      e.count, e.leastBytes, available));
    promised += e.count * e.leastBytes;
  }
  // ASCII's last value needs no separator after it.
  if (promised > available + (ascii ? 1 : 0))
    throw fail(fmt::format("the header promises at least {} bytes of data; the file holds {}",
                           promised, available));
}

}  // namespace graspkit::detail
