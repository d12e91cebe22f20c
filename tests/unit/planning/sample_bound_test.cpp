// The contact energy's bounds before any query (planning/sample_bound.hpp): checked against the
// nearest point found by brute force over every triangle, and against closed forms on a cube.

#include "planning/sample_bound.hpp"

#include <cmath>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "geometry/closest_point.hpp"
#include "graspkit/math/transform.hpp"

namespace graspkit::planning {
namespace {

// The cube [-h, h]^3 as twelve triangles.
TriangleMesh cube(double h) {
  TriangleMesh mesh;
  for (int i = 0; i < 8; ++i)
    mesh.vertices.emplace_back(i & 1 ? h : -h, i & 2 ? h : -h, i & 4 ? h : -h);
  const std::uint32_t faces[12][3] = {{0, 1, 3}, {0, 3, 2}, {4, 6, 7}, {4, 7, 5},
                                      {0, 4, 5}, {0, 5, 1}, {2, 3, 7}, {2, 7, 6},
                                      {0, 2, 6}, {0, 6, 4}, {1, 5, 7}, {1, 7, 3}};
  for (const auto& f : faces) mesh.triangles.push_back({f[0], f[1], f[2]});
  return mesh;
}

// The true sample: the nearest surface point over every triangle, in the world.
SampleBound trueSample(const TriangleMesh& mesh, const Transform& pose, const Vector3& point,
                       const Vector3& normal) {
  double best = std::numeric_limits<double>::infinity();
  Vector3 nearest = Vector3::Zero();
  for (const auto& t : mesh.triangles) {
    const Vector3 q =
        pose * geometry::closestPointOnTriangle(pose.inverse() * point, mesh.vertices[t[0]],
                                                mesh.vertices[t[1]], mesh.vertices[t[2]]);
    if ((q - point).norm() < best) {
      best = (q - point).norm();
      nearest = q;
    }
  }
  return {best, best > 0 ? normal.dot(nearest - point) / best : 1.0};
}

TEST(SampleBound, NeverCutsOffTheTrueSampleOfARandomSurface) {
  std::mt19937_64 random(3);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int bounded = 0, facing = 0;
  for (int object = 0; object < 20; ++object) {
    // A triangle soup in a long box, turned and moved: the box and the ball differ.
    TriangleMesh mesh;
    for (int v = 0; v < 60; ++v)
      mesh.vertices.emplace_back(80 * unit(random), 20 * unit(random), 35 * unit(random));
    for (std::uint32_t t = 0; t + 2 < 60; t += 3) mesh.triangles.push_back({t, t + 1, t + 2});
    const Transform pose = makeTransform(
        Vector3(100 * unit(random), 100 * unit(random), 100 * unit(random)),
        Eigen::Quaterniond(unit(random), unit(random), unit(random), unit(random)).normalized());
    const ObjectBounds bounds = objectBounds(mesh, pose);
    for (int k = 0; k < 500; ++k) {
      const Vector3 point =
          pose * Vector3(300 * unit(random), 300 * unit(random), 300 * unit(random));
      const Vector3 normal = Vector3(unit(random), unit(random), unit(random)).normalized();
      const SampleBound bound = sampleBound(bounds, point, normal);
      const SampleBound truth = trueSample(mesh, pose, point, normal);
      ASSERT_LE(bound.distance, truth.distance) << object << " " << k;
      ASSERT_GE(bound.cosine, truth.cosine) << object << " " << k;
      bounded += bound.distance > 0;
      facing += bound.cosine < 0;
    }
  }
  // The bounds say something: most points lie outside the ball, and many face away.
  EXPECT_GT(bounded, 5000);
  EXPECT_GT(facing, 2000);
}

TEST(SampleBound, MatchesTheClosedFormsOfACube) {
  const double h = 10.0, r = h * std::sqrt(3.0);
  const Transform pose = makeTransform(
      Vector3(5, -7, 3), Eigen::Quaterniond(Eigen::AngleAxisd(0.4, Vector3::UnitY())));
  const ObjectBounds bounds = objectBounds(cube(h), pose);
  EXPECT_NEAR(bounds.ballRadius, r, 1e-12);
  // On the cube's x axis at D from its centre, the box's distance is the true one, D - h.
  const double D = 50.0;
  const Vector3 axis = pose.linear() * Vector3::UnitX();
  const Vector3 point = pose * Vector3(D, 0, 0);
  const SampleBound toward = sampleBound(bounds, point, -axis);
  EXPECT_NEAR(toward.distance, D - h, 1e-6);
  EXPECT_DOUBLE_EQ(toward.cosine, 1.0);  // facing the centre: the cone holds the normal
  // Facing straight away: the cone of half-angle asin(r / D) allows at most -cos(that angle).
  const SampleBound away = sampleBound(bounds, point, axis);
  EXPECT_NEAR(away.cosine, -std::sqrt(1.0 - r * r / (D * D)), 1e-8);
  // Within the ball nothing is bounded.
  const SampleBound inside = sampleBound(bounds, pose * Vector3(h, h, 0), axis);
  EXPECT_EQ(inside.distance, 0.0);
  EXPECT_EQ(inside.cosine, 1.0);
  // A mesh without triangles bounds nothing (its samples are 0).
  TriangleMesh points = cube(h);
  points.triangles.clear();
  EXPECT_EQ(sampleBound(objectBounds(points, pose), point, axis).distance, 0.0);
}

}  // namespace
}  // namespace graspkit::planning
