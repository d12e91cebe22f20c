#include "graspkit/model/kinematic_chain.hpp"

namespace graspkit {

int jointsConsumed(DynamicJointType type) {
  switch (type) {
    case DynamicJointType::Revolute:
    case DynamicJointType::Prismatic:
      return 1;
    case DynamicJointType::Universal:
      return 2;
    case DynamicJointType::Ball:
      return 3;
    case DynamicJointType::Fixed:
      return 0;
  }
  return 1;
}

namespace {

// Each joint frame of the chain in turn into `frames` (its storage kept).
void accumulateJointFrames(const KinematicChain& chain, const Transform& chain_base_in_world,
                           std::span<const double> joint_values, std::vector<Transform>& frames) {
  frames.clear();
  Transform frame = chain_base_in_world;
  for (std::size_t j = 0; j < chain.joints.size(); ++j) {
    frame = frame * chain.joints[j].transform(joint_values[j]);
    frames.push_back(frame);
  }
}

}  // namespace

std::vector<Transform> jointFrames(const KinematicChain& chain,
                                   const Transform& chain_base_in_world,
                                   std::span<const double> joint_values) {
  std::vector<Transform> frames;
  frames.reserve(chain.joints.size());
  accumulateJointFrames(chain, chain_base_in_world, joint_values, frames);
  return frames;
}

std::vector<Transform> linkPoses(const KinematicChain& chain, const Transform& chain_base_in_world,
                                 std::span<const double> joint_values) {
  std::vector<Transform> poses;
  linkPoses(chain, chain_base_in_world, joint_values, poses);
  return poses;
}

void linkPoses(const KinematicChain& chain, const Transform& chain_base_in_world,
               std::span<const double> joint_values, std::vector<Transform>& poses) {
  thread_local std::vector<Transform> frames;
  accumulateJointFrames(chain, chain_base_in_world, joint_values, frames);
  poses.clear();
  for (const Link& link : chain.links) {
    poses.push_back((link.lastJoint < 0 ? chain_base_in_world : frames[link.lastJoint]) *
                    link.frame);
  }
}

}  // namespace graspkit
