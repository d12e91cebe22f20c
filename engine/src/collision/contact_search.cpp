#include "graspkit/collision/contact_search.hpp"

#include <algorithm>
#include <cmath>

#include "collision/contact_compaction.hpp"
#include "collision/contact_neighbourhood.hpp"
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

// Raw contacts between `query` (moved into the frame of `target` by `query_to_target`) and
// `target`, as point pairs (on query, on target) in the target's frame. Returns whether some
// triangle pairs cross.
bool searchPairs(const raycast::EmbreeMesh& query_surface, const Transform& query_to_target,
                 const raycast::EmbreeMesh& target, double threshold, bool touching_is_contact,
                 std::vector<RawContact>& out, SearchEnd end = SearchEnd::AllPairs) {
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
  for (std::size_t q = 0; q < query.triangles.size(); ++q) {
    if (!query_surface.triangleBox(static_cast<unsigned>(q)).intersects(reach_in_query)) continue;
    const auto& corners = query.triangles[q];
    const Triangle tq = {query_to_target * query.vertices[corners[0]],
                         query_to_target * query.vertices[corners[1]],
                         query_to_target * query.vertices[corners[2]]};
    Eigen::AlignedBox3d box(tq.a);
    box.extend(tq.b).extend(tq.c);
    if (!box.intersects(reach)) continue;
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
    target.forEachTriangleNear(ball.center, ball.radius + threshold, [&](unsigned t) {
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
    });
    // Embree's traversal order is not part of its contract; contacts must not depend on it, so
    // the few candidates that give contacts are put in triangle order (sorting them all would
    // cost more than testing them).
    found.clear();
    runs.clear();
    for (unsigned t : candidates) {
      const Triangle tt = triangleOf(target_mesh, t, target_mesh.vertices);
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

ContactResult findContacts(const World& world, const BodyRef& body1, const BodyRef& body2,
                           const ContactRequest& request) {
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
  result.interpenetrating = searchPairs(*search.query, search.query_to_target, *search.target,
                                        request.threshold, request.touchingIsContact, raw);
  const Transform first_inverse = first_pose.inverse();
  const Transform second_inverse = second_pose.inverse();
  for (RawContact& r : raw) {
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
  collision::removeDuplicates(raw, request.duplicateDistance);
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
