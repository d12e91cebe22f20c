#pragma once
// Mass properties of a closed triangle mesh from volume integrals (Mirtich, "Fast and accurate
// computation of polyhedral mass properties", 1996), plus the surface centroid GraspIt! uses
// as the default centre of gravity.

#include "graspkit/mesh.hpp"

namespace graspkit {

struct MassProperties {
  double volume = 0.0;  // mm^3
  Vector3 centroid;     // volume centroid, mm, body frame
  Matrix3 inertia;      // about the centroid, per unit mass (density = 1/volume), mm^2
  bool valid = false;   // false for an open, degenerate or inside-out mesh
};

// Volume, centroid and inertia of the solid bounded by `mesh`. Never returns NaN: a mesh whose
// integrals are unusable (volume < 1e-5 mm^3, NaN, centroid more than 500 mm out) comes back
// with valid = false and zero values. "Open" is judged geometrically, by the divergence theorem
// (a hole or a missing face fails), not by isClosed: GraspIt!'s models are often closed only
// geometrically (unwelded seams, T-junctions) and GraspIt! integrates them.
MassProperties computeMassProperties(const TriangleMesh& mesh);

// Area-weighted centroid of the surface (GraspIt!'s default CoG).
Vector3 surfaceCentroid(const TriangleMesh& mesh);

// Largest distance from `point` to a vertex (GraspIt!'s maxRadius when point = CoG).
double maxRadius(const TriangleMesh& mesh, const Vector3& point);

// True when every edge is shared by exactly two triangles with opposite orientation.
bool isClosed(const TriangleMesh& mesh);

}  // namespace graspkit
