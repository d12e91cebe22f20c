#pragma once
// Whether closing the hand can bring it into contact with the object, decided without closing
// it: most states of an autograsp-quality search close on empty space (on GraspIt!'s plannerMug,
// 1,918 of the first 2,000 closes touch nothing of the mug), and their energy is known to be
// that of no contact at all.
//
// The bound. A close moves only the DOFs, each within an interval (RobotType::closeMotion: from
// its value toward its closing end, or anywhere within its limits), so every joint of a chain
// stays within an interval too: one box in the chain's joint space holds every posture the
// close can pass through, whatever stops it. Each link is held by a few balls (its vertices
// split across their box's longest side, twice). Over a box, each ball moves away
// from where it is at the box's centre by at most sum_j half-width_j * lever_j, where lever_j
// bounds the ball centre's distance from the axis of revolute joint j (the DH translations from
// that joint to the link, plus the centre's offset in the link frame) and is 1 for a prismatic
// joint. When no ball, grown by that and by the contact threshold, holds a point of the
// object's surface, no posture in the box has a contact; otherwise the box is split in two
// across the joint that moves the failing ball most, as branch and bound does, until a budget
// of boxes runs out. Links that do not move are measured exactly (FCL, collision.hpp).
//
// Only "cannot touch" is a proof. "May touch" says nothing: the close then runs.

#include <memory>
#include <vector>

#include "graspkit/math/transform.hpp"

namespace graspkit {

class PlanningScene;
struct RobotModel;

// What the bound needs of a hand model, computed once per model.
struct CloseReach {
  // A ball holding part of a link's mesh (a link without triangles has none: it cannot touch).
  struct LinkBall {
    std::size_t link = 0;              // chain-local
    Vector3 centre = Vector3::Zero();  // in the link's body frame
    double radius = 0.0;
    std::vector<double> levers;  // per chain-local joint; 0 past the link's last joint
  };
  std::shared_ptr<const RobotModel> model;
  std::vector<std::vector<LinkBall>> chains;  // [chain]: every ball of its links
  Vector3 palmCentre = Vector3::Zero();
  double palmRadius = -1.0;  // negative: the palm has no triangles
};

CloseReach closeReachOf(std::shared_ptr<const RobotModel> model);

// False only when no posture the hand's close can pass through (from the scene's hand as it
// stands) brings a hand link within `threshold` mm of the object's surface. `reach` must be of
// the scene hand's model. True for a hand whose close moves more than its DOFs
// (CloseMotion::Unknown) or that carries another robot.
bool closeMayTouchObject(const PlanningScene& scene, const CloseReach& reach, double threshold);

}  // namespace graspkit
