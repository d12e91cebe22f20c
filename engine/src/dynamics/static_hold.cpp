#include "graspkit/dynamics/static_hold.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "dynamics/generalized_coordinates.hpp"
#include "graspkit/math/nonnegative_least_squares.hpp"

namespace graspkit {

namespace {

using dynamics::GeneralizedCoordinates;
using dynamics::MatrixX;
using dynamics::VectorX;

// A DOF this near a limit (rad or mm) may be held there by the limit, whose force statics does
// not know: as near as the dynamics' joint-limit constraints enter its problem.
constexpr double kNearLimit = 1e-3;

// The residual (in units of the object's weight, rows scaled to their largest entry) below which
// an equilibrium is taken to exist: far above rounding, far below any force that matters.
constexpr double kEquilibriumResidual = 1e-7;

// Adds the contact to `out` (its impulse times `per_second`, a force) when it involves the object.
void addContact(const World& world, const BodyRef& object, const ContactImpulse& impulse,
                double per_second, HeldContacts& out) {
  const bool first = impulse.body1 == object;
  if (!first && !(impulse.body2 == object)) {
    out.betweenOthers = true;
    return;
  }
  const double sign = first ? 1.0 : -1.0;
  HeldContact contact;
  contact.other = first ? impulse.body2 : impulse.body1;
  contact.point = bodyPose(world, impulse.body1) * impulse.localPoint;
  contact.normal = sign * impulse.normal;
  contact.mu = impulse.mu;
  contact.force = sign * per_second * impulse.impulse;
  out.onObject.push_back(contact);
}

// Why no robot touching the object can be judged by statics, or "" when all can.
std::string unjudgedRobots(const World& world, const GeneralizedCoordinates& coordinates,
                           const std::vector<bool>& touched) {
  for (int r = 0; r < world.robotCount(); ++r) {
    const int offset = coordinates.robotOffset(r);
    if (offset < 0) continue;
    const Robot& robot = world.robot(r);
    for (int d = 0; d < robot.dofCount(); ++d) {
      if (!touched[offset + d]) continue;
      const Dof& dof = robot.model().dofs[d];
      if (dof.type != DofType::Rigid)
        return fmt::format("DOF {} of '{}' is {}: its joints or force change under load", d,
                           robot.name(),
                           dof.type == DofType::Breakaway ? "breakaway" : "compliant");
      const double value = robot.dofValues()[d];
      if (value <= dof.min + kNearLimit || value >= dof.max - kNearLimit)
        return fmt::format("DOF {} of '{}' is at a limit, whose force statics does not know", d,
                           robot.name());
    }
  }
  return "";
}

}  // namespace

HeldContacts heldContacts(const World& world, int object,
                          const std::vector<ContactImpulse>& previousImpulses,
                          const std::vector<ContactImpulse>& lastImpulses, double dt) {
  if (!(dt > 0.0)) throw Error("static hold: the step length must be positive");
  const BodyRef target = BodyRef::body(object);
  HeldContacts out;
  // Each step's impulse over 2 dt: the two steps' mean force.
  for (const ContactImpulse& impulse : previousImpulses)
    addContact(world, target, impulse, 0.5 / dt, out);
  for (const ContactImpulse& impulse : lastImpulses)
    addContact(world, target, impulse, 0.5 / dt, out);
  return out;
}

StaticHoldResult staticHold(const World& world, int object, const HeldContacts& contacts,
                            const StaticHoldRequest& request) {
  if (object < 0 || object >= static_cast<int>(world.bodies().size()) ||
      !world.bodies()[object].isDynamic())
    throw Error(fmt::format("static hold: body {} is not a graspable body of the world", object));
  const StaticHoldMargins& margins = request.margins;
  if (margins.coneEdges < 3 || !(margins.frictionShare >= 0.0 && margins.frictionShare <= 1.0) ||
      !request.acceleration.allFinite() || !(margins.loadFactor >= 1.0) ||
      !(margins.disturbance >= 0.0) || !(margins.leastShare >= 0.0 && margins.leastShare <= 1.0) ||
      !std::isfinite(margins.loadFactor + margins.disturbance))
    throw Error(
        "static hold: the pull must be finite, the friction share within [0, 1], the "
        "load factor at least 1, the disturbance not negative, the least share within [0, "
        "1] and the pyramid at least 3 edges");
  StaticHoldResult result;
  if (contacts.betweenOthers) {
    result.reason = "bodies other than the object touch each other (forces between DOFs)";
    return result;
  }
  if (contacts.onObject.empty()) {
    result.reason = "nothing touches the object";
    return result;
  }
  const BodyRef target = BodyRef::body(object);
  const GeneralizedCoordinates coordinates(world);
  const int n = coordinates.size();
  const BodyModel& model = *world.bodies()[object].model;
  // Forces in units of the object's weight under the pull (or of its largest contact force).
  double unit = model.mass * request.acceleration.norm();
  for (const HeldContact& c : contacts.onObject) unit = std::max(unit, 1e-9 * c.force.norm());
  if (!(unit > 0.0)) unit = 1.0;

  // G_c^T for each contact: the generalized force of a unit force on the object at the contact,
  // the link it touches pushed back.
  const int edges = margins.coneEdges;
  const int columns = static_cast<int>(contacts.onObject.size()) * edges;
  MatrixX A = MatrixX::Zero(n, columns);
  VectorX b = VectorX::Zero(n);
  std::vector<bool> touched(n, false);
  // Only contacts that bear load at rest count: one the squeeze barely presses may be a gap
  // within the contact search's reach, which the object would have to move to close.
  double largest = 0.0;
  for (const HeldContact& c : contacts.onObject) largest = std::max(largest, c.force.dot(c.normal));
  const double least = margins.leastShare * largest;
  for (std::size_t i = 0; i < contacts.onObject.size(); ++i) {
    const HeldContact& c = contacts.onObject[i];
    if (c.force.dot(c.normal) < least) continue;
    if (c.other.kind != BodyRef::Kind::Link) {
      result.reason = fmt::format("the object touches '{}', which is not a hand's link",
                                  bodyName(world, c.other));
      return result;
    }
    const MatrixX Gt =
        (coordinates.linearJacobian(target, c.point) - coordinates.linearJacobian(c.other, c.point))
            .transpose();
    b += Gt * (c.force / unit);
    // The pyramid: the normal plus the shared friction along `edges` directions of the plane.
    const Vector3 t1 = c.normal.unitOrthogonal();
    const Vector3 t2 = c.normal.cross(t1);
    const double mu = margins.frictionShare * c.mu;
    for (int e = 0; e < edges; ++e) {
      const double angle = 2.0 * std::numbers::pi * e / edges;
      const Vector3 edge = c.normal + mu * (std::cos(angle) * t1 + std::sin(angle) * t2);
      A.col(static_cast<int>(i) * edges + e) = Gt * edge;
    }
    for (int k = 0; k < n; ++k)
      if (Gt.row(k).squaredNorm() > 0.0) touched[k] = true;
  }
  if (std::string why = unjudgedRobots(world, coordinates, touched); !why.empty()) {
    result.reason = std::move(why);
    return result;
  }
  // The pull's generalized force: on the object, and on the links of the DOFs it touches (a
  // saturated controller does not carry the links' weight as well as its squeeze).
  VectorX pull = VectorX::Zero(n);
  for (const BodyRef& ref : coordinates.movingBodies()) {
    const BodyModel& part = bodyModel(world, ref);
    const Vector3 centre = bodyPose(world, ref) * part.cog;
    pull += coordinates.linearJacobian(ref, centre).transpose() *
            (part.mass * request.acceleration / unit);
  }
  b -= margins.loadFactor * pull;
  // Only the coordinates some contact moves: the others' balance is the dynamics' own business
  // (a finger in the air goes on closing).
  std::vector<int> rows;
  for (int k = 0; k < n; ++k)
    if (touched[k]) rows.push_back(k);
  MatrixX A_rows(rows.size(), columns);
  VectorX b_rows(rows.size()), scales(rows.size());
  for (std::size_t r = 0; r < rows.size(); ++r) {
    scales[r] = A.row(rows[r]).cwiseAbs().maxCoeff();
    A_rows.row(r) = A.row(rows[r]) / scales[r];
    b_rows[r] = b[rows[r]] / scales[r];
  }
  // The disturbances, each of the object's 6 wrench axes both ways: a force of `disturbance`
  // times the weight, a moment of that times the object's radius. The loads an equilibrium holds
  // form a convex set, so holding these 12 holds the whole box of loads between them.
  const int free = coordinates.motion(target).freeCoordinate;
  const double radius = std::max(model.maxRadius, 1.0);
  for (int axis = 0; axis < 12; ++axis) {
    VectorX load = b_rows;
    if (margins.disturbance > 0.0) {
      const int k = free + axis / 2;
      const double size = margins.disturbance * (axis / 2 < 3 ? 1.0 : radius);
      const double sign = axis % 2 == 0 ? 1.0 : -1.0;
      for (std::size_t r = 0; r < rows.size(); ++r)
        if (rows[r] == k) load[r] -= sign * size / scales[r];
    } else if (axis > 0) {
      break;
    }
    const NonnegativeLeastSquaresResult solved =
        nonnegativeLeastSquares(A_rows, load, {.enoughResidual = kEquilibriumResidual});
    result.residual = std::max(result.residual, solved.residual);
    if (solved.residual > kEquilibriumResidual) {
      result.reason = fmt::format(
          "no equilibrium for {} times the pull{} within {} of the friction (residual {:.3g})",
          margins.loadFactor, margins.disturbance > 0.0 ? " and a disturbance" : "",
          margins.frictionShare, solved.residual);
      return result;
    }
  }
  result.holds = true;
  return result;
}

}  // namespace graspkit
