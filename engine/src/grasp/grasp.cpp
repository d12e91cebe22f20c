#include "graspkit/grasp/grasp.hpp"

#include <fmt/format.h>

#include "graspkit/base/error.hpp"
#include "graspkit/grasp/autograsp.hpp"
#include "graspkit/grasp/friction_cone.hpp"
#include "graspkit/grasp/quality.hpp"
#include "graspkit/model/world.hpp"

namespace graspkit {

Grasp analyzeGrasp(const World& world, int robot, const BodyRef& object,
                   const GraspRequest& request) {
  world.robot(robot);  // range check before the search
  if (!isValid(world, object)) {
    throw Error(fmt::format("no object {} in the world to grasp", object.index));
  }
  return analyzeGrasp(world, robot, object, robotContacts(world, robot, &object), request);
}

Grasp analyzeGrasp(const World& world, int robot, const BodyRef& object,
                   std::vector<Contact> contacts, const GraspRequest& request) {
  world.robot(robot);
  const BodyModel& model = bodyModel(world, object);  // throws for a bad object
  Grasp grasp;
  grasp.robot = robot;
  grasp.object = object;
  grasp.contacts = std::move(contacts);
  std::vector<Contact> on_object;
  on_object.reserve(grasp.contacts.size());
  for (const Contact& c : grasp.contacts)
    if (c.body2 == object) on_object.push_back(c.mate());
  if (on_object.empty()) {
    grasp.wrenchSpace.failure = "no contacts with the object";
    return grasp;
  }
  const Vector3 cog = bodyPose(world, object) * model.cog;
  grasp.wrenchSpace =
      graspWrenchSpace(graspWrenches(on_object, cog, model.maxRadius), request.wrenchSpace);
  grasp.forceClosure = isForceClosure(grasp.wrenchSpace);
  grasp.epsilon = epsilonQuality(grasp.wrenchSpace);
  grasp.volume = volumeQuality(grasp.wrenchSpace);
  return grasp;
}

}  // namespace graspkit
