#include "graspkit/model/body.hpp"

namespace graspkit {

std::span<const EnumName<BodyKind>> enumNames(std::type_identity<BodyKind>) {
  static constexpr EnumName<BodyKind> kNames[] = {{BodyKind::Obstacle, "obstacle"},
                                                  {BodyKind::Graspable, "graspable"}};
  return kNames;
}

void Body::setPose(const Transform& new_pose) {
  pose = new_pose;
  const Vector3 cog = model ? model->cog : Vector3::Zero();
  const Quaternion rotation(pose.linear());
  state.q.head<3>() = pose * cog;
  state.q.tail<4>() << rotation.w(), rotation.x(), rotation.y(), rotation.z();
}

}  // namespace graspkit
