#include "dynamics/generalized_coordinates.hpp"

#include "graspkit/model/world.hpp"

namespace graspkit::dynamics {

namespace {

Matrix3 skew(const Vector3& v) {
  Matrix3 s;
  s << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return s;
}

}  // namespace

GeneralizedCoordinates::GeneralizedCoordinates(const World& world) {
  robot_offset_.assign(world.robotCount(), -1);
  for (int r = 0; r < world.robotCount(); ++r) {
    if (world.robot(r).dofCount() == 0) continue;
    robot_offset_[r] = size_;
    size_ += world.robot(r).dofCount();
  }
  body_offset_.assign(world.bodies().size(), -1);
  for (std::size_t b = 0; b < world.bodies().size(); ++b) {
    const Body& body = world.bodies()[b];
    if (!body.isDynamic()) continue;
    body_offset_[b] = size_;
    size_ += 6;
    BodyMotion motion;
    motion.freeCoordinate = body_offset_[b];
    motion.centre = body.pose * body.model->cog;
    const BodyRef ref = BodyRef::body(static_cast<int>(b));
    motion_[ref] = motion;
    moving_.push_back(ref);
  }
  for (int r = 0; r < world.robotCount(); ++r) {
    const Robot& robot = world.robot(r);
    const std::vector<JointAxis> above = robotAncestors(world, r);
    // A part without a body file has no mass and no geometry: nothing for dynamics to move.
    auto add = [&](const BodyRef& ref, std::vector<JointAxis> joints) {
      joints.insert(joints.end(), above.begin(), above.end());
      const bool has_body =
          ref.link.isBase()
              ? robot.model().palm != nullptr
              : robot.model().chains[ref.link.chain].links[ref.link.link].body != nullptr;
      if (joints.empty() || !has_body) return;
      moving_.push_back(ref);
      motion_[ref].joints = std::move(joints);
    };
    add(BodyRef::robotBase(r), {});
    for (int c = 0; c < static_cast<int>(robot.model().chains.size()); ++c) {
      const KinematicChain& chain = robot.model().chains[c];
      for (int l = 0; l < static_cast<int>(chain.links.size()); ++l) {
        add(BodyRef::robotLink(r, {c, l}), chainAxes(world, r, c, chain.links[l].lastJoint));
      }
    }
  }
  for (int k = 0; k < static_cast<int>(world.connections().size()); ++k) {
    const Connection& connection = world.connections()[k];
    if (!connection.mount) continue;
    std::vector<JointAxis> joints = robotAncestors(world, connection.childRobot);
    if (joints.empty()) continue;
    moving_.push_back(BodyRef::mount(k));
    motion_[BodyRef::mount(k)].joints = std::move(joints);
  }
}

// The joints of chain `chain` of robot `robot` up to `last_joint` (chain-local, inclusive),
// then those of every robot it hangs from.
std::vector<JointAxis> GeneralizedCoordinates::chainAxes(const World& world, int robot_index,
                                                         int chain_index, int last_joint) const {
  std::vector<JointAxis> axes;
  if (last_joint < 0) return axes;
  const Robot& robot = world.robot(robot_index);
  const KinematicChain& chain = robot.model().chains[chain_index];
  const Transform chain_base = robot.pose() * chain.base;
  const auto values = robot.jointValues().subspan(chain.firstJoint, chain.joints.size());
  const std::vector<Transform> frames = jointFrames(chain, chain_base, values);
  for (int j = 0; j <= last_joint && j < static_cast<int>(chain.joints.size()); ++j) {
    const Joint& joint = chain.joints[j];
    // A joint whose breakaway clutch has engaged stays where it stopped: it no longer follows
    // its DOF, so it carries the links beyond it as a fixed joint would.
    if (robot.breakaway()[chain.firstJoint + j].engaged) continue;
    const Transform& before = j == 0 ? chain_base : frames[j - 1];
    JointAxis axis;
    axis.coordinate = robot_offset_[robot_index] + joint.dof;
    axis.ratio = joint.ratio;
    axis.revolute = joint.type == JointType::Revolute;
    axis.axis = before.linear().col(2);
    axis.origin = before.translation();
    axes.push_back(axis);
  }
  return axes;
}

std::vector<JointAxis> GeneralizedCoordinates::robotAncestors(const World& world, int robot) const {
  for (const Connection& connection : world.connections()) {
    if (connection.childRobot != robot) continue;
    const KinematicChain& chain =
        world.robot(connection.parentRobot).model().chains[connection.parentChain];
    const int last = chain.links.empty() ? -1 : chain.links.back().lastJoint;
    std::vector<JointAxis> axes =
        chainAxes(world, connection.parentRobot, connection.parentChain, last);
    const std::vector<JointAxis> higher = robotAncestors(world, connection.parentRobot);
    axes.insert(axes.end(), higher.begin(), higher.end());
    return axes;
  }
  return {};
}

const BodyMotion& GeneralizedCoordinates::motion(const BodyRef& ref) const {
  const auto found = motion_.find(ref);
  return found == motion_.end() ? still_ : found->second;
}

MatrixX GeneralizedCoordinates::linearJacobian(const BodyRef& ref, const Vector3& p) const {
  MatrixX jacobian = MatrixX::Zero(3, size_);
  const BodyMotion& m = motion(ref);
  if (m.freeCoordinate >= 0) {
    jacobian.block<3, 3>(0, m.freeCoordinate).setIdentity();
    jacobian.block<3, 3>(0, m.freeCoordinate + 3) = -skew(p - m.centre);  // w x r = -r x w
  }
  for (const JointAxis& joint : m.joints) {
    const Vector3 column =
        joint.revolute ? Vector3(joint.axis.cross(p - joint.origin)) : joint.axis;
    jacobian.col(joint.coordinate) += joint.ratio * column;
  }
  return jacobian;
}

MatrixX GeneralizedCoordinates::angularJacobian(const BodyRef& ref) const {
  MatrixX jacobian = MatrixX::Zero(3, size_);
  const BodyMotion& m = motion(ref);
  if (m.freeCoordinate >= 0) jacobian.block<3, 3>(0, m.freeCoordinate + 3).setIdentity();
  for (const JointAxis& joint : m.joints) {
    if (joint.revolute) jacobian.col(joint.coordinate) += joint.ratio * joint.axis;
  }
  return jacobian;
}

}  // namespace graspkit::dynamics
