#pragma once
// Internal: turning joint axes given as lines in space (URDF, MJCF) into the Denavit-Hartenberg
// joints graspkit's chains hold. Each chain's axes at the zero joint vector become DH frames;
// the links keep their own frames on top (Link::frame).

#include "graspkit/math/transform.hpp"
#include "graspkit/model/joint.hpp"

namespace graspkit::io {

// A frame whose z axis is `z` (unit) and whose x axis is as close to `hint` as z allows.
Matrix3 frameWithZ(const Vector3& z, const Vector3& hint);

// The DH transform's constant part for a joint at the origin of frame `before` (whose z is the
// joint's axis) such that the frame after it has its z on the next joint's axis line (point p,
// unit direction u), its x along the common normal. Sets the joint's theta, d, a, alpha and
// writes the frame after it.
void denavitHartenbergTo(const Transform& before, const Vector3& p, const Vector3& u, Joint& joint,
                         Transform& after);

}  // namespace graspkit::io
