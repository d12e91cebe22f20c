#include "graspkit/planning/planning_scene.hpp"

#include <fmt/format.h>

#include "graspkit/base/error.hpp"
#include "graspkit/collision/collision.hpp"

namespace graspkit {

namespace {

RayScene objectOnly(const World& world, const BodyRef& object) {
  RaySceneOptions options;
  options.include = [object](const BodyRef& body) { return body == object; };
  return RayScene(world, options);
}

World validated(World world, int robot, const BodyRef& object) {
  if (robot < 0 || robot >= world.robotCount())
    throw Error(
        fmt::format("robot {} out of range: the world has {} robot(s)", robot, world.robotCount()));
  if (world.robot(robot).model().chains.empty())
    throw Error(fmt::format("robot {} ({}) has no fingers to plan grasps with", robot,
                            world.robot(robot).name()));
  if (object.kind != BodyRef::Kind::Body || !isValid(world, object))
    throw Error("the object to grasp must be a body of the world");
  return world;
}

}  // namespace

PlanningScene::PlanningScene(World world, int robot, BodyRef object,
                             std::shared_ptr<const SearchSpace> space)
    : world_(validated(std::move(world), robot, object)),
      robot_(robot),
      object_(object),
      space_(std::move(space)),
      object_radius_(bodyModel(world_, object).maxRadius),
      object_scene_(objectOnly(world_, object)) {
  if (!space_) throw Error("a planning scene needs a search space");
  for (const BodyRef& body : worldBodies(world_))
    if (body.isLink() && body.index == robot_) hand_links_.push_back(body);
  virtual_contacts_ = hand().model().virtualContacts;
  if (virtual_contacts_.empty()) {
    virtual_contacts_ = deriveVirtualContacts(hand());
    derived_contacts_ = true;
  }
  for (const VirtualContact& contact : virtual_contacts_)
    contact_frames_.push_back(makeTransform(contact.translation, contact.rotation));
}

void PlanningScene::place(std::span<const double> values) {
  setHand(space_->handPose(values), space_->dofs(values));
}

void PlanningScene::setHand(const Transform& pose, std::span<const double> dofs) {
  const Robot& robot = hand();
  for (int j = 0; j < static_cast<int>(robot.breakaway().size()); ++j)
    if (robot.breakaway()[j].engaged) world_.setBreakaway(robot_, j, BreakawayState{});
  world_.setRobotPoseAndDofValues(robot_, pose, dofs, LimitPolicy::Clamp);
}

HandConfiguration PlanningScene::handConfiguration() const {
  return handConfigurationOf(world_, robot_);
}

void PlanningScene::restore(const HandConfiguration& configuration) {
  applyHandConfiguration(world_, robot_, configuration);
}

bool PlanningScene::handCollides() const {
  return anyCollision(world_, hand_links_);
}

namespace {

PlacedVirtualContact placeWithFrame(const Robot& robot, const VirtualContact& contact,
                                    const Transform& frame_in_link) {
  const Transform& link =
      contact.finger < 0 ? robot.pose() : robot.linkPose(contact.finger, contact.link);
  PlacedVirtualContact p;
  p.point = link * contact.location;
  p.normal = (link.linear() * contact.normal).normalized();
  p.frame = link * frame_in_link;
  return p;
}

}  // namespace

std::vector<PlacedVirtualContact> PlanningScene::virtualContacts() const {
  const Robot& robot = hand();
  const auto& contacts = virtual_contacts_;
  std::vector<PlacedVirtualContact> placed;
  placed.reserve(contacts.size());
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    PlacedVirtualContact p = placeWithFrame(robot, contacts[i], contact_frames_[i]);
    p.index = static_cast<int>(i);
    placed.push_back(p);
  }
  return placed;
}

PlacedVirtualContact placeVirtualContact(const Robot& robot, const VirtualContact& contact) {
  return placeWithFrame(robot, contact, makeTransform(contact.translation, contact.rotation));
}

std::optional<SurfacePoint> PlanningScene::nearestObjectPoint(const Vector3& point,
                                                              double maxDistance) const {
  return object_scene_.nearestSurfacePoint(point, maxDistance);
}

HandConfiguration handConfigurationOf(const World& world, int robot) {
  const Robot& hand = world.robot(robot);
  return {hand.pose(),
          {hand.dofValues().begin(), hand.dofValues().end()},
          {hand.breakaway().begin(), hand.breakaway().end()}};
}

void applyHandConfiguration(World& world, int robot, const HandConfiguration& configuration) {
  const Robot& hand = world.robot(robot);
  if (configuration.breakaway.size() != hand.breakaway().size())
    throw Error(fmt::format("robot '{}' has {} joints; the hand configuration has {}", hand.name(),
                            hand.breakaway().size(), configuration.breakaway.size()));
  for (int j = 0; j < static_cast<int>(configuration.breakaway.size()); ++j)
    world.setBreakaway(robot, j, configuration.breakaway[j]);
  world.setRobotPose(robot, configuration.pose);
  world.setDofValues(robot, configuration.dofs, LimitPolicy::Ignore);
}

std::optional<double> evaluateState(PlanningScene& scene, SearchEnergy& energy,
                                    std::span<const double> values) {
  scene.place(values);
  if (energy.rejectsCollisions() && scene.handCollides()) return std::nullopt;
  return energy.evaluate(scene);
}

}  // namespace graspkit
