// Mass properties from Mirtich's volume integrals ("Fast and accurate computation of polyhedral
// mass properties", 1996), as GraspIt! computes them (DynamicBody::computeDefaultInertiaMatrix).
// Each volume integral becomes, by the divergence theorem, a sum of face integrals, and each face
// integral a line integral around the face's projection onto the coordinate plane it is most
// nearly parallel to. For a closed surface this is exact and agrees with any other exact method;
// for an open one the result depends on the method, and GraspIt!'s models are often open, so the
// method is GraspIt!'s: integrands x (volume), x^2/2 (first moments), x^3/3 (second moments) and
// x^2 y/2 (products), each about the body frame's origin.

#include "graspkit/geometry/mass_properties.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace graspkit {
namespace {

// GraspIt!'s limits for trusting the integrals: |volume| >= 1e-5 mm^3, a centroid whose every
// coordinate is within 500 mm of the origin, and no NaN.
constexpr double kMinVolume = 1e-5;           // mm^3
constexpr double kMaxCentroidDistance = 500;  // mm, per coordinate

// Integrals over one triangle's projection onto the plane of axes (a, b): of 1, a, a^2, a^3, b,
// b^2, b^3, ab, a^2 b and a b^2, from the line integrals around its edges (Green's theorem).
struct ProjectionIntegrals {
  double p1 = 0, pa = 0, paa = 0, paaa = 0, pb = 0, pbb = 0, pbbb = 0, pab = 0, paab = 0, pabb = 0;
};

ProjectionIntegrals projectionIntegrals(const std::array<Vector3, 3>& corners, int a, int b) {
  ProjectionIntegrals p;
  for (int e = 0; e < 3; ++e) {
    const double a0 = corners[e][a], b0 = corners[e][b];
    const double a1 = corners[(e + 1) % 3][a], b1 = corners[(e + 1) % 3][b];
    const double da = a1 - a0, db = b1 - b0;
    const double a0_2 = a0 * a0, a0_3 = a0_2 * a0, a0_4 = a0_3 * a0;
    const double b0_2 = b0 * b0, b0_3 = b0_2 * b0, b0_4 = b0_3 * b0;
    const double a1_2 = a1 * a1, a1_3 = a1_2 * a1;
    const double b1_2 = b1 * b1, b1_3 = b1_2 * b1;
    const double c1 = a1 + a0;
    const double ca = a1 * c1 + a0_2, caa = a1 * ca + a0_3, caaa = a1 * caa + a0_4;
    const double cb = b1 * (b1 + b0) + b0_2, cbb = b1 * cb + b0_3, cbbb = b1 * cbb + b0_4;
    const double cab = 3 * a1_2 + 2 * a1 * a0 + a0_2, kab = a1_2 + 2 * a1 * a0 + 3 * a0_2;
    const double caab = a0 * cab + 4 * a1_3, kaab = a1 * kab + 4 * a0_3;
    const double cabb = 4 * b1_3 + 3 * b1_2 * b0 + 2 * b1 * b0_2 + b0_3;
    const double kabb = b1_3 + 2 * b1_2 * b0 + 3 * b1 * b0_2 + 4 * b0_3;
    p.p1 += db * c1;
    p.pa += db * ca;
    p.paa += db * caa;
    p.paaa += db * caaa;
    p.pb += da * cb;
    p.pbb += da * cbb;
    p.pbbb += da * cbbb;
    p.pab += db * (b1 * cab + b0 * kab);
    p.paab += db * (b1 * caab + b0 * kaab);
    p.pabb += da * (a1 * cabb + a0 * kabb);
  }
  p.p1 /= 2.0;
  p.pa /= 6.0;
  p.paa /= 12.0;
  p.paaa /= 20.0;
  p.pb /= -6.0;
  p.pbb /= -12.0;
  p.pbbb /= -20.0;
  p.pab /= 24.0;
  p.paab /= 60.0;
  p.pabb /= -60.0;
  return p;
}

// The volume integrals: of 1 (t0), of x, y, z (t1), of x^2, y^2, z^2 (t2), of xy, yz, zx (tp).
struct VolumeIntegrals {
  double t0 = 0;
  Vector3 t1 = Vector3::Zero(), t2 = Vector3::Zero(), tp = Vector3::Zero();
};

// Adds one triangle's share. Its unit normal comes from its corners in order (a zero-area
// triangle gives NaN, which spoils the sum, as in GraspIt!).
void addTriangle(const std::array<Vector3, 3>& v, VolumeIntegrals& t) {
  const Vector3 cross = (v[1] - v[0]).cross(v[2] - v[1]);
  const Vector3 n = cross / cross.norm();
  const double w = -n.dot(v[0]);
  // Project onto the plane most nearly parallel to the face: c is the normal's largest axis.
  const Vector3 m = n.cwiseAbs();
  const int c = (m.x() > m.y() && m.x() > m.z()) ? 0 : (m.y() > m.z() ? 1 : 2);
  const int a = (c + 1) % 3, b = (a + 1) % 3;
  const ProjectionIntegrals p = projectionIntegrals(v, a, b);
  const double na = n[a], nb = n[b], k1 = 1.0 / n[c];
  const double k2 = k1 * k1, k3 = k2 * k1, k4 = k3 * k1;
  // Integrals over the face itself of a, b, c and their powers and products.
  const double fa = k1 * p.pa, fb = k1 * p.pb;
  const double fc = -k2 * (na * p.pa + nb * p.pb + w * p.p1);
  const double faa = k1 * p.paa, fbb = k1 * p.pbb;
  const double fcc = k3 * (na * na * p.paa + 2 * na * nb * p.pab + nb * nb * p.pbb +
                           w * (2 * (na * p.pa + nb * p.pb) + w * p.p1));
  const double faaa = k1 * p.paaa, fbbb = k1 * p.pbbb;
  const double fccc = -k4 * (na * na * na * p.paaa + 3 * na * na * nb * p.paab +
                             3 * na * nb * nb * p.pabb + nb * nb * nb * p.pbbb +
                             3 * w * (na * na * p.paa + 2 * na * nb * p.pab + nb * nb * p.pbb) +
                             w * w * (3 * (na * p.pa + nb * p.pb) + w * p.p1));
  const double faab = k1 * p.paab;
  const double fbbc = -k2 * (na * p.pabb + nb * p.pbbb + w * p.pbb);
  const double fcca = k3 * (na * na * p.paaa + 2 * na * nb * p.paab + nb * nb * p.pabb +
                            w * (2 * (na * p.paa + nb * p.pab) + w * p.pa));
  t.t0 += n.x() * (a == 0 ? fa : (b == 0 ? fb : fc));
  t.t1[a] += na * faa;
  t.t1[b] += nb * fbb;
  t.t1[c] += n[c] * fcc;
  t.t2[a] += na * faaa;
  t.t2[b] += nb * fbbb;
  t.t2[c] += n[c] * fccc;
  t.tp[a] += na * faab;
  t.tp[b] += nb * fbbc;
  t.tp[c] += n[c] * fcca;
}

VolumeIntegrals volumeIntegrals(const TriangleMesh& mesh) {
  VolumeIntegrals t;
  for (const auto& tri : mesh.triangles)
    addTriangle({mesh.vertices[tri[0]], mesh.vertices[tri[1]], mesh.vertices[tri[2]]}, t);
  t.t1 /= 2.0;
  t.t2 /= 3.0;
  t.tp /= 2.0;
  return t;
}

bool hasRepeatedCorner(const std::array<std::uint32_t, 3>& tri) {
  return tri[0] == tri[1] || tri[1] == tri[2] || tri[2] == tri[0];
}

}  // namespace

MassProperties computeMassProperties(const TriangleMesh& mesh) {
  MassProperties out;
  out.centroid.setZero();
  out.inertia.setZero();
  const VolumeIntegrals t = volumeIntegrals(mesh);
  const Vector3 centroid = t.t1 / t.t0;
  // Written so that NaN fails too. An inside-out mesh has a negative volume and, with density
  // 1/volume, the same centroid and inertia: GraspIt! accepts it, and so does this.
  if (!centroid.allFinite() || !(std::abs(t.t0) >= kMinVolume)) return out;
  if (!(centroid.cwiseAbs().maxCoeff() <= kMaxCentroidDistance)) return out;
  const double density = 1.0 / t.t0;  // unit mass
  Matrix3 inertia;
  inertia(0, 0) = density * (t.t2.y() + t.t2.z());
  inertia(1, 1) = density * (t.t2.z() + t.t2.x());
  inertia(2, 2) = density * (t.t2.x() + t.t2.y());
  inertia(0, 1) = inertia(1, 0) = -density * t.tp.x();
  inertia(1, 2) = inertia(2, 1) = -density * t.tp.y();
  inertia(2, 0) = inertia(0, 2) = -density * t.tp.z();
  // About the centroid (parallel axes, unit mass).
  inertia -= centroid.squaredNorm() * Matrix3::Identity() - centroid * centroid.transpose();
  if (!inertia.allFinite()) return out;
  out.volume = t.t0;
  out.centroid = centroid;
  out.inertia = inertia;
  out.valid = true;
  return out;
}

Vector3 surfaceCentroid(const TriangleMesh& mesh) {
  // The area-weighted mean of the triangle centroids is exact for the surface integral of x;
  // GraspIt!'s 7-point Gauss rule gives the same value.
  Vector3 weighted = Vector3::Zero();
  double area = 0.0;
  for (const auto& tri : mesh.triangles) {
    const Vector3& a = mesh.vertices[tri[0]];
    const Vector3& b = mesh.vertices[tri[1]];
    const Vector3& c = mesh.vertices[tri[2]];
    const double triangle_area = 0.5 * (b - a).cross(c - a).norm();
    weighted += triangle_area * (a + b + c) / 3.0;
    area += triangle_area;
  }
  return area > 0.0 ? Vector3(weighted / area) : Vector3::Zero();
}

double maxRadius(const TriangleMesh& mesh, const Vector3& point) {
  double max_squared = 0.0;
  for (const Vector3& v : mesh.vertices)
    max_squared = std::max(max_squared, (v - point).squaredNorm());
  return std::sqrt(max_squared);
}

bool isClosed(const TriangleMesh& mesh) {
  // Every directed edge must appear once and its reverse once: then each undirected edge is
  // used by exactly two triangles that traverse it in opposite directions. Zero-area triangles
  // with a repeated corner bound nothing and are left out.
  std::vector<std::uint64_t> edges;
  edges.reserve(3 * mesh.triangles.size());
  for (const auto& tri : mesh.triangles) {
    if (hasRepeatedCorner(tri)) continue;
    for (int k = 0; k < 3; ++k) {
      edges.push_back(std::uint64_t{tri[k]} << 32 | tri[(k + 1) % 3]);
    }
  }
  if (edges.empty()) return false;
  std::ranges::sort(edges);
  if (std::ranges::adjacent_find(edges) != edges.end()) return false;
  return std::ranges::all_of(edges, [&](std::uint64_t edge) {
    const std::uint64_t reverse = edge << 32 | edge >> 32;
    return std::ranges::binary_search(edges, reverse);
  });
}

}  // namespace graspkit
