// Mass properties from volume integrals. Each triangle (a, b, c) and a reference point span a
// signed tetrahedron; by the divergence theorem the signed tetrahedra of a closed mesh sum to
// the solid, so their volume, first and second moments sum to the solid's. This is exact, like
// Mirtich's projection/face integrals that GraspIt! uses, and gives the same numbers.

#include "graspkit/mass_properties.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace graspkit {
namespace {

// GraspIt!'s limits for trusting the integrals (DynamicBody's default mass properties).
constexpr double kMinVolume = 1e-5;           // mm^3
constexpr double kMaxCentroidDistance = 500;  // mm

struct VolumeMoments {
  double volume = 0.0;               // integral of 1
  Vector3 first = Vector3::Zero();   // integral of x
  Matrix3 second = Matrix3::Zero();  // integral of x x^T
};

// Moments about `origin`. Taking the origin near the mesh (rather than at the body frame's
// origin) keeps the large, cancelling terms out of the sums for meshes far from their frame.
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
  }
  return m;
}

Vector3 vertexMean(const TriangleMesh& mesh) {
  Vector3 mean = Vector3::Zero();
  for (const Vector3& v : mesh.vertices) mean += v;
  return mesh.vertices.empty() ? mean : Vector3(mean / static_cast<double>(mesh.vertices.size()));
}

bool hasRepeatedCorner(const std::array<std::uint32_t, 3>& tri) {
  return tri[0] == tri[1] || tri[1] == tri[2] || tri[2] == tri[0];
}

}  // namespace

MassProperties computeMassProperties(const TriangleMesh& mesh) {
  MassProperties out;
  out.centroid.setZero();
  out.inertia.setZero();
  const Vector3 origin = vertexMean(mesh);
  const VolumeMoments m = volumeMoments(mesh, origin);
  // Written so that NaN fails too. A negative volume is an inside-out mesh.
  if (!(m.volume >= kMinVolume)) return out;
  const Vector3 offset = m.first / m.volume;  // centroid relative to `origin`
  const Matrix3 central = m.second - m.volume * offset * offset.transpose();
  // Inertia of the solid at density 1/volume (unit mass): (tr(C) 1 - C) / volume.
  const Matrix3 inertia = (central.trace() * Matrix3::Identity() - central) / m.volume;
  const Vector3 centroid = origin + offset;
  if (!centroid.allFinite() || !inertia.allFinite()) return out;
  if (centroid.norm() > kMaxCentroidDistance) return out;
  if (!isClosed(mesh)) return out;
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
