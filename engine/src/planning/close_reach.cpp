// The branch and bound over joint-space boxes described in graspkit/planning/close_reach.hpp.

#include "graspkit/planning/close_reach.hpp"

#include <algorithm>
#include <cmath>

#include "graspkit/collision/collision.hpp"
#include "graspkit/grasp/robot_type.hpp"
#include "graspkit/model/robot.hpp"
#include "graspkit/model/world.hpp"
#include "graspkit/planning/planning_scene.hpp"

namespace graspkit {
namespace {

// Boxes tried per chain before a close is left to run. On plannerMug's autograsp-quality search,
// 32 left 266 of 3,000 closes to run, 64 left 226 and 128 left 215 at half again the bound's
// cost; the search was fastest at 64.
constexpr int kBoxBudget = 64;
// Added to every reach, mm: above the rounding of the kinematics and of Embree's single-precision
// culling (which RayScene pads for) by orders of magnitude, and far below what a ball misses by.
constexpr double kMargin = 1e-3;
// Each link's vertices are split this many times for its balls (up to 2^kSplits balls).
constexpr int kSplits = 2;

struct Ball {
  Vector3 centre;
  double radius;
};

// The ball around the points' box centre holding every point.
Ball ballAround(const std::vector<Vector3>& points) {
  Eigen::AlignedBox3d box;
  for (const Vector3& v : points) box.extend(v);
  Ball ball{box.center(), 0.0};
  for (const Vector3& v : points) ball.radius = std::max(ball.radius, (v - ball.centre).norm());
  return ball;
}

// Balls that together hold every vertex: the vertices split in two across the longest side of
// their box, `depth` times. A long finger link in one ball is mostly empty space; in four, the
// bound proves far more postures clear.
void coveringBalls(const std::vector<Vector3>& points, int depth, std::vector<Ball>& balls) {
  if (points.empty()) return;
  Eigen::AlignedBox3d box;
  for (const Vector3& v : points) box.extend(v);
  if (depth == 0 || points.size() < 8) {
    balls.push_back(ballAround(points));
    return;
  }
  Eigen::Index axis;
  box.sizes().maxCoeff(&axis);
  const double middle = box.center()[axis];
  std::vector<Vector3> low, high;
  for (const Vector3& v : points) (v[axis] < middle ? low : high).push_back(v);
  coveringBalls(low, depth - 1, balls);
  coveringBalls(high, depth - 1, balls);
}

// How far a joint's DH frame can lie from the one before it: |(a, d + value)| over its range.
double longestTranslation(const Joint& joint, const Dof& dof) {
  double d = std::abs(joint.d);
  if (joint.type == JointType::Prismatic)
    d += std::abs(joint.ratio) * std::max(std::abs(dof.min), std::abs(dof.max));
  return std::hypot(joint.a, d);
}

struct Interval {
  double lo, hi;
};

// The values each joint of `chain` can take during the close, from the hand as it stands.
std::vector<Interval> jointIntervals(const Robot& hand, int chain, CloseMotion motion) {
  const RobotModel& model = hand.model();
  const KinematicChain& c = model.chains[static_cast<std::size_t>(chain)];
  std::vector<Interval> intervals;
  for (std::size_t local = 0; local < c.joints.size(); ++local) {
    const Joint& joint = c.joints[local];
    const Dof& dof = model.dofs[static_cast<std::size_t>(joint.dof)];
    double from = hand.dofValues()[static_cast<std::size_t>(joint.dof)];
    double to = from;
    if (motion == CloseMotion::WithinDofLimits) {
      from = dof.min;
      to = dof.max;
    } else if (dof.defaultVelocity != 0.0) {
      to = dof.defaultVelocity > 0 ? dof.max : dof.min;
    }
    // A joint broken away holds a value of its own, which the interval keeps.
    const double now = hand.jointValues()[static_cast<std::size_t>(c.firstJoint) + local];
    const double a = joint.ratio * from, b = joint.ratio * to;
    intervals.push_back({std::min({a, b, now}), std::max({a, b, now})});
  }
  return intervals;
}

class ChainSearch {
 public:
  ChainSearch(const PlanningScene& scene, const CloseReach& reach, int chain, double threshold)
      : scene_(scene),
        balls_(reach.chains[static_cast<std::size_t>(chain)]),
        chain_(scene.hand().model().chains[static_cast<std::size_t>(chain)]),
        base_(scene.hand().pose() * chain_.base),
        threshold_(threshold) {}

  // Whether some posture in the box [lo, hi] may bring a link within the threshold.
  bool mayTouch(std::vector<Interval> box) {
    std::vector<double> centre(box.size());
    for (std::size_t j = 0; j < box.size(); ++j) centre[j] = 0.5 * (box[j].lo + box[j].hi);
    linkPoses(chain_, base_, centre, poses_);
    const LinkBall* failing = nullptr;
    for (const LinkBall& ball : balls_) {
      double drift = 0.0;
      for (std::size_t j = 0; j < box.size(); ++j)
        drift += 0.5 * (box[j].hi - box[j].lo) * ball.levers[j];
      const double reach = ball.radius + drift + threshold_ + kMargin;
      if (!scene_.nearestObjectPoint(poses_[ball.link] * ball.centre, reach)) continue;
      // A link that does not move over the box is where it stands: measured exactly.
      if (drift == 0.0 && !withinDistance(scene_.world(), linkRef(ball.link), scene_.object(),
                                          threshold_ + kMargin))
        continue;
      failing = &ball;
      break;
    }
    if (!failing) return false;
    if (--budget_ <= 0) return true;
    // Split across the joint that moves the failing ball most.
    std::size_t widest = 0;
    double most = 0.0;
    for (std::size_t j = 0; j < box.size(); ++j) {
      const double moves = (box[j].hi - box[j].lo) * failing->levers[j];
      if (moves > most) {
        most = moves;
        widest = j;
      }
    }
    if (most == 0.0) return true;
    std::vector<Interval> upper = box;
    box[widest].hi = upper[widest].lo = centre[widest];
    return mayTouch(std::move(box)) || mayTouch(std::move(upper));
  }

 private:
  using LinkBall = CloseReach::LinkBall;

  BodyRef linkRef(std::size_t link) const {
    const auto chain = static_cast<int>(&chain_ - scene_.hand().model().chains.data());
    return BodyRef::robotLink(scene_.robot(), {chain, static_cast<int>(link)});
  }

  const PlanningScene& scene_;
  const std::vector<LinkBall>& balls_;
  const KinematicChain& chain_;
  Transform base_;
  double threshold_;
  int budget_ = kBoxBudget;
  std::vector<Transform> poses_;
};

}  // namespace

CloseReach closeReachOf(std::shared_ptr<const RobotModel> model) {
  CloseReach reach;
  if (model->palm && model->palm->mesh && !model->palm->mesh->empty()) {
    const Ball palm = ballAround(model->palm->mesh->vertices);
    reach.palmCentre = palm.centre;
    reach.palmRadius = palm.radius;
  }
  for (const KinematicChain& chain : model->chains) {
    std::vector<CloseReach::LinkBall> balls;
    for (std::size_t l = 0; l < chain.links.size(); ++l) {
      const Link& link = chain.links[l];
      if (!link.body || !link.body->mesh || link.body->mesh->empty()) continue;
      std::vector<Ball> covering;
      coveringBalls(link.body->mesh->vertices, kSplits, covering);
      for (const Ball& b : covering) {
        CloseReach::LinkBall ball;
        ball.link = l;
        ball.centre = b.centre;
        ball.radius = b.radius;
        ball.levers.assign(chain.joints.size(), 0.0);
        // From the link back to the chain's base: the lever of joint j is the ball centre's
        // farthest distance from the frame joint j turns about (its axis passes through it).
        double tail = (link.frame * b.centre).norm();
        for (int j = link.lastJoint; j >= 0; --j) {
          const Joint& joint = chain.joints[static_cast<std::size_t>(j)];
          tail += longestTranslation(joint, model->dofs[static_cast<std::size_t>(joint.dof)]);
          ball.levers[static_cast<std::size_t>(j)] =
              joint.type == JointType::Prismatic ? 1.0 : tail;
        }
        balls.push_back(std::move(ball));
      }
    }
    reach.chains.push_back(std::move(balls));
  }
  reach.model = std::move(model);
  return reach;
}

bool closeMayTouchObject(const PlanningScene& scene, const CloseReach& reach, double threshold) {
  const Robot& hand = scene.hand();
  const std::shared_ptr<const RobotType>& type = hand.model().robotType;
  const CloseMotion motion = type ? type->closeMotion() : CloseMotion::TowardClosingEnds;
  if (motion == CloseMotion::Unknown) return true;
  for (const Connection& connection : scene.world().connections())
    if (connection.parentRobot == scene.robot()) return true;
  // The palm does not move: its ball, then its mesh.
  if (reach.palmRadius >= 0.0 &&
      scene.nearestObjectPoint(hand.pose() * reach.palmCentre,
                               reach.palmRadius + threshold + kMargin) &&
      withinDistance(scene.world(), BodyRef::robotBase(scene.robot()), scene.object(),
                     threshold + kMargin))
    return true;
  for (int c = 0; c < static_cast<int>(reach.chains.size()); ++c) {
    ChainSearch search(scene, reach, c, threshold);
    if (search.mayTouch(jointIntervals(hand, c, motion))) return true;
  }
  return false;
}

}  // namespace graspkit
