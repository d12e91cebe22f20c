#include "collision/convex_hull.hpp"

extern "C" {
#include <libqhull_r/qhull_ra.h>
}

#include <cstdio>
#include <unordered_map>

namespace graspkit::collision {
namespace {

FILE* nullSink() {
  static FILE* sink = std::fopen("/dev/null", "w");
  return sink;
}

}  // namespace

std::optional<ConvexHull> convexHull(const std::vector<Vector3>& points) {
  if (points.size() < 4) return std::nullopt;
  std::vector<double> coords;
  coords.reserve(3 * points.size());
  for (const Vector3& p : points) coords.insert(coords.end(), {p.x(), p.y(), p.z()});

  qhT qh_storage;
  qhT* qh = &qh_storage;
  qh_zero(qh, nullSink());
  // Qt: triangulated facets (FCL's faces); the vertices are input points, never moved.
  char flags[] = "qhull Qt";
  const int status = qh_new_qhull(qh, 3, static_cast<int>(points.size()), coords.data(), False,
                                  flags, nullptr, nullSink());
  std::optional<ConvexHull> hull;
  if (status == 0) {
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
  }
  qh_freeqhull(qh, !qh_ALL);
  int still_long = 0, total_long = 0;
  qh_memfreeshort(qh, &still_long, &total_long);
  return hull;
}

}  // namespace graspkit::collision
