#include "graspkit/model/virtual_contact.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "geometry/closest_point.hpp"
#include "graspkit/model/body.hpp"
#include "graspkit/model/robot.hpp"

namespace graspkit {

namespace {

constexpr double kPadCosine = 0.70710678118654752;  // 45 degrees
constexpr double kDerivedFriction = 0.5;
constexpr int kFrictionEdges = 8;
// GraspIt!'s autograsp step: 0.01 of a DOF's default velocity.
constexpr double kClosingStep = 0.01;

// The pad of `mesh` (link frame): triangles whose outward normal is within 45 degrees of
// `motion(centroid)` (a direction in the link frame); nullopt when there are none.
template <typename Motion>
std::optional<VirtualContact> padContact(const TriangleMesh& mesh, Motion motion) {
  Vector3 centroid = Vector3::Zero(), normal = Vector3::Zero();
  double area = 0.0;
  std::vector<std::size_t> pad;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& tri = mesh.triangles[t];
    const Vector3 &a = mesh.vertices[tri[0]], &b = mesh.vertices[tri[1]],
                  &c = mesh.vertices[tri[2]];
    const Vector3 cross = (b - a).cross(c - a);
    const double twiceArea = cross.norm();
    if (twiceArea <= 0) continue;
    const Vector3 n = cross / twiceArea;
    const Vector3 centre = (a + b + c) / 3.0;
    const Vector3 way = motion(centre);
    if (way.norm() <= 0 || n.dot(way.normalized()) < kPadCosine) continue;
    pad.push_back(t);
    centroid += 0.5 * twiceArea * centre;
    normal += 0.5 * twiceArea * n;
    area += 0.5 * twiceArea;
  }
  if (pad.empty() || normal.norm() <= 0) return std::nullopt;
  centroid /= area;
  Vector3 nearest = centroid;
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t t : pad) {
    const auto& tri = mesh.triangles[t];
    const Vector3 q = geometry::closestPointOnTriangle(
        centroid, mesh.vertices[tri[0]], mesh.vertices[tri[1]], mesh.vertices[tri[2]]);
    if ((q - centroid).squaredNorm() < best) {
      best = (q - centroid).squaredNorm();
      nearest = q;
    }
  }
  VirtualContact contact;
  contact.location = nearest;
  contact.translation = nearest;
  contact.normal = normal.normalized();
  contact.rotation = Quaternion(contactFrame(contact.normal));
  contact.sCof = kDerivedFriction;
  for (int e = 0; e < kFrictionEdges; ++e) {
    const double angle = 2.0 * M_PI * e / kFrictionEdges;
    Eigen::Matrix<double, 6, 1> edge = Eigen::Matrix<double, 6, 1>::Zero();
    edge[0] = std::cos(angle);
    edge[1] = std::sin(angle);
    contact.frictionEdges.push_back(edge);
  }
  return contact;
}

}  // namespace

std::vector<VirtualContact> deriveVirtualContacts(const Robot& robot) {
  const RobotModel& model = robot.model();
  std::vector<VirtualContact> contacts;
  if (model.palm && model.palm->mesh) {
    const Vector3 approach = model.approachFrame().linear().col(2);
    if (auto c = padContact(*model.palm->mesh, [&](const Vector3&) { return approach; })) {
      c->finger = -1;
      c->link = 0;
      contacts.push_back(*c);
    }
  }
  // The hand half-way through its range and a closing step later (mid-range, so that no DOF
  // is held at a limit; a link's pad hardly depends on where in its range it is).
  Robot middle = robot;
  std::vector<double> values(model.dofs.size()), ahead(model.dofs.size());
  for (std::size_t d = 0; d < model.dofs.size(); ++d) {
    const Dof& dof = model.dofs[d];
    values[d] = 0.5 * (dof.min + dof.max);
    ahead[d] = values[d] + kClosingStep * dof.defaultVelocity;
  }
  middle.setDofValues(values, LimitPolicy::Ignore);
  Robot closing = middle;
  closing.setDofValues(ahead, LimitPolicy::Ignore);
  for (int c = 0; c < static_cast<int>(model.chains.size()); ++c) {
    for (int l = 0; l < static_cast<int>(model.chains[c].links.size()); ++l) {
      const auto& body = model.chains[c].links[l].body;
      if (!body || !body->mesh) continue;
      const Transform now = middle.linkPose(c, l);
      const Transform next = closing.linkPose(c, l);
      const Transform delta = now.inverse() * next;  // link frame now -> a step later
      if (delta.isApprox(Transform::Identity(), 1e-12)) continue;
      // The displacement of a link point, in the link frame.
      auto motion = [&](const Vector3& p) -> Vector3 { return delta * p - p; };
      if (auto contact = padContact(*body->mesh, motion)) {
        contact->finger = c;
        contact->link = l;
        contacts.push_back(*contact);
      }
    }
  }
  return contacts;
}

std::vector<VirtualContact> deriveFingertipContacts(const Robot& robot) {
  const RobotModel& model = robot.model();
  const std::vector<VirtualContact> all = deriveVirtualContacts(robot);
  Robot middle = robot;
  std::vector<double> values;
  for (const Dof& dof : model.dofs) values.push_back(0.5 * (dof.min + dof.max));
  middle.setDofValues(values, LimitPolicy::Ignore);
  const Vector3 palm = middle.pose().translation();
  // Each chain's reach: its last link's contact (else its last link's origin) from the palm.
  const int chains = static_cast<int>(model.chains.size());
  std::vector<double> reach(static_cast<std::size_t>(chains), 0.0);
  for (int c = 0; c < chains; ++c) {
    const int last = static_cast<int>(model.chains[c].links.size()) - 1;
    if (last < 0) continue;
    Vector3 tip = middle.linkPose(c, last).translation();
    for (const VirtualContact& v : all)
      if (v.finger == c && v.link == last) tip = middle.linkPose(c, last) * v.location;
    reach[c] = (tip - palm).norm();
  }
  std::vector<double> farthest(model.dofs.size(), 0.0);  // per DOF, over the chains it drives
  for (int c = 0; c < chains; ++c)
    for (const Joint& joint : model.chains[c].joints)
      farthest[joint.dof] = std::max(farthest[joint.dof], reach[c]);
  std::vector<VirtualContact> kept;
  for (const VirtualContact& v : all) {
    if (v.finger < 0) {
      kept.push_back(v);
      continue;
    }
    const KinematicChain& chain = model.chains[v.finger];
    if (v.link != static_cast<int>(chain.links.size()) - 1) continue;
    bool finger = true;
    for (const Joint& joint : chain.joints)
      if (reach[v.finger] < 0.9 * farthest[joint.dof]) finger = false;
    if (finger) kept.push_back(v);
  }
  return kept;
}

}  // namespace graspkit
