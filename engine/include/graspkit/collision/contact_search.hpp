#pragma once
// Finding contacts between two bodies, as GraspIt! does: every triangle pair closer than the
// threshold (and not interpenetrating) contributes its nearest point pairs; pairs within the
// duplicate distance on both bodies merge (the closer survives); pairs sharing a normal shrink
// to the perimeter of their patch. Triangle pairs are found through each mesh's shared Embree
// geometry with searches bounded by the threshold, so the cost follows the touching area, not
// the meshes' size.

#include <vector>

#include "graspkit/collision/contact.hpp"

namespace graspkit {

class World;

struct ContactRequest {
  double threshold = kContactThreshold;  // mm
  // mm; point pairs repeated exactly (the same vertex near the same face, found from each
  // triangle around it) count once whatever this is.
  double duplicateDistance = kDuplicateDistance;
  bool compact = true;       // keep only the perimeter of contacts that share a normal
  bool softContacts = true;  // elastic bodies make soft-finger contacts (GraspIt!'s default)
  // Which of two duplicate contacts survives. GraspIt! keeps the one whose two points, each
  // taken in its own body's frame, are nearer (a figure with no physical meaning, but its
  // contact sets follow from it); false keeps the truly closer pair.
  bool graspitDuplicates = true;
  // Surfaces that touch without crossing (a mug standing on a floor, its bottom in the floor's
  // plane) give contacts at distance 0; GraspIt! counts them as interpenetrating.
  bool touchingIsContact = false;
  // With graspitDuplicates false, a threshold above twice this is searched in two stages: first
  // within this, then only the triangle pairs that the first stage's survivors do not already
  // make duplicates of. The contacts are the same, in the same order; two dense meshes face to
  // face (a gripper's fingers closed on each other) are searched many times faster. 0: one stage.
  double firstStageThreshold = kContactThreshold;  // mm
};

struct ContactResult {
  std::vector<Contact> contacts;  // seen from the first body
  // Some triangle pairs intersect: the bodies interpenetrate. Those pairs give no contacts.
  bool interpenetrating = false;
};

// Contacts between two bodies of `world`, seen from `body1` (the normal points into body1).
// Throws graspkit::Error when a BodyRef names nothing.
ContactResult findContacts(const World& world, const BodyRef& body1, const BodyRef& body2,
                           const ContactRequest& request = {});

// Whether findContacts would find any contact between the two bodies: the search stops at the
// first. The cheap question of which links touch something.
bool inContact(const World& world, const BodyRef& body1, const BodyRef& body2,
               const ContactRequest& request = {});

// Whether the two bodies' surfaces come closer than `distance` mm, crossing surfaces included:
// withinDistance's question (graspkit/collision/collision.hpp) answered by the contact search,
// which visits only the triangles near the other body, where FCL's distance traversal has to
// descend many bounding-volume pairs of two near-touching meshes.
bool surfacesWithin(const World& world, const BodyRef& body1, const BodyRef& body2,
                    double distance);

}  // namespace graspkit
