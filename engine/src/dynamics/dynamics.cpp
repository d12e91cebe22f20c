// One time step, as dynamics.hpp describes it: free motion, then the contact and joint-limit
// impulses from Siconos, then the new poses.

#include "graspkit/dynamics/dynamics.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>

#include <Eigen/Eigenvalues>

#include "collision/shared_volume.hpp"
#include "dynamics/breakaway_clutch.hpp"
#include "dynamics/friction_contact_solver.hpp"
#include "dynamics/generalized_coordinates.hpp"
#include "graspkit/collision/collision.hpp"
#include "graspkit/collision/contact_search.hpp"
#include "graspkit/model/world.hpp"

namespace graspkit {

namespace {

using dynamics::GeneralizedCoordinates;
using dynamics::MatrixX;
using dynamics::VectorX;

// Share of a penetration below kRestingSeparation removed per step (GraspIt!'s ERP is 0.05; a
// larger share settles stacks faster, and the push-out speed stays below 10 mm/s).
constexpr double kErrorReduction = 0.2;
constexpr double kMaxContactMargin = 5.0;  // mm
constexpr double kFreeMotionMargin = 0.5;  // mm
// How deep a point of one body may lie inside another before the two are said to share volume.
constexpr double kSharedVolumeDepth = 0.5;  // mm
// Joint-limit constraints enter the problem this close to a limit (rad or mm), or closer than
// two steps of the DOF's motion.
constexpr double kLimitMargin = 1e-3;
// Coulomb joint friction fades in below this joint speed (rad/s, mm/s) so it cannot chatter.
constexpr double kJointFrictionSpeed = 1e-3;

double wrapAngle(double angle) {
  return std::remainder(angle, 2.0 * M_PI);
}

std::string describe(const World& world, const BodyRef& ref) {
  return bodyName(world, ref);
}

// The velocity vector of every coordinate, from the world's bodies and robots.
VectorX currentVelocities(const World& world, const GeneralizedCoordinates& coordinates) {
  VectorX u = VectorX::Zero(coordinates.size());
  for (int r = 0; r < world.robotCount(); ++r) {
    const int offset = coordinates.robotOffset(r);
    const auto velocities = world.robot(r).dofVelocities();
    for (std::size_t d = 0; d < velocities.size(); ++d) u[offset + d] = velocities[d];
  }
  for (std::size_t b = 0; b < world.bodies().size(); ++b) {
    const int offset = coordinates.bodyOffset(static_cast<int>(b));
    if (offset >= 0) u.segment<6>(offset) = world.bodies()[b].state.v;
  }
  return u;
}

// A body's mass and inertia must make a well-posed contact problem: a mass from a microgram to
// a million tonnes, and an inertia (per unit mass) symmetric and positive definite with its
// principal moments within 1e12 of each other. Anything else (1e-300 g, an indefinite inertia
// whose determinant is positive) would reach Siconos as a singular problem, which aborts.
void checkMass(const World& world, const BodyRef& ref) {
  constexpr double kLightest = 1e-6, kHeaviest = 1e12;  // g
  const BodyModel& model = bodyModel(world, ref);
  bool inertia_ok =
      model.inertia.allFinite() && (model.inertia - model.inertia.transpose()).norm() <=
                                       1e-9 * std::max(1.0, model.inertia.norm());
  if (inertia_ok) {
    const Eigen::SelfAdjointEigenSolver<Matrix3> moments(model.inertia);
    const Vector3 m = moments.eigenvalues();
    inertia_ok = moments.info() == Eigen::Success && m.minCoeff() > 0.0 &&
                 m.minCoeff() >= 1e-12 * m.maxCoeff();
  }
  if (!(model.mass >= kLightest && model.mass <= kHeaviest) || !inertia_ok) {
    throw Error(SourceLocation{model.file.string(), 0, "mass"},
                fmt::format("'{}' takes part in dynamics but its mass ({} g, from {} to {}) or "
                            "inertia (symmetric, positive definite) is out of range",
                            describe(world, ref), model.mass, kLightest, kHeaviest));
  }
}

// Mass matrix and generalized forces (gravity, gyroscopic torques of free bodies).
struct MassAndForces {
  MatrixX M;
  VectorX f;
  VectorX robotWeight;  // the generalized gravity forces of the robots' own parts
};

MassAndForces massAndForces(const World& world, const GeneralizedCoordinates& coordinates,
                            const VectorX& u) {
  const int n = coordinates.size();
  MassAndForces out{MatrixX::Zero(n, n), VectorX::Zero(n), VectorX::Zero(n)};
  for (const BodyRef& ref : coordinates.movingBodies()) {
    checkMass(world, ref);
    const BodyModel& model = bodyModel(world, ref);
    const Transform pose = bodyPose(world, ref);
    const Matrix3 R = pose.linear();
    const Matrix3 inertia = model.mass * R * model.inertia * R.transpose();
    const Vector3 weight = model.mass * world.gravity();
    const int free = coordinates.motion(ref).freeCoordinate;
    if (free >= 0) {
      out.M.block<3, 3>(free, free) = model.mass * Matrix3::Identity();
      out.M.block<3, 3>(free + 3, free + 3) = inertia;
      const Vector3 omega = u.segment<3>(free + 3);
      out.f.segment<3>(free) += weight;
      out.f.segment<3>(free + 3) -= omega.cross(inertia * omega);
      continue;
    }
    const MatrixX Jv = coordinates.linearJacobian(ref, pose * model.cog);
    const MatrixX Jw = coordinates.angularJacobian(ref);
    out.M += model.mass * Jv.transpose() * Jv + Jw.transpose() * inertia * Jw;
    out.f += Jv.transpose() * weight;
    out.robotWeight += Jv.transpose() * weight;
  }
  return out;
}

// A robot's controller set-points after this step: each moves towards its target at the DOF's
// speed. A robot without targets holds its posture, brought into range: a world may load a DOF
// outside its limits (barrettGlassDyn's Puma elbow), which GraspIt! refuses to step.
struct SetPoints {
  std::vector<double> targets;
  std::vector<double> references;
  std::vector<double> rates;
};

SetPoints nextSetPoints(const Robot& robot, double h) {
  const auto& dofs = robot.model().dofs;
  SetPoints next;
  next.targets.assign(robot.dofTargets().begin(), robot.dofTargets().end());
  if (next.targets.empty()) {
    for (int d = 0; d < robot.dofCount(); ++d) {
      next.targets.push_back(dofs[d].clamp(robot.dofValues()[d]));
    }
  }
  const auto start = robot.dofReferences().empty() ? robot.dofValues() : robot.dofReferences();
  next.references.assign(start.begin(), start.end());
  next.rates.assign(next.references.size(), 0.0);
  for (int d = 0; d < robot.dofCount(); ++d) {
    const double speed = dofs[d].defaultVelocity != 0.0 ? std::abs(dofs[d].defaultVelocity) : 1.0;
    const double move = std::clamp(next.targets[d] - next.references[d], -speed * h, speed * h);
    next.references[d] += move;
    next.rates[d] = move / h;
  }
  return next;
}

// A DOF's PD controller in one step. Below maxEffort its stiffness and damping are taken
// implicitly (h*Kd + h^2*Kp on the mass matrix's diagonal), so GraspIt!'s stiff gains are stable
// at its 2.5 ms step; a saturated controller pushes with maxEffort and nothing more.
struct Controller {
  int coordinate = 0;
  double Kp = 0.0;
  double Kd = 0.0;
  double maxEffort = 0.0;  // 0: unlimited
  double error = 0.0;      // set-point minus position
  double rate = 0.0;       // the set-point's speed
  double feedForward = 0.0;
  double saturated = 0.0;  // the force's sign once it saturates, else 0

  // The force if it acts implicitly and the coordinate ends the step at velocity v.
  double implicitForce(double v, double h) const {
    return Kp * (error - h * v) + Kd * (rate - v) + feedForward;
  }
  void addTo(VectorX& f, VectorX& damping, double h) const {
    if (saturated != 0.0) {
      f[coordinate] += saturated * maxEffort;
    } else {
      f[coordinate] += Kp * error + Kd * rate + feedForward;
      damping[coordinate] += h * Kd + h * h * Kp;
    }
  }
  // Saturates the controller if its force at velocity v would exceed maxEffort; returns whether
  // it changed.
  bool saturateAt(double v, double h) {
    if (saturated != 0.0 || maxEffort <= 0.0) return false;
    const double force = implicitForce(v, h);
    if (std::abs(force) <= maxEffort) return false;
    saturated = std::copysign(1.0, force);
    return true;
  }
};

// GraspIt!'s compliant DOF is a force source, not a PD: it pushes towards its set-point with a
// force that ramps from 0 to maxEffort over the first second of the simulation, acting on a
// revolute DOF through a 40 mm lever.
constexpr double kCompliantRampSeconds = 1.0;
constexpr double kCompliantLever = 40.0;  // mm

double compliantForce(const Dof& dof, bool revolute, double error, double time) {
  if (revolute) error = wrapAngle(error);
  if (error == 0.0 || dof.maxEffort <= 0.0) return 0.0;
  const double force = dof.maxEffort * std::min(1.0, time / kCompliantRampSeconds);
  return std::copysign(revolute ? force * kCompliantLever : force, error);
}

// DOF PD controllers (with gravity compensation), saturated where their force at the current
// velocity already exceeds maxEffort, and passive joint springs and friction.
void addJointForces(const World& world, const GeneralizedCoordinates& coordinates, const VectorX& u,
                    const VectorX& robot_weight, double h, std::vector<SetPoints>& set_points,
                    std::vector<Controller>& controllers, VectorX& f, VectorX& damping) {
  set_points.assign(world.robotCount(), {});
  for (int r = 0; r < world.robotCount(); ++r) {
    const Robot& robot = world.robot(r);
    const int offset = coordinates.robotOffset(r);
    if (offset < 0) continue;
    set_points[r] = nextSetPoints(robot, h);
    const std::vector<double>& rates = set_points[r].rates;
    const RobotModel& model = robot.model();
    for (int d = 0; d < robot.dofCount(); ++d) {
      const Dof& dof = model.dofs[d];
      const bool revolute =
          dof.joints.empty() || model.joint(dof.joints.front()).type == JointType::Revolute;
      if (dof.type == DofType::Compliant) {
        f[offset + d] += compliantForce(
            dof, revolute, set_points[r].targets[d] - robot.dofValues()[d], world.time());
        continue;
      }
      if (dof.Kp == 0.0 && dof.Kd == 0.0) continue;
      Controller controller;
      controller.coordinate = offset + d;
      controller.Kp = dof.Kp;
      controller.Kd = dof.Kd;
      controller.maxEffort = dof.maxEffort;
      controller.error = set_points[r].references[d] - robot.dofValues()[d];
      if (revolute) controller.error = wrapAngle(controller.error);
      controller.rate = rates[d];
      // The controller carries the robot's own weight (gravity feed-forward), so an arm holds
      // its set-points under gravity instead of sagging by weight / Kp.
      controller.feedForward = -robot_weight[controller.coordinate];
      // Explicitly, at the current velocity (the step's first guess).
      const double force = controller.Kp * controller.error +
                           controller.Kd * (controller.rate - u[controller.coordinate]) +
                           controller.feedForward;
      if (controller.maxEffort > 0.0 && std::abs(force) > controller.maxEffort)
        controller.saturated = std::copysign(1.0, force);
      controllers.push_back(controller);
    }
    for (int j = 0; j < model.jointCount(); ++j) {
      const Joint& joint = model.joint(j);
      if (robot.breakaway()[j].engaged)
        continue;  // held by its clutch, see generalized_coordinates
      const int i = offset + joint.dof;
      const double velocity = joint.ratio * u[i];
      const double spring = -joint.springStiffness * (robot.jointValues()[j] - joint.restValue);
      const double friction =
          -joint.coulombFriction * std::clamp(velocity / kJointFrictionSpeed, -1.0, 1.0);
      f[i] += joint.ratio * (spring + friction);
      damping[i] += h * joint.ratio * joint.ratio * joint.viscousFriction;
    }
  }
}

// How far apart two bodies' surfaces may close within one step, as a bound: their relative
// velocity at the midpoint m of their centres of mass plus the relative angular velocity times
// the farthest any of their points can be from m.
double closingSpeedBound(const World& world, const GeneralizedCoordinates& coordinates,
                         const VectorX& u, const BodyRef& a, const BodyRef& b) {
  const BodyModel& model_a = bodyModel(world, a);
  const BodyModel& model_b = bodyModel(world, b);
  const Vector3 centre_a = bodyPose(world, a) * model_a.cog;
  const Vector3 centre_b = bodyPose(world, b) * model_b.cog;
  const Vector3 middle = 0.5 * (centre_a + centre_b);
  const double linear =
      ((coordinates.linearJacobian(a, middle) - coordinates.linearJacobian(b, middle)) * u).norm();
  const double angular =
      ((coordinates.angularJacobian(a) - coordinates.angularJacobian(b)) * u).norm();
  const double reach =
      0.5 * (centre_a - centre_b).norm() + std::max(model_a.maxRadius, model_b.maxRadius);
  return linear + angular * reach;
}

// The constraints of one step: 3 rows each (normal, tangent, tangent).
struct Constraints {
  MatrixX G;                   // rows x coordinates
  VectorX offset;              // added to G*u: the gap the step may close (normal rows)
  VectorX mu;                  // per constraint
  VectorX compliance;          // per constraint, added to W's normal diagonal
  std::vector<int> limitRows;  // first row of each joint-limit constraint
  std::vector<std::pair<BodyRef, BodyRef>> bodies;  // per contact constraint
  std::vector<Vector3> localPoints;                 // per contact: its point in body1's frame
  std::vector<Matrix3> frames;                      // per contact: columns t1, t2, normal
  std::vector<double> distances;                    // per contact: its separation, mm
  std::map<std::pair<BodyRef, BodyRef>, double> thresholds;  // per pair: the search's, mm
  int contacts = 0;
  int limits = 0;

  // Rows are added per constraint; the columns are the coordinates.
  explicit Constraints(int coordinates) : G(0, coordinates) {}
  int add(const MatrixX& rows, double gap_offset, double friction, double soft) {
    const int first = static_cast<int>(G.rows());
    G.conservativeResize(first + 3, Eigen::NoChange);
    G.middleRows(first, 3) = rows;
    offset.conservativeResize(first + 3);
    offset.segment<3>(first) << gap_offset, 0.0, 0.0;
    mu.conservativeResize(mu.size() + 1);
    mu[mu.size() - 1] = friction;
    compliance.conservativeResize(compliance.size() + 1);
    compliance[compliance.size() - 1] = soft;
    return first;
  }
};

// How far the step may close a gap: all of it down to the resting separation. Inside it a
// contact only may not close, and below half of it, it is pushed back out at a share per step:
// the band between keeps bodies that cannot all move apart (an object wedged between fixed
// links) from asking for push-outs step after step.
double gapOffset(double separation, double h) {
  const double gap = separation - kRestingSeparation;
  if (gap > 0.0) return gap / h;
  return separation < 0.5 * kRestingSeparation ? kErrorReduction * gap / h : 0.0;
}

// A soft contact (either body has <youngs>) gives way like a mattress of GraspIt!'s 3 mm
// thickness over the patch that its neighbourhood radius spans: k = E * pi r^2 / 3 mm.
// 1 Pa is 1 g/(mm s^2) in these units. Returns the compliance added to W, 1/(h^2 k).
double contactCompliance(const BodyModel& a, const BodyModel& b, double h) {
  double stiffness = 0.0;
  for (const BodyModel* model : {&a, &b}) {
    if (!model->youngs || *model->youngs <= 0.0) continue;
    const double radius = 0.4 * 1000.0 * std::cbrt(1.0 / *model->youngs);
    const double k = *model->youngs * M_PI * radius * radius / 3.0;
    stiffness = stiffness == 0.0 ? k : 1.0 / (1.0 / stiffness + 1.0 / k);  // in series
  }
  return stiffness > 0.0 ? 1.0 / (h * h * stiffness) : 0.0;
}

void addContacts(const World& world, const GeneralizedCoordinates& coordinates, const VectorX& u,
                 const VectorX& free_velocity, double h, Constraints& constraints) {
  ContactRequest request;
  request.softContacts = false;
  // Compaction keeps the perimeter of contacts that share a normal, right for two flat faces
  // but not for a curved body on a face, whose deepest points may lie inside that perimeter.
  request.compact = false;
  request.graspitDuplicates = false;
  // A body standing exactly on another (as worlds place them) is in contact, not in collision.
  request.touchingIsContact = true;
  for (const BodyPair& pair : nearbyPairs(world, kMaxContactMargin)) {
    if (!coordinates.motion(pair.first).moves() && !coordinates.motion(pair.second).moves()) {
      continue;
    }
    // Contacts within what the step can close, before or after its free motion (a controller
    // can start a finger from rest), so that nothing tunnels: a held object and the hand moving
    // together need no more than the contact threshold.
    // The free motion's share is capped: a saturated controller's free velocity (what it would
    // reach if nothing resisted) is far above what contacts let happen, and a margin that large
    // brings hundreds of contacts into the problem.
    const double before = closingSpeedBound(world, coordinates, u, pair.first, pair.second);
    const double after =
        closingSpeedBound(world, coordinates, free_velocity, pair.first, pair.second);
    request.threshold =
        std::min(kMaxContactMargin, kContactThreshold + 2.0 * h * before +
                                        std::min(2.0 * h * after, kFreeMotionMargin));
    const ContactResult found = findContacts(world, pair.first, pair.second, request);
    if (found.interpenetrating) {
      throw DynamicsError(fmt::format("at t = {:.4f} s, '{}' and '{}' interpenetrate", world.time(),
                                      describe(world, pair.first), describe(world, pair.second)),
                          dynamicStateJson(world));
    }
    constraints.thresholds[{pair.first, pair.second}] = request.threshold;
    const BodyModel& first = bodyModel(world, pair.first);
    const BodyModel& second = bodyModel(world, pair.second);
    const double compliance = contactCompliance(first, second, h);
    const Transform first_inverse = bodyPose(world, pair.first).inverse();
    for (const Contact& contact : found.contacts) {
      const MatrixX relative = coordinates.linearJacobian(pair.first, contact.position1) -
                               coordinates.linearJacobian(pair.second, contact.position2);
      MatrixX rows(3, coordinates.size());
      rows.row(0) = contact.frame.col(2).transpose() * relative;
      rows.row(1) = contact.frame.col(0).transpose() * relative;
      rows.row(2) = contact.frame.col(1).transpose() * relative;
      if (rows.isZero()) continue;
      const double slip = (rows.bottomRows(2) * u).norm();
      const double mu = frictionCoefficient(first.material, second.material, true, slip);
      constraints.add(rows, gapOffset(contact.distance, h), mu, compliance);
      constraints.bodies.emplace_back(pair.first, pair.second);
      constraints.localPoints.push_back(first_inverse * contact.position1);
      constraints.frames.push_back(contact.frame);
      constraints.distances.push_back(contact.distance);
      ++constraints.contacts;
    }
  }
}

// Where a contact was within this of one of the last step's on the same pair (body1's frame),
// it starts from that one's impulse.
constexpr double kWarmStartReach = 1.0;  // mm

VectorX warmStart(const World& world, const Constraints& constraints) {
  VectorX start = VectorX::Zero(constraints.G.rows());
  const std::vector<ContactImpulse>& last = world.lastImpulses();
  for (int c = 0; c < constraints.contacts; ++c) {
    const ContactImpulse* nearest = nullptr;
    double best = kWarmStartReach;
    for (const ContactImpulse& previous : last) {
      if (!(previous.body1 == constraints.bodies[c].first) ||
          !(previous.body2 == constraints.bodies[c].second)) {
        continue;
      }
      const double gap = (previous.localPoint - constraints.localPoints[c]).norm();
      if (gap < best) {
        best = gap;
        nearest = &previous;
      }
    }
    if (!nearest) continue;
    const Matrix3& frame = constraints.frames[c];
    start.segment<3>(3 * c) << frame.col(2).dot(nearest->impulse),
        frame.col(0).dot(nearest->impulse), frame.col(1).dot(nearest->impulse);
  }
  return start;
}

std::vector<ContactImpulse> contactImpulses(const Constraints& constraints,
                                            const VectorX& reaction) {
  std::vector<ContactImpulse> impulses;
  for (int c = 0; c < constraints.contacts; ++c) {
    const Matrix3& frame = constraints.frames[c];
    const Vector3 r = reaction.segment<3>(3 * c);
    if (r.isZero()) continue;
    impulses.push_back({constraints.bodies[c].first, constraints.bodies[c].second,
                        constraints.localPoints[c],
                        r[0] * frame.col(2) + r[1] * frame.col(0) + r[2] * frame.col(1),
                        frame.col(2), constraints.mu[c]});
  }
  return impulses;
}

void addJointLimits(const World& world, const GeneralizedCoordinates& coordinates, const VectorX& u,
                    double h, Constraints& constraints) {
  for (int r = 0; r < world.robotCount(); ++r) {
    const int offset = coordinates.robotOffset(r);
    if (offset < 0) continue;
    const Robot& robot = world.robot(r);
    for (int d = 0; d < robot.dofCount(); ++d) {
      const Dof& dof = robot.model().dofs[d];
      const int i = offset + d;
      const double reach = kLimitMargin + 2.0 * h * std::abs(u[i]);
      const double value = robot.dofValues()[d];
      for (const double sign : {1.0, -1.0}) {
        const double room = sign > 0 ? value - dof.min : dof.max - value;
        if (room > reach) continue;
        MatrixX rows = MatrixX::Zero(3, coordinates.size());
        rows(0, i) = sign;
        // Out of range (as loaded, or by drift): back in at a bounded speed.
        const double gap = room > 0.0 ? room / h : std::max(kErrorReduction * room / h, -1.0);
        constraints.limitRows.push_back(constraints.add(rows, gap, 0.0, 0.0));
        ++constraints.limits;
      }
    }
  }
}

void checkVelocities(const World& world, const GeneralizedCoordinates& coordinates,
                     const VectorX& u) {
  if (!u.allFinite()) {
    throw DynamicsError(
        fmt::format("at t = {:.4f} s, a velocity is not a finite number", world.time()),
        dynamicStateJson(world));
  }
  for (const BodyRef& ref : coordinates.movingBodies()) {
    const BodyModel& model = bodyModel(world, ref);
    const Vector3 centre = bodyPose(world, ref) * model.cog;
    const double linear = (coordinates.linearJacobian(ref, centre) * u).norm();
    const double angular = (coordinates.angularJacobian(ref) * u).norm();
    if (linear > kRunawaySpeed || angular > kRunawayAngularSpeed) {
      throw DynamicsError(fmt::format("at t = {:.4f} s, '{}' runs away at {:.0f} mm/s and {:.1f} "
                                      "rad/s: the simulation is unstable",
                                      world.time(), describe(world, ref), linear, angular),
                          dynamicStateJson(world));
    }
  }
}

// New poses from the new velocities: positions by the velocity at the end of the step
// (semi-implicit Euler), except that a free body no contact pushed follows the exact parabola
// of its free flight, so a throw or a fall has no integration error.
void integrate(World& world, const GeneralizedCoordinates& coordinates, const VectorX& u, double h,
               const std::vector<bool>& pushed) {
  for (int r = 0; r < world.robotCount(); ++r) {
    const int offset = coordinates.robotOffset(r);
    if (offset < 0) continue;
    const int count = world.robot(r).dofCount();
    std::vector<double> values(world.robot(r).dofValues().begin(),
                               world.robot(r).dofValues().end());
    std::vector<double> velocities(count);
    for (int d = 0; d < count; ++d) {
      velocities[d] = u[offset + d];
      values[d] += h * velocities[d];
    }
    world.setDofValues(r, values, LimitPolicy::Ignore);
    world.setDofVelocities(r, velocities);
  }
  for (std::size_t b = 0; b < world.bodies().size(); ++b) {
    const int offset = coordinates.bodyOffset(static_cast<int>(b));
    if (offset < 0) continue;
    Body& body = world.bodies()[b];
    const Vector3 v = u.segment<3>(offset);
    const Vector3 w = u.segment<3>(offset + 3);
    Vector3 centre = body.pose * body.model->cog + h * v;
    if (!pushed[b]) centre -= 0.5 * h * h * world.gravity();
    Quaternion rotation(body.pose.linear());
    const double angle = w.norm() * h;
    if (angle > 0.0) rotation = Eigen::AngleAxisd(angle, w.normalized()) * rotation;
    rotation.normalize();
    Transform pose = Transform::Identity();
    pose.linear() = rotation.toRotationMatrix();
    pose.translation() = centre - pose.linear() * body.model->cog;
    body.setPose(pose);
    body.state.v = u.segment<6>(offset);
  }
}

}  // namespace

std::string dynamicStateJson(const World& world) {
  nlohmann::json state;
  state["time"] = world.time();
  state["gravity"] = {world.gravity().x(), world.gravity().y(), world.gravity().z()};
  nlohmann::json bodies = nlohmann::json::array();
  for (const Body& body : world.bodies()) {
    const Quaternion q(body.pose.linear());
    const Vector3 t = body.pose.translation();
    bodies.push_back(
        {{"name", body.name},
         {"dynamic", body.isDynamic()},
         {"position", {t.x(), t.y(), t.z()}},
         {"orientation_wxyz", {q.w(), q.x(), q.y(), q.z()}},
         {"velocity", std::vector<double>(body.state.v.data(), body.state.v.data() + 6)}});
  }
  state["bodies"] = bodies;
  nlohmann::json robots = nlohmann::json::array();
  for (int r = 0; r < world.robotCount(); ++r) {
    const Robot& robot = world.robot(r);
    const auto list = [](std::span<const double> values) {
      return std::vector<double>(values.begin(), values.end());
    };
    // The base pose and the joints whose clutch broke away: with the DOF values they give every
    // link's pose, so a trajectory can be played back (graspkit view --trajectory).
    const Quaternion q(robot.pose().linear());
    const Vector3 t = robot.pose().translation();
    nlohmann::json brokeAway = nlohmann::json::array();
    for (std::size_t j = 0; j < robot.breakaway().size(); ++j)
      if (robot.breakaway()[j].engaged) brokeAway.push_back({j, robot.breakaway()[j].value});
    robots.push_back({{"name", robot.name()},
                      {"position", {t.x(), t.y(), t.z()}},
                      {"orientation_wxyz", {q.w(), q.x(), q.y(), q.z()}},
                      {"broken_away", brokeAway},
                      {"dof_values", list(robot.dofValues())},
                      {"dof_velocities", list(robot.dofVelocities())},
                      {"dof_targets", list(robot.dofTargets())},
                      {"dof_references", list(robot.dofReferences())}});
  }
  state["robots"] = robots;
  return state.dump();
}

void setClosingTargets(World& world, int robot_index) {
  const Robot& robot = world.robot(robot_index);
  std::vector<double> targets(robot.dofValues().begin(), robot.dofValues().end());
  for (int d = 0; d < robot.dofCount(); ++d) {
    const Dof& dof = robot.model().dofs[d];
    if (dof.defaultVelocity > 0.0) targets[d] = dof.max;
    if (dof.defaultVelocity < 0.0) targets[d] = dof.min;
  }
  world.setDofTargets(robot_index, targets);
}

namespace {

// How often one step re-solves with more controllers saturated (each pass saturates at least
// one more, so a hand needs at most its DOF count).
constexpr int kMaxControllerPasses = 8;
// A solution closing a contact faster than its gap allows by this (mm/s) could not meet its
// push-out requests.
constexpr double kClosingTolerance = 1.0;
// Siconos' relative residual sought, and the sweeps allowed: fewer with push-out requests, which
// a solver that has not nearly met them by then (residual 1e-5) is taken not to be able to meet.
// A squeeze asks for push-out nearly every step and NSGS almost never meets it (measured over a
// box's 10 validations: 135 of 23,400 met, all within 100 sweeps), so 100 sweeps, not 300. Not
// 30: the 25 met between 30 and 100 sweeps decide whether two of those grasps hold.
// Those are solved by NSGS alone: Newton's method meets push-out requests NSGS gives up on (a
// squeeze whose object is wedged), and the object is then pushed out of a held grasp.
// The residual is relative to the free motion, which a saturated finger makes large: at 1e-8 a
// contact kept from closing still closed at ~3 um/s, enough to close a held grasp's last
// microns within a 2 s pull; 1e-10 costs a held glass 4 more sweeps a step.
constexpr double kSolverTolerance = 1e-10;
constexpr int kMaxSolverIterations = 5000;
constexpr int kPushOutIterations = 100;

// How much faster than its gap allows any contact or limit closes at velocity v (mm/s or rad/s;
// 0 when none does).
double overclosing(const Constraints& constraints, const VectorX& v) {
  double worst = 0.0;
  for (Eigen::Index row = 0; row < constraints.G.rows(); row += 3) {
    worst =
        std::max(worst, -(constraints.G.row(row).dot(v) + std::max(constraints.offset[row], 0.0)));
  }
  return worst;
}

// The step's motion without constraint impulses, and what the constraints need of it.
struct FreeMotion {
  Eigen::LDLT<MatrixX> solver;  // of the mass matrix with the implicit gains
  VectorX velocity;
  MatrixX MinvGt;  // the solver applied to the constraints' G^T (empty without constraints)
};

FreeMotion freeMotion(const MassAndForces& dynamics, const VectorX& passive_damping,
                      const std::vector<Controller>& controllers, const VectorX& u, double h,
                      const Constraints* constraints = nullptr) {
  VectorX f = dynamics.f;
  VectorX damping = passive_damping;
  for (const Controller& controller : controllers) controller.addTo(f, damping, h);
  MatrixX effective = dynamics.M;
  effective.diagonal() += damping;
  // Coordinates nothing with mass hangs on (a DOF that only moves massless parts) keep a unit
  // mass so the system stays solvable; they move only as their forces say.
  for (Eigen::Index i = 0; i < effective.rows(); ++i) {
    if (effective(i, i) <= 0.0) effective(i, i) = 1.0;
  }
  FreeMotion motion{Eigen::LDLT<MatrixX>(effective), {}, {}};
  motion.velocity = motion.solver.solve(dynamics.M * u + h * f);
  if (constraints) motion.MinvGt = motion.solver.solve(constraints->G.transpose());
  return motion;
}

// The contact and limit impulses of the step (Siconos), from `start`.
dynamics::FrictionContactSolution solveContacts(const World& world, const Constraints& constraints,
                                                const VectorX& offset, FreeMotion& motion,
                                                const VectorX& start, int max_iterations,
                                                StepReport& report) {
  if (motion.MinvGt.size() == 0) motion.MinvGt = motion.solver.solve(constraints.G.transpose());
  MatrixX W = constraints.G * motion.MinvGt;
  const int count = static_cast<int>(constraints.mu.size());
  for (int c = 0; c < count; ++c) W(3 * c, 3 * c) += constraints.compliance[c];
  for (const int row : constraints.limitRows) {  // frictionless: tangents carry nothing
    W(row + 1, row + 1) = W(row + 2, row + 2) = 1.0;
  }
  const VectorX q = constraints.G * motion.velocity + offset;
  const bool pushes_out = offset.minCoeff() < 0.0;
  dynamics::FrictionContactSolution solution = dynamics::solveFrictionContact(
      W, q, constraints.mu, start, kSolverTolerance, max_iterations,
      pushes_out ? dynamics::ContactSolverMethod::GaussSeidel
                 : dynamics::ContactSolverMethod::NewtonThenGaussSeidel);
  report.solverIterations += solution.iterations;
  report.solverError = solution.error;
  // Push-out requests may be more than the bodies can do; the caller then asks for less.
  if (!solution.solved && !pushes_out) {
    throw DynamicsError(fmt::format("at t = {:.4f} s, the contact problem ({} contacts, {} "
                                    "joint limits) could not be solved: Siconos {} stopped at "
                                    "residual {:.3g}",
                                    world.time(), constraints.contacts, constraints.limits,
                                    solution.solver, solution.error),
                        dynamicStateJson(world));
  }
  return solution;
}

// How far apart the linearised motion must leave a pair's contacts for the step to be taken
// as not having brought the pair into collision without asking FCL.
constexpr double kSurelyApart = 0.02;  // mm

// Whether the step (velocity v over h) surely left bodies a and b apart, so that the FCL check
// of the new poses can be skipped (near-touching meshes make it the dearest part of a step).
// Feature pairs farther apart than the pair's search threshold close by at most the step's
// displacement bound; every pair within it is a contact, whose gap the linearised motion
// predicts, and rotation bends a point's path from that prediction by at most the displacement
// times the angle turned.
bool surelyApart(const World& world, const GeneralizedCoordinates& coordinates,
                 const Constraints& constraints, const VectorX& v, double h, const BodyRef& a,
                 const BodyRef& b) {
  const auto threshold = constraints.thresholds.find({a, b});
  if (threshold == constraints.thresholds.end()) return false;
  const double displacement = h * closingSpeedBound(world, coordinates, v, a, b);
  if (!(displacement < threshold->second)) return false;
  const double turn =
      h * ((coordinates.angularJacobian(a) - coordinates.angularJacobian(b)) * v).norm();
  const double bend = displacement * std::min(turn, 1.0);
  for (int c = 0; c < constraints.contacts; ++c) {
    if (!(constraints.bodies[c].first == a) || !(constraints.bodies[c].second == b)) continue;
    const double predicted = constraints.distances[c] + h * constraints.G.row(3 * c).dot(v);
    if (!(predicted - bend >= kSurelyApart)) return false;
  }
  return true;
}

// One attempt at a step of h. Returns nullopt when the new poses make two bodies that were in
// contact interpenetrate (the linearised contacts let an edge or a corner through); the world is
// then unchanged and the caller splits the step.
std::optional<StepReport> tryStep(World& world, double h, std::pair<BodyRef, BodyRef>& offending) {
  // Nothing below changes the world until the step has succeeded, so an error's state (taken
  // when it is thrown) is the state before the step.
  const GeneralizedCoordinates coordinates(world);
  const int n = coordinates.size();
  StepReport report;
  if (n == 0) {
    world.setTime(world.time() + h);
    report.time = world.time();
    return report;
  }
  const VectorX u = currentVelocities(world, coordinates);
  checkVelocities(world, coordinates, u);

  MassAndForces dynamics = massAndForces(world, coordinates, u);
  VectorX damping = VectorX::Zero(n);
  std::vector<SetPoints> set_points;
  std::vector<Controller> controllers;
  addJointForces(world, coordinates, u, dynamics.robotWeight, h, set_points, controllers,
                 dynamics.f, damping);
  FreeMotion motion = freeMotion(dynamics, damping, controllers, u, h);

  Constraints constraints(n);
  addContacts(world, coordinates, u, motion.velocity, h, constraints);
  addJointLimits(world, coordinates, u, h, constraints);
  report.contacts = constraints.contacts;
  report.jointLimits = constraints.limits;

  VectorX velocity = motion.velocity;
  std::vector<ContactImpulse> impulses;
  std::vector<bool> pushed(world.bodies().size(), false);
  if (constraints.G.rows() > 0) {
    VectorX start = warmStart(world, constraints);
    dynamics::FrictionContactSolution solution;
    // A controller below maxEffort acts as a stiff implicit spring, which contacts could load far
    // beyond maxEffort (a finger pressed back by the object it squeezes). Such controllers
    // saturate and the step is solved again, until every controller's force is what it can give.
    // Contacts inside the resting separation are pushed back out to it, unless the bodies cannot
    // all move apart (an object wedged between fingers that are fixed or pushing): then they are
    // only kept from closing, which standing still always satisfies.
    VectorX offset = constraints.offset;
    for (int pass = 0;; ++pass) {
      const bool push_out = offset.minCoeff() < 0.0;
      solution = solveContacts(world, constraints, offset, motion, start,
                               push_out ? kPushOutIterations : kMaxSolverIterations, report);
      velocity = motion.velocity + motion.MinvGt * solution.reaction;
      if (push_out &&
          (!solution.solved || overclosing(constraints, velocity) > kClosingTolerance)) {
        offset = offset.cwiseMax(0.0);
        start = solution.reaction;
        continue;
      }
      bool changed = false;
      for (Controller& controller : controllers)
        changed = controller.saturateAt(velocity[controller.coordinate], h) || changed;
      if (!changed || pass == kMaxControllerPasses) break;
      motion = freeMotion(dynamics, damping, controllers, u, h, &constraints);
      start = solution.reaction;
    }
    impulses = contactImpulses(constraints, solution.reaction);
    for (int c = 0; c < constraints.contacts; ++c) {
      if (solution.reaction[3 * c] <= 0.0) continue;
      ++report.activeContacts;
      for (const BodyRef& ref : {constraints.bodies[c].first, constraints.bodies[c].second}) {
        if (ref.kind == BodyRef::Kind::Body) pushed[ref.index] = true;
      }
    }
  }
  checkVelocities(world, coordinates, velocity);
  World next = world.clone();
  for (int r = 0; r < next.robotCount(); ++r) {
    if (set_points[r].targets.empty()) continue;
    next.setDofTargets(r, set_points[r].targets);
    next.setDofReferences(r, set_points[r].references);
  }
  integrate(next, coordinates, velocity, h, pushed);
  dynamics::updateBreakawayClutches(world, next, impulses, h);
  next.setLastImpulses(std::move(impulses));
  // Only bodies that had contacts can have reached each other within the step (the contact
  // margins bound the closing speed), and a body the step's contacts pushed beyond its margin
  // with another: the margins bound free motion, and a squeeze that gives way can shoot an object
  // out between the fingers (a Barrett's mug reached 1.6 m/s within a step, towards a palm 0.9 mm
  // away). Links move as their joints drive them; checking every link pair whose bound outran
  // its margin cost the Robotiq 2F-85's validation 12 % (its linkage's bars, always near).
  std::set<std::pair<BodyRef, BodyRef>> touching(constraints.bodies.begin(),
                                                 constraints.bodies.end());
  const auto pushedBody = [&](const BodyRef& ref) {
    return ref.kind == BodyRef::Kind::Body && pushed[ref.index];
  };
  for (const auto& [pair, threshold] : constraints.thresholds) {
    if (!pushedBody(pair.first) && !pushedBody(pair.second)) continue;
    if (!(h * closingSpeedBound(world, coordinates, velocity, pair.first, pair.second) < threshold))
      touching.insert(pair);
  }
  // A pair that already touched as the step began (FCL counts touching surfaces as colliding) is
  // not the step's doing.
  for (const auto& [a, b] : touching) {
    if (surelyApart(world, coordinates, constraints, velocity, h, a, b)) continue;
    if (collide(next, a, b) && !collide(world, a, b)) {
      offending = {a, b};
      return std::nullopt;
    }
  }
  next.setTime(world.time() + h);
  world = std::move(next);
  report.time = world.time();
  return report;
}

// GraspIt!'s remedy for a step that ends in collision: bisect it.
constexpr int kMaxBisections = 6;

StepReport bisectingStep(World& world, double h, int depth) {
  std::pair<BodyRef, BodyRef> offending;
  if (std::optional<StepReport> report = tryStep(world, h, offending)) return *report;
  if (depth == kMaxBisections) {
    throw DynamicsError(fmt::format("at t = {:.4f} s, '{}' and '{}' interpenetrate even with the "
                                    "step cut to {:.3g} s",
                                    world.time(), describe(world, offending.first),
                                    describe(world, offending.second), h),
                        dynamicStateJson(world));
  }
  bisectingStep(world, h / 2.0, depth + 1);
  return bisectingStep(world, h / 2.0, depth + 1);
}

// Bodies placed inside one another with no faces crossing (coplanar sides, or one object loaded
// twice at one pose) pass the step's test of crossing triangles; a simulation from there would
// report them at rest, inside each other. Objects and obstacles only: a hand's links meet at its
// joints by design.
void refuseSharedVolume(const World& world) {
  const auto& bodies = world.bodies();
  for (const BodyPair& pair : nearbyPairs(world, 0.0)) {
    if (pair.first.kind != BodyRef::Kind::Body || pair.second.kind != BodyRef::Kind::Body) continue;
    if (!bodies[pair.first.index].isDynamic() && !bodies[pair.second.index].isDynamic()) continue;
    if (sharesVolume(world, pair.first, pair.second, kSharedVolumeDepth)) {
      throw DynamicsError(fmt::format("at t = {:.4f} s, '{}' and '{}' interpenetrate: a point of "
                                      "one lies more than {} mm inside the other",
                                      world.time(), describe(world, pair.first),
                                      describe(world, pair.second), kSharedVolumeDepth),
                          dynamicStateJson(world));
    }
  }
}

}  // namespace

StepReport step(World& world, double h) {
  if (!(h > 0.0 && h <= kMaxTimeStep)) {
    throw Error(fmt::format("time step {} s is outside (0, {}] s", h, kMaxTimeStep));
  }
  if (!world.gravity().allFinite()) throw Error("gravity is not a finite vector");
  return bisectingStep(world, h, 0);
}

SimulateResult simulate(World& world, const SimulateRequest& request) {
  if (!(request.seconds >= 0.0 && std::isfinite(request.seconds))) {
    throw Error(fmt::format("simulated time {} s must be a finite number >= 0", request.seconds));
  }
  if (!(request.dt >= kMinTimeStep && request.dt <= kMaxTimeStep)) {
    throw Error(fmt::format("time step {} s is outside [{}, {}] s", request.dt, kMinTimeStep,
                            kMaxTimeStep));
  }
  // Checked where a world starts (time 0), not before each of grasp validation's trials, which
  // continue a settled world: the check walks every triangle of the objects it compares.
  if (world.time() == 0.0) refuseSharedVolume(world);
  SimulateResult result;
  const double end = world.time() + request.seconds;
  // Steps until the end time, the last one shortened to land on it.
  while (world.time() < end - 1e-12) {
    const double h = std::min(request.dt, end - world.time());
    result.last = step(world, h < request.dt * 1e-6 ? request.dt : h);
    ++result.steps;
    if (request.onStep && !request.onStep(world, result.last)) {
      result.stoppedEarly = true;
      break;
    }
  }
  result.time = world.time();
  return result;
}

}  // namespace graspkit
