#include "graspkit/collision/contact_search.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>

#include "collision/contact_compaction.hpp"
#include "collision/contact_neighbourhood.hpp"
#include "collision/contact_search_stages.hpp"
#include "collision/distinct_point_pairs.hpp"
#include "collision/triangle_contact.hpp"
#include "collision/working_memory.hpp"
#include "graspkit/collision/contact_patch.hpp"
#include "graspkit/model/material.hpp"
#include "graspkit/model/world.hpp"
#include "raycast/embree_mesh.hpp"

namespace graspkit {
namespace {

using collision::Neighbourhood;
using collision::PatchCandidate;
using collision::PointPair;
using collision::RawContact;
using collision::Triangle;

Triangle triangleOf(const TriangleMesh& mesh, std::size_t index,
                    const std::vector<Vector3>& vertices) {
  const auto& t = mesh.triangles[index];
  return {vertices[t[0]], vertices[t[1]], vertices[t[2]]};
}

// Triangle `index` of `mesh` moved by `transform`.
Triangle movedTriangle(const TriangleMesh& mesh, std::size_t index, const Transform& transform) {
  const auto& t = mesh.triangles[index];
  return {transform * mesh.vertices[t[0]], transform * mesh.vertices[t[1]],
          transform * mesh.vertices[t[2]]};
}

Eigen::AlignedBox3d boxOf(const Triangle& t) {
  Eigen::AlignedBox3d box(t.a);
  box.extend(t.b).extend(t.c);
  return box;
}

// Bounds of a mesh's local box seen from another frame.
Eigen::AlignedBox3d transformedBox(const Eigen::AlignedBox3d& box, const Transform& transform) {
  Eigen::AlignedBox3d out;
  for (int corner = 0; corner < 8; ++corner)
    out.extend(transform * box.corner(static_cast<Eigen::AlignedBox3d::CornerType>(corner)));
  return out;
}

// The smallest ball holding a triangle: the longest edge's when the triangle is right- or
// obtuse-angled, else the circumscribed one. A link's triangles are often far larger than the
// object's, and the Embree search around one visits every object triangle in its ball, so a ball
// tighter than the bounding box's saves much of that search.
struct Ball {
  Vector3 center;
  double radius;
};

Ball enclosingBall(const Triangle& t) {
  const Vector3 ab = t.b - t.a, bc = t.c - t.b, ca = t.a - t.c;
  const double ab2 = ab.squaredNorm(), bc2 = bc.squaredNorm(), ca2 = ca.squaredNorm();
  Vector3 center;
  if (ab2 >= bc2 + ca2) {
    center = 0.5 * (t.a + t.b);
  } else if (bc2 >= ab2 + ca2) {
    center = 0.5 * (t.b + t.c);
  } else if (ca2 >= ab2 + bc2) {
    center = 0.5 * (t.c + t.a);
  } else {  // acute, so |ab x ac| > 0
    const Vector3 ac = -ca;
    const Vector3 n = ab.cross(ac);
    center = t.a + (ab2 * ac - ca2 * ab).cross(n) / (2.0 * n.squaredNorm());
  }
  // Measured rather than taken from the formula, so that rounding cannot leave a vertex out.
  const double radius = std::sqrt(std::max(
      {(t.a - center).squaredNorm(), (t.b - center).squaredNorm(), (t.c - center).squaredNorm()}));
  return {center, radius};
}

// Where a search may stop: after every triangle, once a query triangle has given a contact, or
// at the first contact or crossing pair (the question "closer than the threshold?").
enum class SearchEnd { AllPairs, FirstContact, FirstContactOrCrossing };

// The raw contacts one target triangle gave one query triangle: found[begin, end).
struct FoundRun {
  unsigned triangle;
  std::size_t begin;
  std::size_t end;
};

// The second stage of a search in two stages (ContactRequest::firstStageThreshold): the first
// stage's surviving contacts, as points on the query and on the target in the target's frame.
// Every contact the second stage could add ranks after them (it is farther apart), so one that
// lies within the duplicate distance of a survivor on both bodies is removed by it whatever
// else is found: a triangle pair all of whose contacts would be is not searched.
class SurvivorCover {
 public:
  SurvivorCover(double duplicate_distance, double threshold)
      // Less a margin for the rounding of the frames the survivors passed through, and for the
      // touching points moved onto each other (kTouchingTolerance).
      : reach_(duplicate_distance - 1e-4), threshold_(threshold) {}

  void add(const Vector3& on_query, const Vector3& on_target) {
    survivors_.push_back({on_query, on_target});
  }

  // Every contact of the query triangle: its point on the triangle, and the target's within the
  // threshold of the triangle.
  bool coversQuery(const Triangle& query) const {
    return covers(query, reach_, query, reach_ - threshold_);
  }

  bool coversPair(const Triangle& query, const Triangle& target) const {
    return covers(query, reach_, target, reach_);
  }

 private:
  static bool within(const Triangle& t, const Vector3& p, double r_sq) {
    return (t.a - p).squaredNorm() <= r_sq && (t.b - p).squaredNorm() <= r_sq &&
           (t.c - p).squaredNorm() <= r_sq;
  }

  // Some survivor's ball of radius rq holds `query`, and its ball of radius rt holds `target`
  // (a ball holds a triangle when it holds its corners). The last one that did is tried first:
  // triangles come in order over the surface.
  bool covers(const Triangle& query, double rq, const Triangle& target, double rt) const {
    if (rq <= 0.0 || rt <= 0.0) return false;
    const double rq_sq = rq * rq, rt_sq = rt * rt;
    const std::size_t n = survivors_.size();
    for (std::size_t k = 0; k < n; ++k) {
      const std::size_t i = (last_ + k) % n;
      if (within(query, survivors_[i].first, rq_sq) &&
          within(target, survivors_[i].second, rt_sq)) {
        last_ = i;
        return true;
      }
    }
    return false;
  }

  std::vector<std::pair<Vector3, Vector3>> survivors_;
  double reach_;
  double threshold_;
  mutable std::size_t last_ = 0;
};

// Which pairs of meshes to search in two stages. The second stage pays only where many raw
// contacts crowd behind each survivor (dense meshes face to face); elsewhere the first stage is
// a search made twice. Whether a pair was dense at its last search on this thread says: the
// simulation searches the same pairs step after step. The contacts do not depend on it.
class DenseMemory {
 public:
  using Key = std::pair<const void*, const void*>;  // the query's and the target's geometry
  // Raw contacts that make a pair dense: over the whole threshold in one search (the 2F-85's
  // fingers closed on each other gave 400,000; a finger on an object, hundreds to thousands),
  // and within the first stage's.
  static constexpr std::size_t kDenseOneStage = 20000;
  static constexpr std::size_t kDenseFirstStage = 2000;

  static bool dense(const Key& key) {
    const auto found = pairs().find(key);
    return found != pairs().end() && found->second;
  }

  static void remember(const Key& key, bool dense) {
    auto& known = pairs();
    if (known.size() > 4096) known.clear();  // geometry comes and goes; a hint is only a hint
    known[key] = dense;
  }

 private:
  static std::map<Key, bool>& pairs() {
    thread_local std::map<Key, bool> known;
    return known;
  }
};

// A query triangle and a target triangle that may come within the threshold of each other.
struct NearPair {
  unsigned query;
  unsigned target;
};

std::vector<NearPair>& nearPairsMemory() {
  thread_local std::vector<NearPair> pairs;
  return pairs;
}

// The tests' choice of where candidates come from (collision::setCandidatesFromTarget).
std::optional<bool>& candidatesFromTarget() {
  thread_local std::optional<bool> chosen;
  return chosen;
}

// Whether to find each query triangle's near target triangles from the target's side. Embree
// finds the target triangles around a ball holding the query triangle; when the query's
// triangles are much larger than the target's (a hand link's against a mug's), that ball holds
// dozens of target triangles that the query triangle's box then sifts out. Each target triangle
// asking for the query triangles around its own, smaller, ball visits fewer. Only where the
// candidates come from changes: each query triangle still meets every target triangle within
// the threshold, in the same order, so the contacts are the same.
bool nearFromTarget(const raycast::EmbreeMesh& query, const raycast::EmbreeMesh& target) {
  return candidatesFromTarget().value_or(query.meanTriangleSize() >
                                         2.0 * target.meanTriangleSize());
}

// The pairs of query and target triangles whose balls (each triangle's smallest, grown by the
// threshold on one side) meet, in nearPairsMemory() in order of query, then target triangle.
// Every pair of triangles within the threshold of each other is among them: the target
// triangle lies in its ball, and the query triangle then within the threshold of that ball.
void pairsNearFromTarget(const raycast::EmbreeMesh& query, const Transform& query_to_target,
                         const raycast::EmbreeMesh& target, double threshold) {
  std::vector<NearPair>& pairs = nearPairsMemory();
  pairs.clear();
  // Each query triangle's box in the target's frame, grown by the threshold, as the search
  // computes it: a pair whose boxes miss each other is sifted out here rather than sorted.
  const TriangleMesh& query_mesh = query.mesh();
  thread_local std::vector<Vector3> moved_memory;
  thread_local std::vector<Eigen::AlignedBox3d> query_boxes_memory;
  std::vector<Vector3>& moved = moved_memory;
  std::vector<Eigen::AlignedBox3d>& query_boxes = query_boxes_memory;
  moved.resize(query_mesh.vertices.size());
  for (std::size_t v = 0; v < moved.size(); ++v)
    moved[v] = query_to_target * query_mesh.vertices[v];
  query_boxes.resize(query_mesh.triangles.size());
  for (std::size_t q = 0; q < query_boxes.size(); ++q) {
    const auto& corners = query_mesh.triangles[q];
    Eigen::AlignedBox3d box(moved[corners[0]]);
    box.extend(moved[corners[1]]).extend(moved[corners[2]]);
    box.min().array() -= threshold;
    box.max().array() += threshold;
    query_boxes[q] = box;
  }
  const TriangleMesh& target_mesh = target.mesh();
  const Transform target_to_query = query_to_target.inverse();
  // Embree finds the target triangles near a ball holding the query's box grown by the
  // threshold (so a dense scan costs what its part near the query costs, not its size); the
  // box itself, seen from the query's frame, passes over the rest.
  Eigen::AlignedBox3d reach = query.bounds();
  reach.min().array() -= threshold;
  reach.max().array() += threshold;
  thread_local std::vector<unsigned> near_target_memory;
  std::vector<unsigned>& near_target = near_target_memory;
  near_target.clear();
  target.forEachTriangleNear(query_to_target * reach.center(), 0.5 * reach.diagonal().norm(),
                             [&](unsigned t) { near_target.push_back(t); });
  for (const unsigned t : near_target) {
    const Triangle moved_target = movedTriangle(target_mesh, t, target_to_query);
    if (!boxOf(moved_target).intersects(reach)) continue;
    const Ball ball = enclosingBall(moved_target);
    const Eigen::AlignedBox3d& target_box = target.triangleBox(t);
    query.forEachTriangleNear(ball.center, ball.radius + threshold, [&](unsigned q) {
      if (query_boxes[q].intersects(target_box)) pairs.push_back({q, t});
    });
  }
  std::sort(pairs.begin(), pairs.end(), [](const NearPair& a, const NearPair& b) {
    return a.query != b.query ? a.query < b.query : a.target < b.target;
  });
}

// Raw contacts between `query` (moved into the frame of `target` by `query_to_target`) and
// `target`, as point pairs (on query, on target) in the target's frame. Returns whether some
// triangle pairs cross.
bool searchPairs(const raycast::EmbreeMesh& query_surface, const Transform& query_to_target,
                 const raycast::EmbreeMesh& target, double threshold, bool touching_is_contact,
                 std::vector<RawContact>& out, SearchEnd end = SearchEnd::AllPairs,
                 const SurvivorCover* cover = nullptr) {
  // A search that stops at its first contact would pay for every pair up front.
  const bool from_target = end == SearchEnd::AllPairs && nearFromTarget(query_surface, target);
  if (from_target) pairsNearFromTarget(query_surface, query_to_target, target, threshold);
  const TriangleMesh& query = query_surface.mesh();
  const TriangleMesh& target_mesh = target.mesh();
  Eigen::AlignedBox3d reach = target.bounds();
  reach.min().array() -= threshold;
  reach.max().array() += threshold;
  // The same reach seen from the query's frame (a box around the turned box, so larger): a
  // query triangle whose own box, kept with its mesh, misses it cannot come near the target,
  // and is passed over without moving its corners. A dense link mesh against an object has
  // tens of thousands of triangles and only a few near it.
  // Grown by a micrometre, far above the rounding of either transform: the exact test below
  // still decides, this one only passes over triangles.
  Eigen::AlignedBox3d reach_in_query = transformedBox(reach, query_to_target.inverse());
  reach_in_query.min().array() -= 1e-3;
  reach_in_query.max().array() += 1e-3;

  // Working memory kept by each thread between searches (allocating it afresh for each search
  // of a simulation step cost page faults); bound once, as each use of a thread_local in a
  // shared library is a call.
  thread_local std::vector<unsigned> candidates_memory;
  thread_local std::vector<PointPair> pairs_memory;
  thread_local std::vector<RawContact> found_memory;
  thread_local std::vector<FoundRun> runs_memory;
  std::vector<unsigned>& candidates = candidates_memory;
  std::vector<PointPair>& pairs = pairs_memory;
  std::vector<RawContact>& found = found_memory;
  std::vector<FoundRun>& runs = runs_memory;
  thread_local collision::DistinctPointPairs distinct_memory;
  collision::DistinctPointPairs& distinct = distinct_memory;
  distinct.start(out);

  bool intersecting = false;
  const double threshold_sq = threshold * threshold;
  const std::vector<NearPair>& near_pairs = nearPairsMemory();
  std::size_t pair_begin = 0, pair_end = 0;  // near_pairs of the query triangle q
  for (std::size_t q = 0; q < query.triangles.size(); ++q) {
    if (from_target) {  // on to the next query triangle that some target triangle found
      if (pair_end == near_pairs.size()) break;
      pair_begin = pair_end;
      q = near_pairs[pair_begin].query;
      while (pair_end < near_pairs.size() && near_pairs[pair_end].query == q) ++pair_end;
    }
    if (!query_surface.triangleBox(static_cast<unsigned>(q)).intersects(reach_in_query)) continue;
    const Triangle tq = movedTriangle(query, q, query_to_target);
    Eigen::AlignedBox3d box = boxOf(tq);
    if (!box.intersects(reach)) continue;
    if (cover && cover->coversQuery(tq)) continue;
    const Ball ball = enclosingBall(tq);
    // The query triangle's plane, unit normal: a target triangle whose box lies wholly beyond
    // the threshold on one side of it can neither touch nor cross the query triangle.
    Vector3 normal = (tq.b - tq.a).cross(tq.c - tq.a);
    const double normal_norm = normal.norm();
    const bool has_plane = normal_norm > 0.0;
    if (has_plane) normal /= normal_norm;
    const double plane_offset = normal.dot(tq.a);
    const Vector3 abs_normal = normal.cwiseAbs();
    box.min().array() -= threshold;
    box.max().array() += threshold;
    // Embree finds the triangles near the query's bounding sphere; their boxes sift them.
    candidates.clear();
    auto sift = [&](unsigned t) {
      const Eigen::AlignedBox3d& near_box = target.triangleBox(t);
      if (!box.intersects(near_box)) return;
      if (has_plane) {
        const double from_plane = normal.dot(near_box.center()) - plane_offset;
        const double half_depth = 0.5 * abs_normal.dot(near_box.sizes());
        // The margin covers the rounding of these sums (mm-sized, far above 1e-9 of them).
        if (std::abs(from_plane) > half_depth + threshold + 1e-9 * (1.0 + std::abs(plane_offset)))
          return;
      }
      candidates.push_back(t);
    };
    if (from_target) {
      for (std::size_t i = pair_begin; i < pair_end; ++i) sift(near_pairs[i].target);
    } else {
      target.forEachTriangleNear(ball.center, ball.radius + threshold,
                                 [&](unsigned t) { sift(t); });
    }
    // Embree's traversal order is not part of its contract; contacts must not depend on it, so
    // the few candidates that give contacts are put in triangle order (sorting them all would
    // cost more than testing them).
    found.clear();
    runs.clear();
    for (unsigned t : candidates) {
      const Triangle tt = triangleOf(target_mesh, t, target_mesh.vertices);
      if (cover && cover->coversPair(tq, tt)) continue;
      pairs.clear();
      if (!collision::triangleContacts(tq, tt, threshold_sq, pairs, touching_is_contact)) {
        intersecting = true;
        if (end == SearchEnd::FirstContactOrCrossing) return true;
        continue;
      }
      if (pairs.empty()) continue;
      const Vector3 face = (tt.b - tt.a).cross(tt.c - tt.a).normalized();
      const std::size_t begin = found.size();
      for (const PointPair& p : pairs) found.push_back({p.onFirst, p.onSecond, face});
      runs.push_back({t, begin, found.size()});
    }
    // The runs are sorted, not the contacts: a triangle's own point pairs keep the order
    // triangleContacts gave them, and two dense meshes face to face give hundreds per triangle.
    std::sort(runs.begin(), runs.end(), [](const FoundRun& a, const FoundRun& b) {
      return a.triangle != b.triangle ? a.triangle < b.triangle : a.begin < b.begin;
    });
    for (const FoundRun& run : runs)
      for (std::size_t i = run.begin; i < run.end; ++i)
        if (distinct.admit(out, found[i])) out.push_back(found[i]);
    if (end != SearchEnd::AllPairs && !out.empty()) break;
  }
  distinct.keepOrReleaseMemory();
  collision::keepOrRelease(found);
  return intersecting;
}

// The normal into the first body. Touching points give no direction; the face of the second
// body then says where the first is.
Vector3 normalOf(const RawContact& raw) {
  const Vector3 gap = raw.onFirst - raw.onSecond;
  const double distance = gap.norm();
  return distance > 1e-12 ? Vector3(gap / distance) : raw.intoFirst;
}

// What the soft-finger patch of a contact gives it: relative radii and e_tau, mm.
struct SoftPatch {
  RelativeRadii radii;
  double torsion = 0.0;
};

// One body's side of a contact: its surface around the point (body frame) fitted in GraspIt!'s
// contact frame, which it builds from the normal in the body's own frame. The first principal
// direction is returned in the world.
PrincipalRadii fitSide(const Neighbourhood& points, const Vector3& point, const Vector3& inward,
                       const Transform& pose, Vector3& direction) {
  const Matrix3 frame = contactFrame(inward);
  std::vector<Vector3> in_frame;
  in_frame.reserve(points.size());
  for (const Vector3& p : points) in_frame.push_back(frame.transpose() * (p - point));
  const PrincipalRadii radii = principalRadii(fitParaboloid(in_frame));
  direction = pose.linear() * (frame * radii.direction);
  return radii;
}

// GraspIt!'s soft contacts between an elastic body and another: each contact's neighbourhood
// on both bodies; contacts sharing a patch on the first body merge into the nearest; each
// survivor's two patches give its relative radii and, under GraspIt!'s static normal force,
// its e_tau. Removes the merged contacts from `raw` and returns one patch per survivor.
std::vector<SoftPatch> softPatches(std::vector<RawContact>& raw, const BodyModel& first,
                                   const Transform& first_pose, const BodyModel& second,
                                   const Transform& second_pose) {
  const double youngs = std::max(first.youngs.value_or(-1.0), second.youngs.value_or(-1.0));
  const double radius = patchNeighbourhoodRadius(youngs);
  const auto first_surface = raycast::embreeMesh(first.mesh);
  const auto second_surface = raycast::embreeMesh(second.mesh);
  const Transform first_inverse = first_pose.inverse();
  const Transform second_inverse = second_pose.inverse();

  std::vector<PatchCandidate> candidates;
  candidates.reserve(raw.size());
  for (std::size_t i = 0; i < raw.size(); ++i) {
    const Vector3 normal = normalOf(raw[i]);
    candidates.push_back(
        {i, std::sqrt(raw[i].distanceSq()),
         collision::surfaceNeighbourhood(*first_surface, first_inverse * raw[i].onFirst,
                                         first_inverse.linear() * normal, radius),
         collision::surfaceNeighbourhood(*second_surface, second_inverse * raw[i].onSecond,
                                         -(second_inverse.linear() * normal), radius)});
  }
  collision::mergeOverlappingPatches(candidates);

  std::vector<RawContact> survivors;
  std::vector<SoftPatch> patches;
  for (const PatchCandidate& candidate : candidates) {
    const RawContact& r = raw[candidate.contact];
    const Vector3 normal = normalOf(r);
    Vector3 direction1, direction2;
    const PrincipalRadii side1 = fitSide(candidate.onFirst, first_inverse * r.onFirst,
                                         first_inverse.linear() * normal, first_pose, direction1);
    const PrincipalRadii side2 =
        fitSide(candidate.onSecond, second_inverse * r.onSecond,
                -(second_inverse.linear() * normal), second_pose, direction2);
    const double angle = std::acos(std::clamp(direction1.dot(direction2), -1.0, 1.0));
    SoftPatch patch;
    patch.radii = relativeRadii(side1, side2, angle);
    patch.torsion = mattressEllipse(patch.radii, youngs, kStaticNormalForce).torsion;
    survivors.push_back(r);
    patches.push_back(patch);
  }
  raw = std::move(survivors);
  return patches;
}

Contact makeContact(const BodyRef& body1, const BodyRef& body2, const RawContact& raw,
                    const BodyModel& model1, const BodyModel& model2, const SoftPatch* patch) {
  Contact contact;
  contact.body1 = body1;
  contact.body2 = body2;
  contact.position1 = raw.onFirst;
  contact.position2 = raw.onSecond;
  contact.distance = std::sqrt(raw.distanceSq());
  contact.normal = normalOf(raw);
  contact.frame = contactFrame(contact.normal);
  contact.mu = staticFriction(model1.material, model2.material);
  if (contact.mu <= 0.0) {
    contact.model = ContactModel::Frictionless;
  } else if (patch) {
    contact.model = ContactModel::SoftFinger;
    contact.torsion = patch->torsion;
    contact.patchRadius1 = patch->radii.r1 > 0.0 ? patch->radii.r1 : kFlatRelativeRadius;
    contact.patchRadius2 = patch->radii.r2 > 0.0 ? patch->radii.r2 : kFlatRelativeRadius;
  } else {
    contact.model = ContactModel::PointWithFriction;
  }
  return contact;
}

}  // namespace

namespace {

// How a pair of bodies is searched. GraspIt! works on each pair in a fixed order (its first body
// is the one loaded first); the clean-up of contacts depends on it, so the search works in that
// order and findContacts turns the result round at the end.
struct PairSearch {
  bool flip = false;
  BodyRef first, second;
  const BodyModel* first_model = nullptr;
  const BodyModel* second_model = nullptr;
  Transform first_pose, second_pose;
  // Walk the smaller mesh's triangles and search the larger one's Embree geometry, unless the
  // smaller one's triangles are much larger (a table's few against a glass's many): a search
  // around a large triangle visits everything within its bounding sphere.
  bool walk_second = false;
  std::shared_ptr<const raycast::EmbreeMesh> query;
  std::shared_ptr<const raycast::EmbreeMesh> target;
  Transform target_pose, query_to_target;
  bool reachable = false;  // the boxes come within the threshold

  PairSearch(const World& world, const BodyRef& body1, const BodyRef& body2, double threshold) {
    const BodyModel& model1 = bodyModel(world, body1);
    const BodyModel& model2 = bodyModel(world, body2);
    if (!model1.mesh || !model2.mesh || model1.mesh->empty() || model2.mesh->empty()) return;
    flip = body2 < body1;
    first = flip ? body2 : body1;
    second = flip ? body1 : body2;
    first_model = flip ? &model2 : &model1;
    second_model = flip ? &model1 : &model2;
    first_pose = bodyPose(world, first);
    second_pose = bodyPose(world, second);
    const auto first_embree = raycast::embreeMesh(first_model->mesh);
    const auto second_embree = raycast::embreeMesh(second_model->mesh);
    walk_second = first_model->mesh->triangleCount() > second_model->mesh->triangleCount();
    const double first_size = first_embree->meanTriangleSize();
    const double second_size = second_embree->meanTriangleSize();
    if (walk_second ? second_size > 4.0 * first_size : first_size > 4.0 * second_size)
      walk_second = !walk_second;
    query = walk_second ? second_embree : first_embree;
    target = walk_second ? first_embree : second_embree;
    const Transform& query_pose = walk_second ? second_pose : first_pose;
    target_pose = walk_second ? first_pose : second_pose;
    query_to_target = target_pose.inverse() * query_pose;
    Eigen::AlignedBox3d reach = target->bounds();
    reach.min().array() -= threshold;
    reach.max().array() += threshold;
    const Eigen::AlignedBox3d& query_box = query->bounds();
    reachable = transformedBox(query_box, query_to_target).intersects(reach);
  }
};

}  // namespace

bool inContact(const World& world, const BodyRef& body1, const BodyRef& body2,
               const ContactRequest& request) {
  const PairSearch search(world, body1, body2, request.threshold);
  if (!search.reachable) return false;
  std::vector<RawContact> raw;
  searchPairs(*search.query, search.query_to_target, *search.target, request.threshold,
              request.touchingIsContact, raw, SearchEnd::FirstContact);
  return !raw.empty();
}

bool surfacesWithin(const World& world, const BodyRef& body1, const BodyRef& body2,
                    double distance) {
  const PairSearch search(world, body1, body2, distance);
  if (!search.reachable) return false;
  std::vector<RawContact> raw;
  const bool crossing = searchPairs(*search.query, search.query_to_target, *search.target, distance,
                                    false, raw, SearchEnd::FirstContactOrCrossing);
  return crossing || !raw.empty();
}

void collision::setCandidatesFromTarget(std::optional<bool> from_target) {
  candidatesFromTarget() = from_target;
}

ContactResult findContacts(const World& world, const BodyRef& body1, const BodyRef& body2,
                           const ContactRequest& request) {
  return collision::findContactsInStages(world, body1, body2, request, std::nullopt);
}

ContactResult collision::findContactsInStages(const World& world, const BodyRef& body1,
                                              const BodyRef& body2, const ContactRequest& request,
                                              std::optional<bool> two_stages) {
  ContactResult result;
  const PairSearch search(world, body1, body2, request.threshold);
  if (!search.reachable) return result;
  const BodyModel& first_model = *search.first_model;
  const BodyModel& second_model = *search.second_model;
  const Transform& first_pose = search.first_pose;
  const Transform& second_pose = search.second_pose;
  const Transform& target_pose = search.target_pose;
  const bool walk_second = search.walk_second;

  // Kept by each thread between searches, as searchPairs' own working memory is: a gripper pad
  // pressed flat on a face gives tens of thousands of raw contacts at every simulation step,
  // and growing them afresh each time cost more in page faults than finding them.
  thread_local std::vector<RawContact> raw_memory;
  std::vector<RawContact>& raw = raw_memory;
  raw.clear();
  const Transform first_inverse = first_pose.inverse();
  const Transform second_inverse = second_pose.inverse();
  // Raw contacts from the target's frame to the world, each body's point on its own side, and
  // ranked.
  const auto toWorld = [&](std::vector<RawContact>& contacts) {
    for (RawContact& r : contacts) {
      r.onFirst = target_pose * r.onFirst;
      r.onSecond = target_pose * r.onSecond;
      r.intoFirst = target_pose.linear() * r.intoFirst;
      // Touching points give no direction of their own (their gap is rounding): they take the
      // face's normal, as points at distance 0 do.
      if (request.touchingIsContact &&
          r.distanceSq() < collision::kTouchingTolerance * collision::kTouchingTolerance)
        r.onSecond = r.onFirst;
      if (walk_second) {
        std::swap(r.onFirst, r.onSecond);
        r.intoFirst = -r.intoFirst;  // the face was the first body's, pointing out of it
      }
      // GraspIt! ranks duplicates by the distance between the two points each expressed in its
      // own body's frame (not a physical distance); its choice of survivors follows from that.
      r.rank = request.graspitDuplicates
                   ? (first_inverse * r.onFirst - second_inverse * r.onSecond).squaredNorm()
                   : r.distanceSq();
    }
  };
  const double first_stage = request.firstStageThreshold;
  const bool may_stage =
      !request.graspitDuplicates && first_stage > 0.0 && request.threshold > 2.0 * first_stage;
  DenseMemory::Key key{search.query.get(), search.target.get()};
  if (!may_stage || !two_stages.value_or(DenseMemory::dense(key))) {
    result.interpenetrating = searchPairs(*search.query, search.query_to_target, *search.target,
                                          request.threshold, request.touchingIsContact, raw);
    if (may_stage) DenseMemory::remember(key, raw.size() >= DenseMemory::kDenseOneStage);
    toWorld(raw);
    collision::removeDuplicates(raw, request.duplicateDistance);
  } else {
    // Duplicates are removed closest first, so the contacts within the first stage's threshold
    // meet each other before any farther one: their survivors are the first survivors of the
    // whole search. Only contacts ranked surely below that threshold (not where the rounding of
    // the frames could put one either side of it) are taken from the first stage.
    result.interpenetrating = searchPairs(*search.query, search.query_to_target, *search.target,
                                          first_stage, request.touchingIsContact, raw);
    DenseMemory::remember(key, raw.size() >= DenseMemory::kDenseFirstStage);
    toWorld(raw);
    const double bound = first_stage * first_stage * (1.0 - 1e-6);
    std::erase_if(raw, [&](const RawContact& r) { return !(r.rank <= bound); });
    collision::removeDuplicates(raw, request.duplicateDistance);
    SurvivorCover cover(request.duplicateDistance, request.threshold);
    const Transform to_target = target_pose.inverse();
    for (const RawContact& r : raw) {
      const Vector3& on_query = walk_second ? r.onSecond : r.onFirst;
      const Vector3& on_target = walk_second ? r.onFirst : r.onSecond;
      cover.add(to_target * on_query, to_target * on_target);
    }
    thread_local std::vector<RawContact> more_memory;
    std::vector<RawContact>& more = more_memory;
    more.clear();
    searchPairs(*search.query, search.query_to_target, *search.target, request.threshold,
                request.touchingIsContact, more, SearchEnd::AllPairs, &cover);
    toWorld(more);
    std::erase_if(more, [&](const RawContact& r) { return r.rank <= bound; });
    // The survivors first, in the order they survived, then the rest: the survivors stay and
    // the rest meet them before each other, as in one search.
    raw.insert(raw.end(), more.begin(), more.end());
    collision::keepOrRelease(more);
    collision::removeDuplicates(raw, request.duplicateDistance);
  }
  if (request.compact) collision::compactContacts(raw);
  std::vector<SoftPatch> patches;
  if (request.softContacts && (first_model.isElastic() || second_model.isElastic()))
    patches = softPatches(raw, first_model, first_pose, second_model, second_pose);
  result.contacts.reserve(raw.size());
  for (std::size_t i = 0; i < raw.size(); ++i) {
    const SoftPatch* patch = patches.empty() ? nullptr : &patches[i];
    Contact c = makeContact(search.first, search.second, raw[i], first_model, second_model, patch);
    result.contacts.push_back(search.flip ? c.mate() : c);
  }
  collision::keepOrRelease(raw);
  return result;
}

}  // namespace graspkit
