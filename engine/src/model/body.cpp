#include "graspkit/model/body.hpp"

namespace graspkit {

void Body::setPose(const Transform& new_pose) {
  pose = new_pose;
  const Vector3 cog = model ? model->cog : Vector3::Zero();
  const Quaternion rotation(pose.linear());
  state.q.head<3>() = pose * cog;
  state.q.tail<4>() << rotation.w(), rotation.x(), rotation.y(), rotation.z();
}

}  // namespace graspkit
