#include "collision/contact_compaction.hpp"

#include <algorithm>
#include <cstdint>
#include <list>
#include <numeric>
#include <optional>

extern "C" {
#include <libqhull_r/qhull_ra.h>
}

#include "collision/working_memory.hpp"
#include "math/qhull_run.hpp"

namespace graspkit::collision {
namespace {

// GraspIt!'s tolerances for grouping contacts by normal and for the perimeter of a group.
constexpr double kNormalTolerance = 1e-3;  // normals agree when n1 . n2 > 1 - this
constexpr double kSamePointSq = 0.1;       // mm^2: points closer than this are one
constexpr double kColinear = 0.1;          // |cross| below this: the points lie on a line

// The indices of the 2-D convex hull's vertices, in qhull's order; nullopt if qhull fails.
std::optional<std::vector<int>> hullVertices2d(std::vector<double>& xy) {
  std::vector<int> vertices;
  const auto failure = detail::runQhull(xy, 2, "n Pp", [&](qhT* qh) {
    vertexT* vertex;
    FORALLvertices {
      vertices.push_back(qh_pointid(qh, vertex->point));
    }
  });
  if (failure) return std::nullopt;
  return vertices;
}

void keepPerimeter(std::vector<RawContact>& group) {
  if (group.size() < 2) return;
  // A line first: walk the points, stretching the segment [end1, end2] to cover them.
  std::size_t end1 = 0, end2 = 1;
  Vector3 line, test;
  std::size_t i = 0;
  for (; i < group.size(); ++i) {
    line = group[end2].onFirst - group[end1].onFirst;
    test = group[i].onFirst - group[end1].onFirst;
    if (test.cross(line).norm() > kColinear) break;
    const double along = test.dot(line);
    if (along < 0) end1 = i;
    if (along > line.squaredNorm()) end2 = i;
  }
  if (i == group.size()) {
    group = {group[end1], group[end2]};
    return;
  }
  // A patch: the 2-D hull in the plane the last two directions span.
  const Vector3 normal = test.cross(line).normalized();
  const Vector3 axis1 = test.normalized();
  const Vector3 axis2 = normal.cross(axis1);
  std::vector<double> xy;
  xy.reserve(2 * group.size());
  for (const RawContact& c : group) {
    xy.push_back(c.onFirst.dot(axis1));
    xy.push_back(c.onFirst.dot(axis2));
  }
  // GraspIt! loses the whole group when qhull fails here; we keep every point instead.
  const auto hull = hullVertices2d(xy);
  if (!hull) return;
  std::vector<RawContact> perimeter;
  for (int index : *hull) perimeter.push_back(group[index]);
  group = std::move(perimeter);
}

}  // namespace

Vector3 RawContact::normal() const {
  const Vector3 gap = onFirst - onSecond;
  const double length = gap.norm();
  return length > 1e-12 ? Vector3(gap / length) : intoFirst;
}

void removeDuplicates(std::vector<RawContact>& contacts, double duplicate_distance) {
  const double limit = duplicate_distance * duplicate_distance;
  auto same = [&](const RawContact& a, const RawContact& b) {
    return (a.onFirst - b.onFirst).squaredNorm() <= limit &&
           (a.onSecond - b.onSecond).squaredNorm() <= limit;
  };
  // GraspIt! lets each contact meet the later ones in its tree's traversal order, the better
  // ranked of a duplicate pair surviving. We apply the same rule free of any order: the best
  // ranked contact stays and removes its duplicates, then the best of the rest, and so on (ties
  // go to the earlier contact). A dense mesh pressed on a face gives tens of thousands of raw
  // contacts and only a handful of survivors, so a pass per survivor costs far less than
  // sorting them all.
  // Both kept by each thread between calls (see findContacts: raw contacts come by the tens of
  // thousands at every step, and fresh memory for them costs page faults).
  thread_local std::vector<std::uint32_t> left_memory;
  thread_local std::vector<RawContact> kept_memory;
  std::vector<std::uint32_t>& left = left_memory;
  std::vector<RawContact>& kept = kept_memory;
  left.resize(contacts.size());
  std::iota(left.begin(), left.end(), 0u);
  kept.clear();
  while (!left.empty()) {
    std::uint32_t best = left.front();
    for (const std::uint32_t index : left)
      if (contacts[index].rank < contacts[best].rank) best = index;
    kept.push_back(contacts[best]);
    std::erase_if(left, [&](std::uint32_t index) {
      return index == best || same(kept.back(), contacts[index]);
    });
  }
  contacts.assign(kept.begin(), kept.end());  // keeps the caller's memory
  keepOrRelease(left);
  keepOrRelease(kept);
}

void compactContacts(std::vector<RawContact>& contacts) {
  if (contacts.size() < 2) return;
  std::vector<std::vector<RawContact>> groups;
  for (const RawContact& c : contacts) {
    const Vector3 n = c.normal();
    auto group = std::find_if(groups.begin(), groups.end(), [&](const auto& g) {
      return g.front().normal().dot(n) > 1.0 - kNormalTolerance;
    });
    if (group == groups.end()) {
      groups.push_back({c});
      continue;
    }
    const bool known = std::any_of(group->begin(), group->end(), [&](const RawContact& other) {
      return (other.onFirst - c.onFirst).squaredNorm() < kSamePointSq;
    });
    if (!known) group->push_back(c);
  }
  contacts.clear();
  for (auto& group : groups) {
    keepPerimeter(group);
    contacts.insert(contacts.end(), group.begin(), group.end());
  }
}

}  // namespace graspkit::collision
