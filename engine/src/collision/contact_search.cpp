#include "graspkit/contact_search.hpp"

#include <algorithm>

#include "collision/contact_compaction.hpp"
#include "collision/triangle_contact.hpp"
#include "graspkit/material.hpp"
#include "graspkit/world.hpp"
#include "raycast/embree_mesh.hpp"

namespace graspkit {
namespace {

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

// Raw contacts between `query` (moved into the frame of `target` by `query_to_target`) and
// `target`, as point pairs (on query, on target) in the target's frame.
bool searchPairs(const TriangleMesh& query, const Transform& query_to_target,
                 const raycast::EmbreeMesh& target, double threshold,
                 std::vector<RawContact>& out) {
  const TriangleMesh& target_mesh = target.mesh();
  Eigen::AlignedBox3d reach = target.bounds();
  reach.min().array() -= threshold;
  reach.max().array() += threshold;

  std::vector<Vector3> moved(query.vertices.size());
  for (std::size_t i = 0; i < moved.size(); ++i) moved[i] = query_to_target * query.vertices[i];

  bool intersecting = false;
  std::vector<unsigned> candidates;
  std::vector<PointPair> pairs;
  const double threshold_sq = threshold * threshold;
  for (std::size_t q = 0; q < query.triangles.size(); ++q) {
    const Triangle tq = triangleOf(query, q, moved);
    Eigen::AlignedBox3d box(tq.a);
    box.extend(tq.b).extend(tq.c);
    if (!box.intersects(reach)) continue;
    const Vector3 center = box.center();
    const double radius = 0.5 * box.diagonal().norm() + threshold;
    box.min().array() -= threshold;
    box.max().array() += threshold;
    // Embree finds the triangles near the query's bounding sphere; their boxes sift them.
    candidates.clear();
    target.forEachTriangleNear(center, radius, [&](unsigned t) {
      const auto& corners = target_mesh.triangles[t];
      Eigen::AlignedBox3d target_box(target_mesh.vertices[corners[0]]);
      target_box.extend(target_mesh.vertices[corners[1]]).extend(target_mesh.vertices[corners[2]]);
      if (box.intersects(target_box)) candidates.push_back(t);
    });
    // Embree's traversal order is not part of its contract; contacts must not depend on it.
    std::sort(candidates.begin(), candidates.end());
    for (unsigned t : candidates) {
      const Triangle tt = triangleOf(target_mesh, t, target_mesh.vertices);
      pairs.clear();
      if (!collision::triangleContacts(tq, tt, threshold_sq, pairs)) {
        intersecting = true;
        continue;
      }
      if (pairs.empty()) continue;
      const Vector3 face = (tt.b - tt.a).cross(tt.c - tt.a).normalized();
      for (const PointPair& p : pairs) out.push_back({p.onFirst, p.onSecond, face});
    }
  }
  return intersecting;
}

Contact makeContact(const BodyRef& body1, const BodyRef& body2, const RawContact& raw,
                    const BodyModel& model1, const BodyModel& model2,
                    const ContactRequest& request) {
  Contact contact;
  contact.body1 = body1;
  contact.body2 = body2;
  contact.position1 = raw.onFirst;
  contact.position2 = raw.onSecond;
  const Vector3 gap = raw.onFirst - raw.onSecond;
  contact.distance = gap.norm();
  // Touching points give no direction; the face of body2 then says where body1 is.
  contact.normal = contact.distance > 1e-12 ? Vector3(gap / contact.distance) : raw.intoFirst;
  contact.frame = contactFrame(contact.normal);
  contact.mu = staticFriction(model1.material, model2.material);
  if (contact.mu <= 0.0) {
    contact.model = ContactModel::Frictionless;
  } else if (request.softContacts && (model1.isElastic() || model2.isElastic())) {
    contact.model = ContactModel::SoftFinger;
  } else {
    contact.model = ContactModel::PointWithFriction;
  }
  return contact;
}

}  // namespace

ContactResult findContacts(const World& world, const BodyRef& body1, const BodyRef& body2,
                           const ContactRequest& request) {
  const BodyModel& model1 = bodyModel(world, body1);
  const BodyModel& model2 = bodyModel(world, body2);
  ContactResult result;
  if (!model1.mesh || !model2.mesh || model1.mesh->empty() || model2.mesh->empty()) return result;

  // GraspIt! works on each pair in a fixed order (its first body is the one loaded first); the
  // clean-up below depends on it, so we work in that order and turn the result round at the end.
  const bool flip = body2 < body1;
  const BodyRef& first = flip ? body2 : body1;
  const BodyRef& second = flip ? body1 : body2;
  const BodyModel& first_model = flip ? model2 : model1;
  const BodyModel& second_model = flip ? model1 : model2;
  const Transform first_pose = bodyPose(world, first);
  const Transform second_pose = bodyPose(world, second);

  // Walk the smaller mesh's triangles and search the larger one's Embree geometry.
  const bool walk_second = first_model.mesh->triangleCount() > second_model.mesh->triangleCount();
  const auto& query = walk_second ? second_model.mesh : first_model.mesh;
  const auto target = raycast::embreeMesh(walk_second ? first_model.mesh : second_model.mesh);
  const Transform& query_pose = walk_second ? second_pose : first_pose;
  const Transform& target_pose = walk_second ? first_pose : second_pose;
  const Transform query_to_target = target_pose.inverse() * query_pose;

  Eigen::AlignedBox3d reach = target->bounds();
  reach.min().array() -= request.threshold;
  reach.max().array() += request.threshold;
  const Eigen::AlignedBox3d& query_box = raycast::embreeMesh(query)->bounds();
  if (!transformedBox(query_box, query_to_target).intersects(reach)) return result;

  std::vector<RawContact> raw;
  result.interpenetrating = searchPairs(*query, query_to_target, *target, request.threshold, raw);
  const Transform first_inverse = first_pose.inverse();
  const Transform second_inverse = second_pose.inverse();
  for (RawContact& r : raw) {
    r.onFirst = target_pose * r.onFirst;
    r.onSecond = target_pose * r.onSecond;
    r.intoFirst = target_pose.linear() * r.intoFirst;
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
  result.contacts.reserve(raw.size());
  for (const RawContact& r : raw) {
    Contact c = makeContact(first, second, r, first_model, second_model, request);
    result.contacts.push_back(flip ? c.mate() : c);
  }
  return result;
}

}  // namespace graspkit
