#include "geometry/convex_hull.hpp"

#include <array>
#include <cstdint>
#include <unordered_map>

extern "C" {
#include <libqhull_r/qhull_ra.h>
}

#include "math/qhull_run.hpp"

namespace graspkit::geometry {
std::optional<ConvexHull> convexHull(const std::vector<Vector3>& points) {
  if (points.size() < 4) return std::nullopt;
  std::vector<double> coords;
  coords.reserve(3 * points.size());
  for (const Vector3& p : points) coords.insert(coords.end(), {p.x(), p.y(), p.z()});

  // Qt: triangulated facets (FCL's faces); the vertices are input points, never moved.
  std::optional<ConvexHull> hull;
  const auto failure = detail::runQhull(coords, 3, "Qt", [&](qhT* qh) {
    hull.emplace();
    auto vertices = std::make_shared<std::vector<Vector3>>();
    auto faces = std::make_shared<std::vector<int>>();
    std::unordered_map<int, int> index;  // input point id -> hull vertex index
    vertexT* vertex;
    FORALLvertices {
      const int id = qh_pointid(qh, vertex->point);
      index.emplace(id, static_cast<int>(vertices->size()));
      vertices->push_back(points[static_cast<std::size_t>(id)]);
    }
    int face_count = 0;
    facetT* facet;
    FORALLfacets {
      faces->push_back(qh_setsize(qh, facet->vertices));
      vertexT** vertexp;
      FOREACHvertex_(facet->vertices) faces->push_back(index.at(qh_pointid(qh, vertex->point)));
      ++face_count;
    }
    hull->vertices.resize(3, static_cast<Eigen::Index>(vertices->size()));
    for (std::size_t i = 0; i < vertices->size(); ++i)
      hull->vertices.col(static_cast<Eigen::Index>(i)) = (*vertices)[i];
    hull->shape = std::make_shared<const fcl::Convexd>(vertices, face_count, faces);
  });
  if (failure) return std::nullopt;
  return hull;
}

std::optional<TriangleMesh> convexHullMesh(const std::vector<Vector3>& points) {
  const auto hull = convexHull(points);
  if (!hull) return std::nullopt;
  TriangleMesh mesh;
  mesh.vertices = hull->shape->getVertices();
  // The mean of the hull's vertices is inside it (it has volume), so a facet faces out when its
  // normal points away from there.
  Vector3 inside = Vector3::Zero();
  for (const Vector3& v : mesh.vertices) inside += v;
  inside /= static_cast<double>(mesh.vertices.size());
  const std::vector<int>& faces = hull->shape->getFaces();
  for (std::size_t at = 0; at < faces.size(); at += 1 + static_cast<std::size_t>(faces[at])) {
    if (faces[at] != 3) return std::nullopt;  // "Qt" triangulates; anything else is a surprise
    std::array<std::uint32_t, 3> t = {static_cast<std::uint32_t>(faces[at + 1]),
                                      static_cast<std::uint32_t>(faces[at + 2]),
                                      static_cast<std::uint32_t>(faces[at + 3])};
    const Vector3& p = mesh.vertices[t[0]];
    const Vector3 normal = (mesh.vertices[t[1]] - p).cross(mesh.vertices[t[2]] - p);
    if (normal.dot(p - inside) < 0) std::swap(t[1], t[2]);
    mesh.triangles.push_back(t);
  }
  return mesh;
}

}  // namespace graspkit::geometry
