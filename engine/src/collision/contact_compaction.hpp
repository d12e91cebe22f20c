#pragma once
// Internal: GraspIt!'s clean-up of raw contact point pairs between two bodies. First, pairs
// within the duplicate distance on both bodies merge, the closer one surviving. Then pairs whose
// normals agree form groups, and each group keeps only its perimeter: the two ends when the
// points lie on a line, the 2-D convex hull (qhull) otherwise.

#include <vector>

#include "graspkit/math/transform.hpp"

namespace graspkit::collision {

struct RawContact {
  Vector3 onFirst;    // world, mm
  Vector3 onSecond;   // world, mm
  Vector3 intoFirst;  // a face normal pointing into the first body, for touching points
  // What duplicates compete on: the smaller survives. The squared separation, or GraspIt!'s
  // own figure (see ContactRequest::graspitDuplicates).
  double rank = 0.0;
  double distanceSq() const { return (onFirst - onSecond).squaredNorm(); }
  Vector3 normal() const;  // into the first body: (onFirst - onSecond) normalised
};

void removeDuplicates(std::vector<RawContact>& contacts, double duplicate_distance);
void compactContacts(std::vector<RawContact>& contacts);

}  // namespace graspkit::collision
