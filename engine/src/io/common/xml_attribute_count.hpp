#pragma once
// A bound on the attributes of one XML element, checked before tinyxml2 parses the text.
//
// tinyxml2 compares each new attribute with every earlier one on the same element (it refuses
// duplicates), so an element with n attributes costs n^2/2 string comparisons: 40,000 attributes
// in a 430 KB file took 14 s. GraspIt!'s elements carry at most a few attributes, so a bound far
// above that costs real files nothing and keeps the parse linear in the file's size.

#include <filesystem>
#include <string_view>

namespace graspkit::xml {

inline constexpr int kMaxAttributesPerElement = 256;

// Throws graspkit::Error naming the file, line and element of the first start tag with more than
// kMaxAttributesPerElement attributes. Comments, CDATA sections, processing instructions and
// declarations are skipped; quoted values may hold any character. The scan is linear and never
// rejects a file tinyxml2 would parse with few attributes per element.
void checkAttributeCounts(const std::filesystem::path& file, std::string_view text);

}  // namespace graspkit::xml
