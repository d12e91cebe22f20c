#pragma once
// Internal: the surface points around a contact that its soft-finger patch is fitted to, and
// GraspIt!'s merge of contacts whose patches share a point (two contacts on one patch of an
// elastic body are one contact). See graspkit/collision/contact_patch.hpp for what is fitted.

#include <vector>

#include "graspkit/math/transform.hpp"

namespace graspkit::raycast {
class EmbreeMesh;
}

namespace graspkit::collision {

// Points of one body's surface around a contact, in the body's frame (mm): the corners of every
// triangle that faces the same way as the surface at the contact and comes within the radius
// of it, each once, then the contact point itself (GraspIt!'s RegionCallback and FindRegion).
using Neighbourhood = std::vector<Vector3>;

// `inward` is the contact normal pointing into the body (body frame).
Neighbourhood surfaceNeighbourhood(const raycast::EmbreeMesh& mesh, const Vector3& point,
                                   const Vector3& inward, double radius);

// The contacts of one body pair, each with its neighbourhoods on the first and second body.
struct PatchCandidate {
  std::size_t contact;  // index into the caller's contact list
  double distance;      // separation of the contact's two points, mm
  Neighbourhood onFirst;
  Neighbourhood onSecond;
};

// GraspIt!'s mergeSoftNeighborhoods: while two contacts' neighbourhoods on the first body
// overlap (share a point exactly: same mesh, same vertex), the farther one goes and its points
// join the nearer one's (on both bodies; a tie, within 1e-9 mm, keeps the one GraspIt!'s scan
// meets second). The survivors keep their order. Quadratic in the number of contacts at worst.
void mergeOverlappingPatches(std::vector<PatchCandidate>& candidates);

}  // namespace graspkit::collision
