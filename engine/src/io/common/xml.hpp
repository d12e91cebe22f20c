#pragma once
// Internal helpers for reading GraspIt! XML: located errors, strict locale-independent numbers,
// direct-children lookups (GraspIt! scans only direct children; the first match wins), and the
// <transform> grammar.

#include <filesystem>
#include <initializer_list>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <tinyxml2.h>

#include "graspkit/base/error.hpp"
#include "graspkit/math/transform.hpp"

namespace graspkit::xml {

// An XML file parsed into memory, remembering its name for error messages.
class Document {
 public:
  explicit Document(const std::filesystem::path& file);
  const tinyxml2::XMLElement& root() const { return *root_; }
  const std::filesystem::path& file() const { return file_; }
  std::string displayName() const { return file_.string(); }

 private:
  std::filesystem::path file_;
  tinyxml2::XMLDocument doc_;
  const tinyxml2::XMLElement* root_ = nullptr;
};

// The location of `element` in `file`.
SourceLocation at(const std::filesystem::path& file, const tinyxml2::XMLElement& element);

// The quaternion (w x y z), rescaled when its norm would overflow or underflow (callers
// normalise, as makeTransform does); throws naming `element` when it has no direction.
Quaternion checkedQuaternion(const std::filesystem::path& file, const tinyxml2::XMLElement& element,
                             double w, double x, double y, double z);

// The first direct child named `name`, or null.
const tinyxml2::XMLElement* child(const tinyxml2::XMLElement& parent, const char* name);
std::vector<const tinyxml2::XMLElement*> children(const tinyxml2::XMLElement& parent,
                                                  const char* name);

// The trimmed text of an element ("" when it has none).
std::string text(const tinyxml2::XMLElement& element);

// Warns about direct children whose names are not in `known`.
void warnUnknownChildren(const std::filesystem::path& file, const tinyxml2::XMLElement& parent,
                         std::initializer_list<std::string_view> known);

// Numbers. A leading '+' is accepted (GraspIt! writes it); NaN and infinities are rejected.
std::optional<double> toDouble(std::string_view token);
std::vector<std::string_view> tokens(std::string_view text);

// Reads the element's text as exactly `count` numbers (any count when count < 0).
std::vector<double> numbers(const std::filesystem::path& file, const tinyxml2::XMLElement& element,
                            int count);
double number(const std::filesystem::path& file, const tinyxml2::XMLElement& element);
Vector3 vector3(const std::filesystem::path& file, const tinyxml2::XMLElement& element);
int integer(const std::filesystem::path& file, const tinyxml2::XMLElement& element);

// A required direct child; throws naming the parent when it is missing.
const tinyxml2::XMLElement& requiredChild(const std::filesystem::path& file,
                                          const tinyxml2::XMLElement& parent, const char* name);

// Runs `load` (which reads another file that `element` names); an Error it throws is re-thrown
// located at `element` too, so the message shows both places.
template <typename Load>
auto locatedAt(const std::filesystem::path& file, const tinyxml2::XMLElement& element,
               const Load& load) -> decltype(load()) {
  try {
    return load();
  } catch (const Error& e) {
    throw Error(at(file, element), e.what());
  }
}

// A required child's number; throws naming the parent when the child is missing.
double requiredNumber(const std::filesystem::path& file, const tinyxml2::XMLElement& parent,
                      const char* name);
double optionalNumber(const std::filesystem::path& file, const tinyxml2::XMLElement& parent,
                      const char* name, double fallback);

// An attribute's integer value; throws naming the element when it is not an integer.
std::optional<int> intAttribute(const std::filesystem::path& file,
                                const tinyxml2::XMLElement& element, const char* name);

// The <transform> grammar: children compose in document order, each in the frame the previous
// ones leave. translation "x y z"; rotation "deg axis"; rotationMatrix (9 numbers, column-major);
// fullTransform "(w x y z)[x y z]". Unknown children count as the identity, with a warning.
Transform transform(const std::filesystem::path& file, const tinyxml2::XMLElement& element);
Transform parseFullTransform(const std::filesystem::path& file, const tinyxml2::XMLElement& element,
                             std::string_view text);

}  // namespace graspkit::xml
