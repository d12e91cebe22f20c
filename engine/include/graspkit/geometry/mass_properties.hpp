#pragma once
// Mass properties of a triangle mesh from Mirtich's volume integrals ("Fast and accurate
// computation of polyhedral mass properties", 1996), computed as GraspIt! computes them, plus
// the surface centroid GraspIt! uses as the default centre of gravity.

#include "graspkit/geometry/mesh.hpp"

namespace graspkit {

struct MassProperties {
  double volume = 0.0;  // mm^3
  Vector3 centroid;     // volume centroid, mm, body frame
  Matrix3 inertia;      // about the centroid, per unit mass (density = 1/volume), mm^2
  bool valid = false;   // false where GraspIt! falls back (see computeMassProperties)
};

// Volume, centroid and inertia of the solid bounded by `mesh`, about the body frame's origin and
// then the centroid, with GraspIt!'s rules: the integrals are taken whether or not the surface is
// closed (an open mesh gives GraspIt!'s numbers), an inside-out mesh gives a negative volume and
// the same centroid and inertia, and the result is unusable (valid = false, zero values, never
// NaN) when |volume| < 1e-5 mm^3, a centroid coordinate is beyond 500 mm, or anything is NaN (a
// zero-area triangle makes it so, as in GraspIt!).
MassProperties computeMassProperties(const TriangleMesh& mesh);

// Area-weighted centroid of the surface (GraspIt!'s default CoG).
Vector3 surfaceCentroid(const TriangleMesh& mesh);

// Largest distance from `point` to a vertex (GraspIt!'s maxRadius when point = CoG).
double maxRadius(const TriangleMesh& mesh, const Vector3& point);

// True when every edge is shared by exactly two triangles with opposite orientation.
bool isClosed(const TriangleMesh& mesh);

}  // namespace graspkit
