#include "graspkit/model/closing_direction.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <set>

namespace graspkit {

namespace {

// A link's geometric centre in the world (its origin when it has no geometry).
Vector3 tipPoint(const Robot& robot, int chain) {
  const KinematicChain& c = robot.model().chains[chain];
  const int last = static_cast<int>(c.links.size()) - 1;
  const Transform& pose = robot.linkPose(chain, last);
  const auto& mesh = c.links[last].body ? c.links[last].body->mesh : nullptr;
  if (!mesh || mesh->vertices.empty()) return pose.translation();
  Vector3 lo = mesh->vertices.front(), hi = lo;
  for (const Vector3& v : mesh->vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  return pose * Vector3(0.5 * (lo + hi));
}

}  // namespace

std::vector<int> inferClosingDirections(const RobotModel& model) {
  std::vector<int> out(model.dofs.size(), 1);
  std::vector<int> tips;  // chains that end in a link
  for (std::size_t c = 0; c < model.chains.size(); ++c)
    if (!model.chains[c].links.empty()) tips.push_back(static_cast<int>(c));
  if (tips.empty()) return out;
  Robot robot(std::make_shared<const RobotModel>(model));
  // Two postures for the other DOFs: their defaults and mid-range.
  std::vector<std::vector<double>> contexts(2);
  for (const Dof& dof : model.dofs) {
    contexts[0].push_back(dof.defaultValue);
    contexts[1].push_back(0.5 * (dof.min + dof.max));
  }
  constexpr double kFractions[] = {0.1, 0.3, 0.5, 0.7, 0.9};
  // How far (of the tips' reach from the hand's origin) the tips must move away: a distal joint
  // that swings its short link past the centre is no evidence.
  constexpr double kEvidence = 0.1;
  for (std::size_t d = 0; d < model.dofs.size(); ++d) {
    const Dof& dof = model.dofs[d];
    if (!(dof.max > dof.min)) continue;
    // A range even about zero prefers neither side (a finger that bends both ways).
    if (std::abs(dof.max + dof.min) < 0.1 * (dof.max - dof.min)) continue;
    std::set<int> moved;
    for (const int c : tips)
      for (const Joint& joint : model.chains[c].joints)
        if (joint.dof == static_cast<int>(d)) moved.insert(c);
    if (moved.empty()) continue;
    // Opens towards the upper limit only when, in every context, the moved tips go steadily
    // farther from the grasp centre as the DOF rises, by at least 10 % of their reach.
    bool opens_upwards = true;
    for (const std::vector<double>& context : contexts) {
      robot.setDofValues(context);
      Vector3 centre = Vector3::Zero();
      for (const int c : tips) centre += tipPoint(robot, c);
      centre /= static_cast<double>(tips.size());
      double previous = -1.0, first = 0.0, reach = 0.0;
      for (const double f : kFractions) {
        std::vector<double> values = context;
        values[d] = dof.min + f * (dof.max - dof.min);
        robot.setDofValues(values);
        double sum = 0.0;
        for (const int c : moved) {
          sum += (tipPoint(robot, c) - centre).norm();
          reach = std::max(reach, (tipPoint(robot, c) - robot.pose().translation()).norm());
        }
        if (previous < 0.0) first = sum;
        if (previous >= 0.0 && sum <= previous) opens_upwards = false;
        previous = sum;
      }
      if (previous - first < kEvidence * reach) opens_upwards = false;
      if (!opens_upwards) break;
    }
    if (opens_upwards) out[d] = -1;
  }
  return out;
}

void setClosingDirections(RobotModel& robot, const std::vector<int>& directions) {
  for (std::size_t d = 0; d < robot.dofs.size() && d < directions.size(); ++d) {
    Dof& dof = robot.dofs[d];
    dof.defaultVelocity = (directions[d] < 0 ? -1.0 : 1.0) * std::abs(dof.defaultVelocity);
  }
}

}  // namespace graspkit
