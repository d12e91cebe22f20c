// graspkit.RayScene: rays and nearest surface points in batches, NumPy in and out, over the
// engine's Embree scene. The GIL is released while the batch is traced.

#include <chrono>
#include <cmath>
#include <limits>
#include <mutex>
#include <shared_mutex>

#include <fmt/format.h>

#include "graspkit/raycast/ray_scene.hpp"
#include "python_support.hpp"

namespace graspkit::python {
namespace {

constexpr double kFar = 1e20;  // mm, the engine's limit on coordinates

struct BoundRayScene {
  WorldPtr world;  // the world it was built from (for body names); it does not follow changes
  RayScene scene;
  std::vector<std::string> names;
  // Queries run without the GIL: they share the scene, update() takes it alone.
  std::shared_ptr<std::shared_mutex> mutex = std::make_shared<std::shared_mutex>();
};

// One batch's answers, as NumPy arrays; rows without an answer hold -1, inf and NaN.
struct RayHits {
  py::array_t<bool> hit;
  py::array_t<std::int32_t> body;
  py::array_t<std::int32_t> triangle;
  py::array_t<double> distance;
  py::array_t<double> point;
  py::array_t<double> normal;

  explicit RayHits(py::ssize_t n)
      : hit(n),
        body(n),
        triangle(n),
        distance(n),
        point({n, py::ssize_t{3}}),
        normal({n, py::ssize_t{3}}) {}
};

// Raw pointers into a RayHits, so that it can be filled without the GIL.
struct HitColumns {
  bool* hit;
  std::int32_t* body;
  std::int32_t* triangle;
  double* distance;
  double* point;
  double* normal;
  const std::vector<BodyRef>* bodies;

  void set(std::size_t i, const BodyRef& ref, int tri, const Vector3& p, const Vector3& n,
           double d) const {
    hit[i] = true;
    body[i] =
        static_cast<std::int32_t>(std::find(bodies->begin(), bodies->end(), ref) - bodies->begin());
    triangle[i] = tri;
    distance[i] = d;
    for (int k = 0; k < 3; ++k) {
      point[3 * i + k] = p[k];
      normal[3 * i + k] = n[k];
    }
  }
  void miss(std::size_t i) const {
    constexpr double nan = std::numeric_limits<double>::quiet_NaN();
    hit[i] = false;
    body[i] = -1;
    triangle[i] = -1;
    distance[i] = std::numeric_limits<double>::infinity();
    for (int k = 0; k < 3; ++k) point[3 * i + k] = normal[3 * i + k] = nan;
  }
};

HitColumns columns(RayHits& hits, const RayScene& scene) {
  return {hits.hit.mutable_data(),
          hits.body.mutable_data(),
          hits.triangle.mutable_data(),
          hits.distance.mutable_data(),
          hits.point.mutable_data(),
          hits.normal.mutable_data(),
          &scene.bodies()};
}

void checkRays(const double* origins, const double* directions, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) {
    const Vector3 o(origins[3 * i], origins[3 * i + 1], origins[3 * i + 2]);
    const Vector3 d(directions[3 * i], directions[3 * i + 1], directions[3 * i + 2]);
    const char* problem = !o.allFinite() || !d.allFinite() ? "a value is not a finite number"
                          : d.isZero(0)                    ? "the direction is zero"
                          : o.cwiseAbs().maxCoeff() > kFar
                              ? "the origin is more than 1e20 mm from the world origin"
                              : nullptr;
    if (problem) throw py::value_error(fmt::format("ray {}: {}", i, problem));
  }
}

void storeHit(void* context, std::size_t index, const RayHit* hit) {
  const auto& out = *static_cast<const HitColumns*>(context);
  if (hit)
    out.set(index, hit->body, hit->triangle, hit->point, hit->normal, hit->distance);
  else
    out.miss(index);
}

RayHits intersect(const BoundRayScene& s, const py::handle& origins_in,
                  const py::handle& directions_in, double max_distance) {
  const auto origins = toPoints(origins_in, "origins");
  const auto directions = toPoints(directions_in, "directions");
  if (origins.shape(0) != directions.shape(0))
    throw py::value_error(
        fmt::format("{} origins but {} directions", origins.shape(0), directions.shape(0)));
  if (std::isnan(max_distance) || max_distance < 0)
    throw py::value_error("max_distance must be >= 0");
  const auto n = static_cast<std::size_t>(origins.shape(0));
  RayHits hits(origins.shape(0));
  const HitColumns out = columns(hits, s.scene);
  const double* o = origins.data();
  const double* d = directions.data();
  checkRays(o, d, n);
  py::gil_scoped_release release;
  std::shared_lock lock(*s.mutex);
  // In chunks that stay in the cache, so a batch of millions needs no second copy of itself.
  constexpr std::size_t kChunk = 256;
  Ray rays[kChunk];
  for (std::size_t start = 0; start < n; start += kChunk) {
    const std::size_t count = std::min(kChunk, n - start);
    for (std::size_t i = 0; i < count; ++i) {
      const std::size_t j = 3 * (start + i);
      rays[i].origin = Vector3(o[j], o[j + 1], o[j + 2]);
      rays[i].direction = Vector3(d[j], d[j + 1], d[j + 2]);
      rays[i].tmin = 0.0;
      rays[i].tmax = max_distance;
    }
    HitColumns chunk = out;
    chunk.hit += start;
    chunk.body += start;
    chunk.triangle += start;
    chunk.distance += start;
    chunk.point += 3 * start;
    chunk.normal += 3 * start;
    s.scene.intersect(std::span<const Ray>(rays, count), &storeHit, &chunk);
  }
  return hits;
}

RayHits nearest(const BoundRayScene& s, const py::handle& points_in, double max_distance) {
  const auto points = toPoints(points_in, "points");
  if (std::isnan(max_distance) || max_distance < 0)
    throw py::value_error("max_distance must be >= 0");
  const auto n = static_cast<std::size_t>(points.shape(0));
  const double* p = points.data();
  for (std::size_t i = 0; i < n; ++i)
    if (!Vector3(p[3 * i], p[3 * i + 1], p[3 * i + 2]).allFinite())
      throw py::value_error(fmt::format("point {}: a coordinate is not a finite number", i));
  RayHits hits(points.shape(0));
  const HitColumns out = columns(hits, s.scene);
  py::gil_scoped_release release;
  std::shared_lock lock(*s.mutex);
  for (std::size_t i = 0; i < n; ++i) {
    const auto found =
        s.scene.nearestSurfacePoint(Vector3(p[3 * i], p[3 * i + 1], p[3 * i + 2]), max_distance);
    if (found)
      out.set(i, found->body, found->triangle, found->point, found->normal, found->distance);
    else
      out.miss(i);
  }
  return hits;
}

// The same rays through the engine's C++ call alone (rays converted beforehand, untimed): the
// baseline bench/python_bench.py compares RayScene.intersect with.
double cppIntersectSeconds(const BoundRayScene& s, const py::handle& origins_in,
                           const py::handle& directions_in) {
  const auto origins = toPoints(origins_in, "origins");
  const auto directions = toPoints(directions_in, "directions");
  std::vector<Ray> rays(static_cast<std::size_t>(origins.shape(0)));
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const double* o = origins.data() + 3 * i;
    const double* d = directions.data() + 3 * i;
    rays[i].origin = Vector3(o[0], o[1], o[2]);
    rays[i].direction = Vector3(d[0], d[1], d[2]);
  }
  std::vector<std::optional<RayHit>> hits(rays.size());
  py::gil_scoped_release release;
  std::shared_lock lock(*s.mutex);
  const auto start = std::chrono::steady_clock::now();
  s.scene.intersect(rays, hits);
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

void bindRays(py::module_& m) {
  py::class_<RayHits>(m, "RayHits",
                      "Answers of one batch, a row per query; rows without one hold hit False, "
                      "body and triangle -1, distance inf, point and normal NaN.")
      .def_readonly("hit", &RayHits::hit, "(N,) bool")
      .def_readonly("body", &RayHits::body, "(N,) index into RayScene.body_names")
      .def_readonly("triangle", &RayHits::triangle, "(N,) index into that body's triangles")
      .def_readonly("distance", &RayHits::distance, "(N,) mm from the origin (query point)")
      .def_readonly("point", &RayHits::point, "(N, 3) world, mm")
      .def_readonly("normal", &RayHits::normal,
                    "(N, 3) the triangle's counter-clockwise unit normal")
      .def("__len__", [](const RayHits& h) { return h.hit.shape(0); });

  py::class_<BoundRayScene>(m, "RayScene",
                            "The world's meshes as they stand, for batches of rays and nearest "
                            "points (Embree). Call update() after the world moves.")
      .def(py::init([](const WorldPtr& world, bool links) {
             RaySceneOptions options;
             if (!links) options.include = [](const BodyRef& b) { return !b.isLink(); };
             BoundRayScene s{world, RayScene(world->world, options), {}};
             for (const BodyRef& ref : s.scene.bodies())
               s.names.push_back(bodyName(world->world, ref));
             return s;
           }),
           py::arg("world"), py::kw_only(), py::arg("links") = true,
           "links=False leaves robot links out (casting at an object in a hand).")
      .def_readonly("body_names", &BoundRayScene::names)
      .def(
          "update",
          [](BoundRayScene& s, const WorldPtr& world) {
            if (world.get() != s.world.get())
              throw py::value_error("update: the scene was built from another world");
            // With the GIL held, so the world does not change meanwhile; queries in flight
            // hold no GIL, so waiting for them here cannot deadlock.
            std::unique_lock lock(*s.mutex);
            s.scene.update(world->world);
          },
          py::arg("world"), "Moves the scene's bodies to where the world has them now.")
      .def("intersect", &intersect, py::arg("origins"), py::arg("directions"),
           py::arg("max_distance") = std::numeric_limits<double>::infinity(),
           "The first hit of each ray: origins and directions (N, 3), mm; directions any "
           "non-zero length.")
      .def("nearest", &nearest, py::arg("points"),
           py::arg("max_distance") = std::numeric_limits<double>::infinity(),
           "The nearest surface point to each of points (N, 3) within max_distance.")
      .def("_cpp_intersect_seconds", &cppIntersectSeconds, py::arg("origins"),
           py::arg("directions"));
}

}  // namespace graspkit::python
