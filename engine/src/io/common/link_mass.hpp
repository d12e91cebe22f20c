#pragma once
// Internal: a link's mass properties from the parts a URDF or MJCF file gives (each part's mass
// and inertia gathered about the link's origin), shared by both readers.

#include "graspkit/model/body.hpp"

namespace graspkit::io {

// Sets `body`'s mass (g), CoG (mm) and inertia (per unit mass, about the CoG, mm^2) from the
// parts' total mass, their sum of mass times centre, and their inertia about the body origin
// (g mm^2). Parts with mass but no inertia (MJCF geoms counted by mass alone) take the inertia
// of the body's mesh. With no mass at all, GraspIt!'s defaults: 300 g and the mesh's inertia.
// The body's mesh must be set.
void setLinkMassProperties(BodyModel& body, double mass, const Vector3& moment,
                           const Matrix3& inertia_about_origin);

}  // namespace graspkit::io
