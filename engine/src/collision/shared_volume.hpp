#pragma once
// Internal: whether two bodies share volume, not only surface. The contact search sees crossing
// triangles; two bodies can overlap with no triangle crossing another when their faces are
// coplanar (a box placed inside an equal box's footprint, or the same object loaded twice at
// one pose). Dynamics asks this of the state it starts from, so that such a world is an error
// and not a simulation that "completes" with the bodies inside each other.

#include "graspkit/model/body_ref.hpp"

namespace graspkit {

class World;

// True when a point of one body (a triangle's centroid, or its centre of mass where that lies
// inside it) lies inside the other deeper than `depth` mm. Only closed meshes (every edge shared
// by two triangles) are judged: inside and outside mean nothing for an open one, which gives
// false.
bool sharesVolume(const World& world, const BodyRef& body1, const BodyRef& body2, double depth);

}  // namespace graspkit
