#include "graspkit/io/graspit/virtual_contact_file.hpp"

#include <fmt/format.h>

#include "graspkit/io/graspit/robot_file.hpp"
#include "io/common/xml.hpp"

namespace graspkit {
namespace {

namespace fs = std::filesystem;
using tinyxml2::XMLElement;

VirtualContact readContact(const fs::path& file, const XMLElement& element) {
  VirtualContact contact;
  contact.finger = xml::integer(file, xml::requiredChild(file, element, "finger_number"));
  contact.link = xml::integer(file, xml::requiredChild(file, element, "link_number"));
  if (const auto* edges = xml::child(element, "friction_edges")) {
    for (const XMLElement* edge : xml::children(*edges, "friction_edge")) {
      const auto v = xml::numbers(file, *edge, 6);
      contact.frictionEdges.push_back(Eigen::Matrix<double, 6, 1>(v.data()));
    }
  }
  if (const auto* count = xml::child(element, "num_friction_edges")) {
    const int expected = xml::integer(file, *count);
    if (expected != static_cast<int>(contact.frictionEdges.size())) {
      throw Error(xml::at(file, *count),
                  fmt::format("says {} friction edges, <friction_edges> has {}", expected,
                              contact.frictionEdges.size()));
    }
  }
  contact.location = xml::vector3(file, xml::requiredChild(file, element, "location"));
  const auto q = xml::numbers(file, xml::requiredChild(file, element, "rotation"), 4);  // w x y z
  contact.rotation =
      xml::checkedQuaternion(file, *xml::child(element, "rotation"), q[0], q[1], q[2], q[3])
          .normalized();
  if (const auto* t = xml::child(element, "translation"))
    contact.translation = xml::vector3(file, *t);
  contact.normal = xml::vector3(file, xml::requiredChild(file, element, "normal"));
  contact.sCof = xml::optionalNumber(file, element, "sCof", 0.0);
  return contact;
}

}  // namespace

std::vector<VirtualContact> loadVirtualContactFile(const fs::path& file) {
  xml::Document doc(file);
  std::vector<VirtualContact> contacts;
  for (const XMLElement* e : xml::children(doc.root(), "virtual_contact")) {
    contacts.push_back(readContact(file, *e));
  }
  return contacts;
}

}  // namespace graspkit
