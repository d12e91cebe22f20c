#pragma once
// A reader of flat XML text that does not use graspkit's own XML readers, so tests that check
// those readers against GraspIt!'s files have an independent view of the same files.

#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <string>
#include <vector>

namespace graspkit::test {

inline std::string readText(const std::filesystem::path& path) {
  std::ifstream in(path);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Text of every <tag ...>text</tag> in `xml`, in order (GraspIt!'s files are flat enough).
inline std::vector<std::string> tagTexts(const std::string& xml, const std::string& tag) {
  const std::regex pattern("<" + tag + R"((\s[^>]*)?>\s*([^<]*?)\s*</)" + tag + ">");
  std::vector<std::string> texts;
  for (auto it = std::sregex_iterator(xml.begin(), xml.end(), pattern);
       it != std::sregex_iterator(); ++it) {
    texts.push_back((*it)[2]);
  }
  return texts;
}

}  // namespace graspkit::test
