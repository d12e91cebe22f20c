#include "graspkit/collision/contact.hpp"

#include <cmath>

namespace graspkit {

std::span<const EnumName<ContactModel>> enumNames(std::type_identity<ContactModel>) {
  static constexpr EnumName<ContactModel> kNames[] = {{ContactModel::Frictionless, "frictionless"},
                                                      {ContactModel::PointWithFriction, "point"},
                                                      {ContactModel::SoftFinger, "soft_finger"}};
  return kNames;
}

Contact Contact::mate() const {
  Contact m = *this;
  m.body1 = body2;
  m.body2 = body1;
  m.position1 = position2;
  m.position2 = position1;
  m.normal = -normal;
  m.frame = contactFrame(m.normal);
  return m;
}

}  // namespace graspkit
