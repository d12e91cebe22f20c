#include "batch/object_list.hpp"

#include <algorithm>
#include <set>
#include <sstream>

#include <fmt/format.h>

#include "graspkit/base/input_file.hpp"
#include "graspkit/base/utf8.hpp"

namespace graspkit::cli {

namespace fs = std::filesystem;

void requireUtf8(const std::string& text, const SourceLocation& where, const char* what) {
  if (const auto bad = firstInvalidUtf8(text))
    throw Error(where, fmt::format("{} holds byte 0x{:02X}, which is not UTF-8", what,
                                   static_cast<unsigned char>(text[*bad])));
}

std::vector<fs::path> objectFiles(const fs::path& source) {
  fs::path list = source;
  if (fs::is_directory(source)) {
    list = source / "objects.txt";
    if (!fs::exists(list)) {
      std::vector<fs::path> files;
      for (const auto& entry : fs::directory_iterator(source)) {
        if (entry.path().extension() != ".xml") continue;
        requireUtf8(entry.path().filename().string(), SourceLocation{source.string()},
                    "--objects: a file name in the folder");
        files.push_back(entry.path());
      }
      std::sort(files.begin(), files.end());
      if (files.empty())
        throw Error(SourceLocation{source.string()}, "--objects: the folder holds no .xml file");
      return files;
    }
  }
  std::vector<fs::path> files;
  std::istringstream lines(readInputFile(list));
  std::string line;
  int number = 0;
  while (std::getline(lines, line)) {
    ++number;
    requireUtf8(line, SourceLocation{list.string(), number}, "the line");
    line = line.substr(0, line.find('#'));
    line.erase(0, line.find_first_not_of(" \t\r"));
    line.erase(line.find_last_not_of(" \t\r") + 1);
    if (line.empty()) continue;
    const fs::path file = fs::path(line).is_absolute() ? fs::path(line) : list.parent_path() / line;
    files.push_back(file.lexically_normal());
  }
  if (files.empty()) throw Error(SourceLocation{list.string()}, "--objects: the list is empty");
  return files;
}

std::vector<std::string> objectNames(const std::vector<fs::path>& files) {
  std::vector<std::string> names;
  std::set<std::string> used;
  for (const fs::path& file : files) {
    std::string name = file.stem().string();
    for (int k = 2; !used.insert(name).second; ++k)
      name = fmt::format("{}_{}", file.stem().string(), k);
    names.push_back(name);
  }
  return names;
}

}  // namespace graspkit::cli
