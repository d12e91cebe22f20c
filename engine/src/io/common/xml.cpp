#include "io/common/xml.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>

#include <fmt/format.h>

#include "graspkit/base/input_file.hpp"
#include "graspkit/base/log.hpp"
#include "graspkit/base/utf8.hpp"
#include "io/common/xml_attribute_count.hpp"

namespace graspkit::xml {

Document::Document(const std::filesystem::path& file) : file_(file) {
  const std::string text = readInputFile(file);
  // tinyxml2 takes any bytes; a name that is not UTF-8 could not be written back or printed.
  if (const auto bad = firstInvalidUtf8(text)) {
    const auto line = 1 + std::count(text.begin(), text.begin() + static_cast<long>(*bad), '\n');
    throw Error(SourceLocation{file.string(), static_cast<int>(line)},
                fmt::format("byte {} (0x{:02X}) is not UTF-8: XML files are read as UTF-8 text",
                            *bad + 1, static_cast<unsigned char>(text[*bad])));
  }
  checkAttributeCounts(file, text);
  if (doc_.Parse(text.data(), text.size()) != tinyxml2::XML_SUCCESS) {
    const int line = doc_.ErrorLineNum();
    const std::string detail = doc_.ErrorStr() ? doc_.ErrorStr() : "parse error";
    // For an unclosed or mismatched tag tinyxml2 names the element ("XMLElement name=dof") and
    // gives its line: report it as the location's element.
    std::string element;
    if (const auto name = detail.find("XMLElement name="); name != std::string::npos) {
      element = detail.substr(name + 16);
      element = element.substr(0, element.find_first_of(" \t\r\n"));
    }
    throw Error(SourceLocation{file.string(), line, element},
                fmt::format("malformed XML: {}", detail));
  }
  root_ = doc_.RootElement();
  if (!root_) throw Error(SourceLocation{file.string()}, "the file has no root element");
  // A second element after the root is content a reader would silently drop.
  if (const tinyxml2::XMLElement* extra = root_->NextSiblingElement()) {
    throw Error(
        at(file, *extra),
        fmt::format("content after the root element <{}>, which ends the document", root_->Name()));
  }
}

SourceLocation at(const std::filesystem::path& file, const tinyxml2::XMLElement& element) {
  return SourceLocation{file.string(), element.GetLineNum(), element.Name()};
}

const tinyxml2::XMLElement* child(const tinyxml2::XMLElement& parent, const char* name) {
  return parent.FirstChildElement(name);
}

std::vector<const tinyxml2::XMLElement*> children(const tinyxml2::XMLElement& parent,
                                                  const char* name) {
  std::vector<const tinyxml2::XMLElement*> out;
  for (auto* e = parent.FirstChildElement(name); e; e = e->NextSiblingElement(name))
    out.push_back(e);
  return out;
}

std::string text(const tinyxml2::XMLElement& element) {
  const char* raw = element.GetText();
  if (!raw) return {};
  std::string_view view(raw);
  const auto first = view.find_first_not_of(" \t\r\n");
  if (first == std::string_view::npos) return {};
  const auto last = view.find_last_not_of(" \t\r\n");
  return std::string(view.substr(first, last - first + 1));
}

void warnUnknownChildren(const std::filesystem::path& file, const tinyxml2::XMLElement& parent,
                         std::initializer_list<std::string_view> known) {
  for (auto* e = parent.FirstChildElement(); e; e = e->NextSiblingElement()) {
    if (std::find(known.begin(), known.end(), std::string_view(e->Name())) == known.end()) {
      warn(WarningKind::UnknownElement, at(file, *e),
           fmt::format("unknown tag inside <{}> ignored", parent.Name()));
    }
  }
}

std::optional<double> toDouble(std::string_view token) {
  while (!token.empty() && std::isspace(static_cast<unsigned char>(token.front())))
    token.remove_prefix(1);
  while (!token.empty() && std::isspace(static_cast<unsigned char>(token.back())))
    token.remove_suffix(1);
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  if (token.empty() || token.front() == '+') return std::nullopt;
  double value = 0.0;
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (ec != std::errc() || end != token.data() + token.size() || !std::isfinite(value)) {
    return std::nullopt;
  }
  return value;
}

std::vector<std::string_view> tokens(std::string_view text) {
  std::vector<std::string_view> out;
  std::size_t pos = 0;
  while (true) {
    pos = text.find_first_not_of(" \t\r\n,", pos);
    if (pos == std::string_view::npos) break;
    const std::size_t end = std::min(text.find_first_of(" \t\r\n,", pos), text.size());
    out.push_back(text.substr(pos, end - pos));
    pos = end;
  }
  return out;
}

std::vector<double> numbers(const std::filesystem::path& file, const tinyxml2::XMLElement& element,
                            int count) {
  const std::string content = text(element);
  std::vector<double> out;
  for (std::string_view token : tokens(content)) {
    auto value = toDouble(token);
    if (!value) {
      throw Error(at(file, element), fmt::format("'{}' is not a finite number", token));
    }
    out.push_back(*value);
  }
  if (count >= 0 && static_cast<int>(out.size()) != count) {
    throw Error(at(file, element), fmt::format("expected {} number{}, found {} in '{}'", count,
                                               count == 1 ? "" : "s", out.size(), content));
  }
  return out;
}

double number(const std::filesystem::path& file, const tinyxml2::XMLElement& element) {
  return numbers(file, element, 1)[0];
}

Vector3 vector3(const std::filesystem::path& file, const tinyxml2::XMLElement& element) {
  const auto v = numbers(file, element, 3);
  return Vector3(v[0], v[1], v[2]);
}

int integer(const std::filesystem::path& file, const tinyxml2::XMLElement& element) {
  std::string content = text(element);
  std::string_view view(content);
  if (!view.empty() && view.front() == '+') view.remove_prefix(1);
  int value = 0;
  const auto [end, ec] = std::from_chars(view.data(), view.data() + view.size(), value);
  if (view.empty() || ec != std::errc() || end != view.data() + view.size()) {
    throw Error(at(file, element), fmt::format("'{}' is not an integer", content));
  }
  return value;
}

const tinyxml2::XMLElement& requiredChild(const std::filesystem::path& file,
                                          const tinyxml2::XMLElement& parent, const char* name) {
  const auto* element = child(parent, name);
  if (!element) throw Error(at(file, parent), fmt::format("missing <{}>", name));
  return *element;
}

double requiredNumber(const std::filesystem::path& file, const tinyxml2::XMLElement& parent,
                      const char* name) {
  const auto* element = child(parent, name);
  if (!element) throw Error(at(file, parent), fmt::format("missing <{}>", name));
  return number(file, *element);
}

double optionalNumber(const std::filesystem::path& file, const tinyxml2::XMLElement& parent,
                      const char* name, double fallback) {
  const auto* element = child(parent, name);
  return element ? number(file, *element) : fallback;
}

std::optional<int> intAttribute(const std::filesystem::path& file,
                                const tinyxml2::XMLElement& element, const char* name) {
  const char* raw = element.Attribute(name);
  if (!raw) return std::nullopt;
  std::string_view view(raw);
  while (!view.empty() && view.front() == ' ') view.remove_prefix(1);
  while (!view.empty() && view.back() == ' ') view.remove_suffix(1);
  int value = 0;
  const auto [end, ec] = std::from_chars(view.data(), view.data() + view.size(), value);
  if (view.empty() || ec != std::errc() || end != view.data() + view.size()) {
    throw Error(at(file, element), fmt::format("attribute {}='{}' is not an integer", name, raw));
  }
  return value;
}

namespace {

Transform rotationAbout(const std::filesystem::path& file, const tinyxml2::XMLElement& element) {
  const std::string content = text(element);  // `parts` views into it: keep it alive
  const auto parts = tokens(content);
  const auto degrees = parts.size() == 2 ? toDouble(parts[0]) : std::nullopt;
  if (!degrees || parts[1].size() != 1 ||
      std::string_view("xyzXYZ").find(parts[1][0]) == std::string_view::npos) {
    throw Error(at(file, element),
                fmt::format("expected '<degrees> <x|y|z>', found '{}'", content));
  }
  const int axis = std::tolower(static_cast<unsigned char>(parts[1][0])) - 'x';
  Transform t = Transform::Identity();
  t.linear() =
      Eigen::AngleAxisd(degreesToRadians(*degrees), Vector3::Unit(axis)).toRotationMatrix();
  return t;
}

Transform rotationMatrix(const std::filesystem::path& file, const tinyxml2::XMLElement& element) {
  const auto v = numbers(file, element, 9);
  Matrix3 r;
  // Column-major: the first three numbers are column 0 (GraspIt! kept this pre-port meaning).
  r << v[0], v[3], v[6], v[1], v[4], v[7], v[2], v[5], v[8];
  if (!(r * r.transpose()).isApprox(Matrix3::Identity(), 1e-3) || r.determinant() < 0) {
    throw Error(at(file, element), "rotationMatrix is not a rotation");
  }
  // Files carry 4 to 6 significant digits, so R is only nearly orthonormal. GraspIt! turns it
  // into a quaternion (Eigen's conversion) and normalises that; doing the same reproduces its
  // link poses to 1e-9 where an orthogonal projection of R would differ by 1e-5.
  return makeTransform(Vector3::Zero(), Quaternion(r));
}

}  // namespace

Transform parseFullTransform(const std::filesystem::path& file, const tinyxml2::XMLElement& element,
                             std::string_view content) {
  const auto open_q = content.find('('), close_q = content.find(')');
  const auto open_t = content.find('['), close_t = content.find(']');
  auto fail = [&]() -> Error {
    return Error(at(file, element),
                 fmt::format("expected '(w x y z)[x y z]', found '{}'", std::string(content)));
  };
  if (open_q == std::string_view::npos || close_q == std::string_view::npos ||
      open_t == std::string_view::npos || close_t == std::string_view::npos || close_q < open_q ||
      close_t < open_t || open_t < close_q) {
    throw fail();
  }
  auto read = [&](std::string_view part, std::size_t count) {
    std::vector<double> values;
    for (auto token : tokens(part)) {
      auto v = toDouble(token);
      if (!v) throw fail();
      values.push_back(*v);
    }
    if (values.size() != count) throw fail();
    return values;
  };
  const auto q = read(content.substr(open_q + 1, close_q - open_q - 1), 4);
  const auto t = read(content.substr(open_t + 1, close_t - open_t - 1), 3);
  if (const char* why = translationProblem(Vector3(t[0], t[1], t[2])))
    throw Error(at(file, element), fmt::format("the translation {}", why));
  return makeTransform(Vector3(t[0], t[1], t[2]),
                       checkedQuaternion(file, element, q[0], q[1], q[2], q[3]));
}

Quaternion checkedQuaternion(const std::filesystem::path& file, const tinyxml2::XMLElement& element,
                             double w, double x, double y, double z) {
  // Scaled by the largest component first: (1e200 1e200 0 0) has a norm past double range and
  // (1e-200 0 0 0) one below it, yet both name a rotation.
  const double largest = std::max({std::abs(w), std::abs(x), std::abs(y), std::abs(z)});
  if (!(largest > 0.0) || !std::isfinite(largest)) {
    throw Error(at(file, element), "the quaternion has zero length: it names no rotation");
  }
  // In the ordinary range the quaternion stays as written, to the bit (makeTransform normalises
  // it): saved worlds reload to the very same pose. Only the extremes are rescaled.
  if (largest > 1e-100 && largest < 1e100) return Quaternion(w, x, y, z);
  return Quaternion(w / largest, x / largest, y / largest, z / largest);
}

Transform transform(const std::filesystem::path& file, const tinyxml2::XMLElement& element) {
  Transform total = Transform::Identity();
  for (auto* part = element.FirstChildElement(); part; part = part->NextSiblingElement()) {
    const std::string_view name = part->Name();
    Transform step = Transform::Identity();
    if (name == "translation") {
      step.translation() = vector3(file, *part);
      if (const char* why = translationProblem(step.translation()))
        throw Error(at(file, *part), fmt::format("the translation {}", why));
    } else if (name == "rotation") {
      step = rotationAbout(file, *part);
    } else if (name == "rotationMatrix") {
      step = rotationMatrix(file, *part);
    } else if (name == "fullTransform") {
      step = parseFullTransform(file, *part, text(*part));
    } else {
      warn(WarningKind::UnknownElement, at(file, *part),
           "unknown transform element ignored (identity)");
    }
    total = total * step;
  }
  return total;
}

}  // namespace graspkit::xml
