#pragma once
// What one search thread works in: its own clone of the world, the hand and the object being
// grasped, the search space, and the queries the energies need (hand collisions, the nearest
// point of the object, the virtual contacts in world coordinates). Concurrent searches each
// make their own PlanningScene from the same world, so nothing in it is shared between threads
// except immutable models.

#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "graspkit/model/body_ref.hpp"
#include "graspkit/model/virtual_contact.hpp"
#include "graspkit/model/world.hpp"
#include "graspkit/planning/hand_configuration.hpp"
#include "graspkit/planning/search_energy.hpp"
#include "graspkit/planning/search_space.hpp"
#include "graspkit/raycast/ray_scene.hpp"

namespace graspkit {

// A virtual contact of the hand placed in the world.
struct PlacedVirtualContact {
  Vector3 point = Vector3::Zero();          // world, mm
  Vector3 normal = Vector3::UnitZ();        // world, unit, pointing away from the hand
  Transform frame = Transform::Identity();  // the contact frame in the world (z = normal)
  int index = 0;                            // into RobotModel::virtualContacts
};

// `contact` (in its link's frame) placed where `robot`'s links are now.
PlacedVirtualContact placeVirtualContact(const Robot& robot, const VirtualContact& contact);

class PlanningScene {
 public:
  // Throws graspkit::Error for a bad robot index, a robot that is not a hand, or an object that
  // is not a graspable body of `world`.
  PlanningScene(World world, int robot, BodyRef object, std::shared_ptr<const SearchSpace> space);

  World& world() { return world_; }
  const World& world() const { return world_; }
  int robot() const { return robot_; }
  const Robot& hand() const { return world_.robot(robot_); }
  const BodyRef& object() const { return object_; }
  const SearchSpace& space() const { return *space_; }
  const std::shared_ptr<const SearchSpace>& spacePtr() const { return space_; }
  // The object's largest CoG-to-vertex distance: GraspIt!'s length scale for torques and for
  // the distance between states.
  double objectRadius() const { return object_radius_; }

  // Puts the hand where `values` say (pose and DOFs).
  void place(std::span<const double> values);
  // Puts the hand at `pose` with `dofs` (clamped into range), every joint re-engaged, so what
  // an earlier autograsp left behind (broken-away joints) cannot leak into the next state.
  void setHand(const Transform& pose, std::span<const double> dofs);
  // The hand's configuration, to put it back after an energy moved it (autograsp does).
  HandConfiguration handConfiguration() const;
  void restore(const HandConfiguration& configuration);

  // Whether any of the hand's links collides with anything (other bodies or the hand itself,
  // as the world's collision filter pairs them).
  bool handCollides() const;

  // The hand's virtual contacts where the hand now is.
  std::vector<PlacedVirtualContact> virtualContacts() const;
  // The virtual contacts the energies use (PlacedVirtualContact::index points here): the
  // model's, or, for a hand whose file gives none, deriveVirtualContacts() of it.
  const std::vector<VirtualContact>& virtualContactModels() const { return virtual_contacts_; }
  bool virtualContactsDerived() const { return derived_contacts_; }
  // The nearest point of the object's surface to `point`, within `maxDistance` mm.
  std::optional<SurfacePoint> nearestObjectPoint(
      const Vector3& point, double maxDistance = std::numeric_limits<double>::infinity()) const;

  const std::vector<BodyRef>& handLinks() const { return hand_links_; }

 private:
  World world_;
  int robot_;
  BodyRef object_;
  std::shared_ptr<const SearchSpace> space_;
  double object_radius_ = 0.0;
  std::vector<BodyRef> hand_links_;
  RayScene object_scene_;
  std::vector<VirtualContact> virtual_contacts_;
  std::vector<Transform> contact_frames_;  // each contact's frame in its link's, made once
  bool derived_contacts_ = false;
};

// Places the hand at `values` and returns the state's energy, or nullopt when the state is
// illegal (the hand collides and the energy rejects collisions). The hand stays where the
// energy left it.
std::optional<double> evaluateState(PlanningScene& scene, SearchEnergy& energy,
                                    std::span<const double> values);

}  // namespace graspkit
