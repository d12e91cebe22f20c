#include "graspkit/dataset/dataset_planning.hpp"

#include <optional>

#include "graspkit/base/error.hpp"
#include "graspkit/base/version.hpp"
#include "graspkit/dynamics/grasp_validation.hpp"
#include "graspkit/io/graspit/body_file.hpp"
#include "graspkit/io/graspit/world_file.hpp"
#include "graspkit/planning/hand_configuration.hpp"
#include "graspkit/planning/planner.hpp"
#include "graspkit/planning/search_space.hpp"
#include "graspkit/plugin/registry.hpp"

namespace graspkit {
namespace {

// The hand (robot 0) 300 mm above the object (body 0) at the origin.
std::shared_ptr<World> handOverObject(const DatasetRequest& request) {
  auto world = request.loadedHand
                   ? std::make_shared<World>(request.loadedHand->clone())
                   : std::make_shared<World>(loadAnyFile(request.hand, request.load));
  if (world->robotCount() != 1 || !world->bodies().empty())
    throw Error(SourceLocation{request.hand.string()}, "the hand must be a robot file");
  Body object;
  object.model = loadBodyFile(request.object);
  object.kind = BodyKind::Graspable;
  object.name = object.model->name.empty() ? request.object.stem().string() : object.model->name;
  object.filename = request.object;
  world->addBody(object);
  Transform above = Transform::Identity();
  above.translation() = Vector3(0, 0, 300);
  world->setRobotPose(0, above);
  return world;
}

DatasetGrasp datasetGrasp(const PlannedGrasp& g, const std::optional<ValidationResult>& label) {
  const BodyRef object = BodyRef::body(0);  // at the origin: world frame = object frame
  DatasetGrasp d;
  d.pregrasp = g.pose;
  d.grasp = g.closed.pose;
  d.openDofs = g.dofs;
  d.closedDofs = g.closed.dofs;
  d.breakaway = g.closed.breakaway;
  d.epsilon = g.epsilon;
  d.volume = g.volume;
  d.forceClosure = g.forceClosure;
  d.held = label ? (label->held ? 1 : 0) : -1;
  if (label) {
    for (const DirectionResult& r : label->directions) {
      // The object sits at the origin unturned: world directions are the object frame's.
      d.validation.push_back(
          {r.direction, r.held, r.slip, r.turn, r.seconds, !r.failure.empty(), r.tried});
    }
  }
  for (const Contact& c : g.contactList) {
    // The normal points into body1: out of the object when the object is body2.
    const bool object_second = c.body2 == object;
    d.contactPoints.push_back(object_second ? c.position2 : c.position1);
    d.contactNormals.push_back(object_second ? c.normal : Vector3(-c.normal));
  }
  return d;
}

}  // namespace

GraspDataset planGraspDataset(const DatasetRequest& request) {
  if (!request.steps && !request.seconds)
    throw Error("a dataset request needs a budget: steps or seconds");
  const auto world = handOverObject(request);
  PlanningRequest plan;
  plan.world = world;
  plan.robot = 0;
  plan.object = BodyRef::body(0);
  plan.position = parseNamed<PositionSpace>("axis-angle", "position space");
  plan.posture = parseNamed<PostureSpace>("eigen", "posture space");
  plan.energy = "contact";
  plan.seed = request.seed;
  plan.threads = 1;  // datasets are made object by object, side by side: one thread each
  plan.bestListSize = request.grasps;
  plan.options = {{"mode", "restarts"}};
  auto planner = Registry::global().makePlanner("simann", plan);
  PlanningBudget budget;
  budget.steps = request.steps;
  budget.seconds = request.seconds;
  PlanningRun run = runPlanner(*planner, budget);
  finishGrasps(plan, run.grasps, 1);

  std::vector<std::optional<ValidationResult>> labels(run.grasps.size());
  if (request.validate) {
    ValidationRequest validation;
    validation.seconds = request.validateSeconds;
    validation.allDirections = request.validateAllDirections;
    validation.statics = request.validateStatics;
    std::vector<World> worlds;
    for (const PlannedGrasp& g : run.grasps) worlds.push_back(graspWorld(plan, g));
    const auto results = validateGrasps(worlds, 0, 0, validation, 1);
    for (std::size_t i = 0; i < results.size(); ++i) labels[i] = results[i];
  }

  GraspDataset dataset;
  const Body& object = world->bodies()[0];
  dataset.objectFile = request.object.string();
  dataset.objectName = object.name;
  dataset.objectMass = object.model->mass;
  dataset.handFile = request.hand.string();
  dataset.handName = world->robot(0).name();
  dataset.engineVersion = engineVersion();
  dataset.seed = request.seed;
  for (std::size_t i = 0; i < run.grasps.size(); ++i)
    dataset.grasps.push_back(datasetGrasp(run.grasps[i], labels[i]));
  return dataset;
}

World datasetGraspWorld(const DatasetRequest& request, const DatasetGrasp& grasp) {
  World world = handOverObject(request)->clone();
  HandConfiguration closed;
  closed.pose = grasp.grasp;
  closed.dofs = grasp.closedDofs;
  closed.breakaway = grasp.breakaway;
  if (closed.breakaway.empty()) closed.breakaway.resize(world.robot(0).breakaway().size());
  applyHandConfiguration(world, 0, closed);
  return world;
}

}  // namespace graspkit
