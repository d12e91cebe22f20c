#pragma once
// Which pairs of bodies collision detection looks at. Two layers decide:
//
// 1. The robots' own rules, fixed by their files and by how robots are mounted; they always
//    apply and no switch below turns them back on. They are the rules GraspIt! sets up when it
//    loads a robot or a world:
//    - a link with collisionRule "Off" collides with nothing (KinematicChain::initChainFromXml);
//    - a link with collisionRule "OverlappingPair" never collides with its target (idem);
//    - the robot file's <disableCollision> pairs (RobotModel::disabledCollisions);
//    - links of one chain never collide with each other, adjacent or not, because link meshes
//      overlap at the joints (World::addRobot);
//    - the base never collides with the first link of each chain (World::addRobot);
//    - a mount piece never collides with its child robot's base nor with the last link of the
//      parent chain it hangs from (World::load, Robot::attachRobot);
//    - a mounted robot's base never collides with the last link of its parent chain
//      (Robot::attachRobot).
// 2. Switches the user sets per body, per pair and per robot (GraspIt!'s toggleCollisions). They
//    only ever turn pairs off: enabling undoes an earlier disabling.
//
// Two obstacles are checked against each other by default, as GraspIt! does (its active-pair
// list excludes nothing by kind); setStaticPairsEnabled(false) skips them.
//
// The filter is a plain value held by World, so World::clone() copies it and a clone's changes
// never reach the original.

#include <utility>
#include <vector>

#include "graspkit/model/body_ref.hpp"

namespace graspkit {

class World;

class CollisionFilter {
 public:
  void setBodyEnabled(const BodyRef& body, bool enabled);
  void setPairEnabled(const BodyRef& a, const BodyRef& b, bool enabled);
  // A robot's base, links and mount piece (the mount of the connection it is the child of).
  void setRobotEnabled(int robot, bool enabled);
  // Obstacle against obstacle; on by default, as in GraspIt!.
  void setStaticPairsEnabled(bool enabled) { static_pairs_ = enabled; }

  // Free body `index` left the world (World::removeBody): its switches go, and the switches of
  // the bodies after it follow them to their new indices.
  void bodyRemoved(int index);

  bool bodyEnabled(const BodyRef& body) const;
  bool pairEnabled(const BodyRef& a, const BodyRef& b) const;  // the user's switch only
  bool robotEnabled(int robot) const;
  bool staticPairsEnabled() const { return static_pairs_; }

  // Whether collision detection looks at the pair (a, b): false for a body with itself, for a
  // pair the robots' rules exclude, and for anything switched off. Throws graspkit::Error when
  // either body is not in `world`.
  bool isActive(const World& world, const BodyRef& a, const BodyRef& b) const;

 private:
  // Kept sorted: lookups are binary searches, and equal filters compare equal.
  std::vector<BodyRef> disabled_bodies_;
  std::vector<std::pair<BodyRef, BodyRef>> disabled_pairs_;  // first < second
  std::vector<int> disabled_robots_;
  bool static_pairs_ = true;
};

// The robots' own rules alone (layer 1 above): false when a rule excludes the pair.
bool robotRulesAllow(const World& world, const BodyRef& a, const BodyRef& b);

}  // namespace graspkit
