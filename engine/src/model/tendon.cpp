#include "graspkit/model/tendon.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "graspkit/base/error.hpp"
#include "graspkit/model/robot.hpp"

namespace graspkit {

namespace {

// GraspIt!'s thresholds: a segment closer to a wrapper's axis than this fraction of the radius
// wraps (the slack stops a wrap point on the surface from triggering again), and the number of
// consecutive wrapping passes on one segment after which it gives up and moves on.
constexpr double kWrapperTolerance = 0.995;
constexpr int kMaxWrapPassesBeforeGivingUp = 11;
// Below this, Bourke's closest-points construction treats a segment as a point or two lines as
// parallel (GraspIt!'s value, mm-based).
constexpr double kDegenerate = 1e-5;

const Transform& poseOf(const Robot& robot, const LinkRef& link) {
  return link.isBase() ? robot.pose() : robot.linkPose(link);
}

struct ClosestPoints {
  double onFirst;   // parameter along p1-p2
  double onSecond;  // parameter along p3-p4
  Vector3 first;
  Vector3 second;
};

// Closest points of the infinite lines p1-p2 and p3-p4 (Paul Bourke's construction); none when
// either pair of points coincides or the lines are parallel.
std::optional<ClosestPoints> closestPointsOfLines(const Vector3& p1, const Vector3& p2,
                                                  const Vector3& p3, const Vector3& p4) {
  const Vector3 p13 = p1 - p3;
  const Vector3 p43 = p4 - p3;
  const Vector3 p21 = p2 - p1;
  if (p43.cwiseAbs().maxCoeff() < kDegenerate || p21.cwiseAbs().maxCoeff() < kDegenerate)
    return std::nullopt;
  const double d4321 = p43.dot(p21);
  const double d4343 = p43.dot(p43);
  const double denominator = p21.dot(p21) * d4343 - d4321 * d4321;
  if (std::abs(denominator) < kDegenerate) return std::nullopt;
  const double d1343 = p13.dot(p43);
  const double mua = (d1343 * d4321 - p13.dot(p21) * d4343) / denominator;
  const double mub = (d1343 + d4321 * mua) / d4343;
  return ClosestPoints{mua, mub, p1 + mua * p21, p3 + mub * p43};
}

// Where segment a-b must be rerouted around `wrapper` (a point on its surface, wrapper link
// frame), or none when the segment clears it.
std::optional<Vector3> wrapPoint(const Robot& robot, const TendonWrapper& wrapper, const Vector3& a,
                                 const Vector3& b) {
  const Transform& pose = poseOf(robot, wrapper.link);
  const Vector3 half_axis = 0.5 * wrapper.length * wrapper.orientation;
  const auto closest = closestPointsOfLines(a, b, pose * (wrapper.position - half_axis),
                                            pose * (wrapper.position + half_axis));
  if (!closest) return std::nullopt;
  if (closest->onSecond < 0.0 || closest->onSecond > 1.0) return std::nullopt;
  // At the ends (or beyond) the segment's nearest point is an insertion point: no wrap.
  if (closest->onFirst <= 0.0 || closest->onFirst >= 1.0) return std::nullopt;
  Vector3 radial = closest->first - closest->second;
  const double distance = radial.norm();
  if (distance >= kWrapperTolerance * wrapper.radius) return std::nullopt;
  if (distance > 0.0) {
    radial /= distance;
  } else {
    // The segment crosses the axis: any radial direction is as good; take the one normal to
    // both (GraspIt! divides by zero here).
    radial = (b - a).cross(pose.linear() * wrapper.orientation).normalized();
  }
  return pose.inverse() * (closest->second + wrapper.radius * radial);
}

std::optional<TendonPathPoint> wrapAround(const Robot& robot, int wrapper_index, const Vector3& a,
                                          const Vector3& b) {
  const TendonWrapper& wrapper = robot.model().tendonWrappers[wrapper_index];
  const auto local = wrapPoint(robot, wrapper, a, b);
  if (!local) return std::nullopt;
  TendonPathPoint point;
  point.link = wrapper.link;
  point.local = *local;
  point.world = poseOf(robot, wrapper.link) * *local;
  point.wrapper = wrapper_index;
  return point;
}

bool segmentNeedsWrap(const Robot& robot, const Tendon& tendon, const Vector3& a,
                      const Vector3& b) {
  for (const TendonWrapper& wrapper : robot.model().tendonWrappers)
    if (!wrapper.exempts(tendon.name) && wrapPoint(robot, wrapper, a, b)) return true;
  return false;
}

// Walks the route segment by segment; a segment that cuts into wrappers gets one wrap point per
// such wrapper, in wrapper order, and is checked again from the same start.
void addWrapPoints(const Robot& robot, const Tendon& tendon, std::vector<TendonPathPoint>& route) {
  const auto& wrappers = robot.model().tendonWrappers;
  std::size_t i = 0;
  int passes = 0;
  while (i + 1 < route.size()) {
    const Vector3 a = route[i].world;
    const Vector3 b = route[i + 1].world;
    std::size_t insert_at = i + 1;
    bool wrapped = false;
    for (std::size_t w = 0; w < wrappers.size(); ++w) {
      if (wrappers[w].exempts(tendon.name)) continue;
      if (auto point = wrapAround(robot, static_cast<int>(w), a, b)) {
        route.insert(route.begin() + static_cast<std::ptrdiff_t>(insert_at++), *point);
        wrapped = true;
      }
    }
    if (wrapped && passes++ >= kMaxWrapPassesBeforeGivingUp) wrapped = false;
    if (!wrapped) {
      ++i;
      passes = 0;
    }
  }
}

// Drops wrap points whose neighbours would run clear of every wrapper without them.
void removeNeedlessWrapPoints(const Robot& robot, const Tendon& tendon,
                              std::vector<TendonPathPoint>& route) {
  for (std::size_t i = 1; i + 1 < route.size();) {
    if (route[i].isWrapPoint() &&
        !segmentNeedsWrap(robot, tendon, route[i - 1].world, route[i + 1].world)) {
      route.erase(route.begin() + static_cast<std::ptrdiff_t>(i));
    } else {
      ++i;
    }
  }
}

double polylineLength(const std::vector<TendonPathPoint>& route) {
  double length = 0.0;
  for (std::size_t i = 1; i < route.size(); ++i)
    length += (route[i].world - route[i - 1].world).norm();
  return length;
}

const Tendon& tendonAt(const Robot& robot, int tendon) {
  const auto& tendons = robot.model().tendons;
  if (tendon < 0 || tendon >= static_cast<int>(tendons.size()))
    throw Error(fmt::format("robot '{}' has {} tendons; there is no tendon {}", robot.name(),
                            tendons.size(), tendon));
  return tendons[tendon];
}

}  // namespace

bool TendonWrapper::exempts(const std::string& tendon) const {
  return std::find(exemptions.begin(), exemptions.end(), tendon) != exemptions.end();
}

TendonPath tendonPath(const Robot& robot, int tendon_index) {
  const Tendon& tendon = tendonAt(robot, tendon_index);
  TendonPath path;
  for (std::size_t i = 0; i < tendon.insertionPoints.size(); ++i) {
    const TendonInsertionPoint& insertion = tendon.insertionPoints[i];
    TendonPathPoint point;
    point.link = insertion.link;
    point.local = insertion.position;
    point.world = poseOf(robot, insertion.link) * insertion.position;
    point.insertionPoint = static_cast<int>(i);
    path.points.push_back(point);
  }
  addWrapPoints(robot, tendon, path.points);
  removeNeedlessWrapPoints(robot, tendon, path.points);
  path.length = polylineLength(path.points);
  return path;
}

double tendonLength(const Robot& robot, const TendonPath& path) {
  double length = 0.0;
  for (std::size_t i = 1; i < path.points.size(); ++i) {
    const TendonPathPoint& a = path.points[i - 1];
    const TendonPathPoint& b = path.points[i];
    length += (poseOf(robot, b.link) * b.local - poseOf(robot, a.link) * a.local).norm();
  }
  return length;
}

double tendonRestLength(const Robot& robot, int tendon_index) {
  const Tendon& tendon = tendonAt(robot, tendon_index);
  if (tendon.restLength) return *tendon.restLength;
  // GraspIt! takes the length when the hand is loaded, at its default DOF values.
  const Robot at_rest(robot.modelPtr());
  const double length = tendonPath(at_rest, tendon_index).length;
  return length - tendon.preTensionLength.value_or(0.0);
}

double tendonForce(const Tendon& tendon, double length, double rest_length, double active_force) {
  const double active = std::max(active_force, 0.0);
  if (!tendon.passiveForce) return active;
  // Only a stretched tendon pulls; a slack one adds nothing.
  const double passive = std::max(length - rest_length, 0.0) * tendon.stiffness;
  return active + passive;
}

std::vector<Vector3> insertionForces(const TendonPath& path, double force) {
  const auto& points = path.points;
  std::vector<Vector3> forces(points.size(), Vector3::Zero());
  for (std::size_t i = 0; i < points.size(); ++i) {
    Vector3 direction = Vector3::Zero();
    if (i > 0) direction += (points[i - 1].world - points[i].world).normalized();
    if (i + 1 < points.size()) direction += (points[i + 1].world - points[i].world).normalized();
    forces[i] = force * direction;
  }
  return forces;
}

Eigen::VectorXd tendonJointTorques(const Robot& robot, const TendonPath& path, double force) {
  const RobotModel& model = robot.model();
  Eigen::VectorXd torques = Eigen::VectorXd::Zero(model.jointCount());
  const std::vector<Vector3> forces = insertionForces(path, force);
  const auto joint_values = robot.jointValues();
  for (std::size_t i = 0; i < path.points.size(); ++i) {
    const TendonPathPoint& point = path.points[i];
    if (point.link.isBase()) continue;  // the palm hangs from no joint
    const KinematicChain& chain = model.chains[point.link.chain];
    const Transform chain_base = robot.pose() * chain.base;
    const auto frames =
        jointFrames(chain, chain_base, joint_values.subspan(chain.firstJoint, chain.joints.size()));
    const Vector3 at = poseOf(robot, point.link) * point.local;
    const int last_joint = chain.links[point.link.link].lastJoint;
    for (int j = 0; j <= last_joint; ++j) {
      // Joint j moves about (or along) the z axis of the frame before its DH transform.
      const Transform& before = j == 0 ? chain_base : frames[j - 1];
      const Vector3 axis = before.linear().col(2);
      const double generalised = chain.joints[j].type == JointType::Revolute
                                     ? axis.dot((at - before.translation()).cross(forces[i]))
                                     : axis.dot(forces[i]);
      torques[chain.firstJoint + j] += generalised;
    }
  }
  return torques;
}

Eigen::VectorXd tendonJointTorques(const Robot& robot, int tendon, double force) {
  return tendonJointTorques(robot, tendonPath(robot, tendon), force);
}

}  // namespace graspkit
