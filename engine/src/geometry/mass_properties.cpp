// Mass properties from volume integrals. Each triangle (a, b, c) and a reference point span a
// signed tetrahedron; by the divergence theorem the signed tetrahedra of a closed mesh sum to
// the solid, so their volume, first and second moments sum to the solid's. This is exact, like
// Mirtich's projection/face integrals that GraspIt! uses, and gives the same numbers.

#include "graspkit/mass_properties.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace graspkit {
namespace {

// GraspIt!'s limits for trusting the integrals (DynamicBody's default mass properties).
constexpr double kMinVolume = 1e-5;           // mm^3
constexpr double kMaxCentroidDistance = 500;  // mm

// How far a surface may be from enclosing a volume (see closureResidual), roughly the area of
// its holes relative to its whole area. Float-precision meshes that are closed give 1e-8 or
// less; GraspIt!'s objects at most 6e-6 (p51.iv, three slits); ShadowHand's Palm.iv 2.5e-4.
// Genuinely open meshes give 4e-3 (ShadowHand's TH_Distal.iv) to 0.2 (a cube missing a face).
constexpr double kMaxClosureResidual = 1e-3;

struct VolumeMoments {
  double volume = 0.0;               // integral of 1
  Vector3 first = Vector3::Zero();   // integral of x
  Matrix3 second = Matrix3::Zero();  // integral of x x^T
  // Surface integrals for the closure test: of n dA, of |n| dA and of n x^T dA.
  Vector3 vector_area = Vector3::Zero();
  double area = 0.0;
  Matrix3 flux = Matrix3::Zero();
};

// Moments about `origin`.
VolumeMoments volumeMoments(const TriangleMesh& mesh, const Vector3& origin) {
  VolumeMoments m;
  for (const auto& tri : mesh.triangles) {
    const Vector3 a = mesh.vertices[tri[0]] - origin;
    const Vector3 b = mesh.vertices[tri[1]] - origin;
    const Vector3 c = mesh.vertices[tri[2]] - origin;
    const double det = a.dot(b.cross(c));  // 6 x signed volume of the tetrahedron (0, a, b, c)
    const Vector3 sum = a + b + c;
    m.volume += det / 6.0;
    m.first += (det / 24.0) * sum;
    // Integral of x x^T over the tetrahedron: det/120 (a a^T + b b^T + c c^T + s s^T).
    m.second += (det / 120.0) *
                (a * a.transpose() + b * b.transpose() + c * c.transpose() + sum * sum.transpose());
    const Vector3 area_normal = 0.5 * (b - a).cross(c - a);
    m.vector_area += area_normal;
    m.area += area_normal.norm();
    m.flux += area_normal * (sum / 3.0).transpose();
  }
  return m;
}

// Whether the surface encloses a volume, judged by the divergence theorem: for a closed
// surface the integral of n dA vanishes and the integral of n x^T dA is the volume times the
// identity, whatever the triangulation. Topological closedness (isClosed) is too strict here:
// GraspIt!'s models are often closed only geometrically (unwelded seams, T-junctions, a few
// doubled faces) and GraspIt! integrates them; a hole or a missing face shows up here instead.
// Returns a dimensionless residual: 0 for a closed surface.
double closureResidual(const VolumeMoments& m, double radius) {
  if (!(m.area > 0.0) || !(radius > 0.0)) return std::numeric_limits<double>::infinity();
  const double flux_volume = m.flux.trace() / 3.0;
  const double vector_area = m.vector_area.norm() / m.area;
  const double flux = (m.flux - flux_volume * Matrix3::Identity()).norm() / (m.area * radius);
  return std::max(vector_area, flux);
}

bool hasRepeatedCorner(const std::array<std::uint32_t, 3>& tri) {
  return tri[0] == tri[1] || tri[1] == tri[2] || tri[2] == tri[0];
}

}  // namespace

MassProperties computeMassProperties(const TriangleMesh& mesh) {
  MassProperties out;
  out.centroid.setZero();
  out.inertia.setZero();
  // GraspIt! integrates about the body frame's origin; for an open mesh (common in its
  // corpus) the result depends on that point, so use the same one.
  const Vector3 origin = Vector3::Zero();
  const VolumeMoments m = volumeMoments(mesh, origin);
  // Written so that NaN fails too. A negative volume is an inside-out mesh.
  if (!(m.volume >= kMinVolume)) return out;
  if (!(closureResidual(m, maxRadius(mesh, origin)) <= kMaxClosureResidual)) return out;
  const Vector3 offset = m.first / m.volume;  // centroid relative to `origin`
  const Matrix3 central = m.second - m.volume * offset * offset.transpose();
  // Inertia of the solid at density 1/volume (unit mass): (tr(C) 1 - C) / volume.
  const Matrix3 inertia = (central.trace() * Matrix3::Identity() - central) / m.volume;
  const Vector3 centroid = origin + offset;
  if (!centroid.allFinite() || !inertia.allFinite()) return out;
  if (centroid.norm() > kMaxCentroidDistance) return out;
  out.volume = m.volume;
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
