#include "graspkit/io/graspit/eigengrasp_file.hpp"

#include <charconv>

#include <fmt/format.h>

#include "graspkit/base/log.hpp"
#include "graspkit/io/graspit/robot_file.hpp"
#include "io/common/xml.hpp"

namespace graspkit {
namespace {

namespace fs = std::filesystem;
using tinyxml2::XMLElement;

// <DimVals d0=".." d3=".."/>: missing attributes are 0. A d<i> past the robot's DOFs is
// skipped with a warning (GraspIt! never checks, and reads out of bounds); any other name is an
// error.
Eigen::VectorXd dimVals(const fs::path& file, const XMLElement& element, int dofs) {
  const auto* dims = xml::child(element, "DimVals");
  if (!dims) throw Error(xml::at(file, element), "missing <DimVals>");
  Eigen::VectorXd values = Eigen::VectorXd::Zero(dofs);
  for (auto* attr = dims->FirstAttribute(); attr; attr = attr->Next()) {
    const std::string_view name = attr->Name();
    // from_chars, not digit arithmetic: d4294967296 must not wrap round to d0.
    const bool digits_only = name.size() > 1 && name[0] == 'd' &&
                             name.find_first_not_of("0123456789", 1) == std::string_view::npos;
    if (!digits_only) {
      throw Error(xml::at(file, *dims),
                  fmt::format("attribute '{}' is not d<index> (d0..d{})", name, dofs - 1));
    }
    int index = -1;
    const std::string_view digits = name.substr(1);
    const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), index);
    if (ec != std::errc() || index >= dofs) {
      warn(WarningKind::Eigengrasp, xml::at(file, *dims),
           fmt::format("attribute '{}' does not name one of the robot's {} DOFs (d0..d{}); skipped",
                       name, dofs, dofs - 1));
      continue;
    }
    auto value = xml::toDouble(attr->Value());
    if (!value) {
      throw Error(xml::at(file, *dims),
                  fmt::format("{}='{}' is not a number", name, attr->Value()));
    }
    values[index] = *value;
  }
  return values;
}

double eigenValue(const fs::path& file, const XMLElement& element) {
  const auto* e = xml::child(element, "EigenValue");
  if (!e || !e->Attribute("value")) return 0.5;
  auto value = xml::toDouble(e->Attribute("value"));
  if (!value) throw Error(xml::at(file, *e), "value is not a number");
  return *value;
}

}  // namespace

EigengraspSet loadEigengraspFile(const fs::path& file, int dof_count) {
  if (file.extension() != ".xml") {
    throw Error(SourceLocation{file.string()}, "eigengrasp files must be .xml");
  }
  xml::Document doc(file);
  const XMLElement& root = doc.root();
  const auto dims = xml::intAttribute(file, root, "dimensions");
  if (!dims || *dims != dof_count) {
    // GraspIt! reads such a file regardless; what fits the robot is used.
    warn(WarningKind::Eigengrasp, xml::at(file, root),
         fmt::format("dimensions is {}, the robot has {} DOFs; the values for d0..d{} are used",
                     dims ? std::to_string(*dims) : "missing", dof_count, dof_count - 1));
  }
  EigengraspSet set;
  for (const XMLElement* e : xml::children(root, "EG")) {
    Eigengrasp grasp;
    grasp.eigenValue = eigenValue(file, *e);
    grasp.direction = dimVals(file, *e, dof_count);
    const double norm = grasp.direction.norm();
    if (norm < 1e-12) {
      warn(WarningKind::Eigengrasp, xml::at(file, *e),
           "eigengrasp is all zeros on the robot's DOFs; skipped");
      continue;
    }
    grasp.direction /= norm;
    if (const auto* limits = xml::child(*e, "Limits")) {
      auto min = limits->Attribute("min") ? xml::toDouble(limits->Attribute("min")) : std::nullopt;
      auto max = limits->Attribute("max") ? xml::toDouble(limits->Attribute("max")) : std::nullopt;
      if (!min || !max || *min > *max) {
        throw Error(xml::at(file, *limits), "expected numeric min <= max");
      }
      grasp.min = min;
      grasp.max = max;
    }
    set.grasps.push_back(std::move(grasp));
  }
  if (set.grasps.empty()) {
    warn(WarningKind::Eigengrasp, xml::at(file, root),
         "no eigengrasp fits the robot; identity eigengrasps are used");
    return identityEigengrasps(dof_count);
  }
  if (const auto* origin = xml::child(root, "ORIGIN"))
    set.origin = dimVals(file, *origin, dof_count);
  if (const auto* norm = xml::child(root, "NORM")) set.norm = dimVals(file, *norm, dof_count);
  return set;
}

}  // namespace graspkit
