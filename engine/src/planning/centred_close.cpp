#include "graspkit/planning/centred_close.hpp"

#include <cmath>
#include <map>
#include <optional>
#include <set>

#include "graspkit/base/error.hpp"
#include "graspkit/collision/collision.hpp"
#include "graspkit/planning/planning_scene.hpp"

namespace graspkit {

namespace {

// The chains of the hand with a link in one of the grasp's contacts.
std::set<int> touchingChains(const PlanningScene& scene, const PlannedGrasp& grasp) {
  std::set<int> chains;
  for (const Contact& c : grasp.contactList)
    for (const BodyRef& body : {c.body1, c.body2})
      if (body.isLink() && body.index == scene.robot() && !body.link.isBase())
        chains.insert(body.link.chain);
  return chains;
}

// The chains that carry one of the scene's virtual contacts: the fingers, when the contacts sit
// on some. A linkage's inner bars (a Robotiq's drivers) carry none: they close with the fingers
// but never reach the object, and their gap to it says nothing of where the pads are.
std::set<int> paddedChains(const PlanningScene& scene) {
  std::set<int> chains;
  for (const VirtualContact& contact : scene.virtualContactModels())
    if (contact.finger >= 0) chains.insert(contact.finger);
  return chains;
}

// With the hand closed in `scene`: the sum, over the chains that touch nothing, of half the
// vector from each chain's nearest point to the object's. Only chains with a virtual contact
// count, unless no chain has one. Nullopt when every such chain touches.
std::optional<Vector3> centringMove(const PlanningScene& scene, const PlannedGrasp& grasp) {
  const std::set<int> touching = touchingChains(scene, grasp);
  const std::set<int> padded = paddedChains(scene);
  std::map<int, DistanceResult> gaps;  // per chain, its nearest link's
  for (const BodyRef& link : scene.handLinks()) {
    if (link.link.isBase() || touching.count(link.link.chain)) continue;
    if (!padded.empty() && !padded.count(link.link.chain)) continue;
    const DistanceResult d = distance(scene.world(), link, scene.object());
    auto [it, added] = gaps.emplace(link.link.chain, d);
    if (!added && d.distance < it->second.distance) it->second = d;
  }
  Vector3 move = Vector3::Zero();
  int chains = 0;
  for (const auto& [chain, gap] : gaps) {
    if (!(gap.distance > 0.0) || !std::isfinite(gap.distance)) continue;
    move += 0.5 * (gap.pointOnB - gap.pointOnA);
    ++chains;
  }
  if (chains == 0) return std::nullopt;
  return move;
}

}  // namespace

void closeCentred(PlanningScene& scene, PlannedGrasp& grasp, const CentringSettings& settings) {
  if (!finishGrasp(scene, grasp, settings.keepGoing, settings.measure)) return;
  for (int move = 0; move < settings.moves && !grasp.forceClosure; ++move) {
    if (settings.keepGoing && !settings.keepGoing()) return;
    const std::optional<Vector3> shift = centringMove(scene, grasp);
    if (!shift || shift->norm() < 1e-6) return;
    PlannedGrasp moved = grasp;
    moved.pose.translation() += *shift;
    try {
      moved.values = scene.space().encode(moved.pose, moved.dofs);
    } catch (const Error&) {
      return;  // a space without an inverse cannot hold the moved pose
    }
    // The search space may bound the position: the moved grasp must be one it can name.
    moved.pose = scene.space().handPose(moved.values);
    scene.setHand(moved.pose, moved.dofs);
    if (scene.handCollides()) return;
    if (!finishGrasp(scene, moved, settings.keepGoing, settings.measure)) return;
    if (orderNeedsVolume(moved, grasp)) {
      measureVolume(scene.world(), scene.robot(), scene.object(), moved);
      measureVolume(scene.world(), scene.robot(), scene.object(), grasp);
    }
    if (!betterGrasp(moved, grasp)) return;
    grasp = std::move(moved);
  }
}

}  // namespace graspkit
