// Autograsp and grasp analysis.

#include <fmt/format.h>

#include "c_api_support.hpp"
#include "graspkit/grasp/autograsp.hpp"

using namespace graspkit;
using namespace graspkit::c_api;

namespace {

graspkit_contact toContact(const Contact& c) {
  graspkit_contact out{};
  out.link = toRef(c.body1);
  out.body = toRef(c.body2);
  for (int i = 0; i < 3; ++i) {
    out.position[i] = c.position1[i];
    out.normal[i] = c.normal[i];
  }
  out.mu = c.mu;
  out.torsion = c.torsion;
  switch (c.model) {
    case ContactModel::Frictionless:
      out.model = GRASPKIT_CONTACT_FRICTIONLESS;
      break;
    case ContactModel::PointWithFriction:
      out.model = GRASPKIT_CONTACT_POINT;
      break;
    case ContactModel::SoftFinger:
      out.model = GRASPKIT_CONTACT_SOFT_FINGER;
      break;
  }
  return out;
}

const Grasp& graspOf(const graspkit_grasp* grasp) {
  return require(grasp, "grasp")->grasp;
}

}  // namespace

extern "C" {

graspkit_status graspkit_robot_autograsp(graspkit_world* world, int32_t robot,
                                         graspkit_autograsp_result* result) {
  return guarded([&] {
    World& w = require(world, "world")->world;
    checkedRobot(w, robot);
    const AutoGraspResult closed = autoGrasp(w, robot);
    if (result) {
      result->end = static_cast<int32_t>(closed.end);
      result->steps = closed.iterations;
    }
  });
}

graspkit_status graspkit_grasp_analyze(const graspkit_world* world, int32_t robot, int32_t object,
                                       int32_t wrench_space, graspkit_grasp** grasp) {
  return guarded([&] {
    const World& w = require(world, "world")->world;
    require(grasp, "grasp");
    checkedRobot(w, robot);
    checkedBody(w, object);
    GraspRequest request;
    switch (wrench_space) {
      case GRASPKIT_GWS_L1:
        request.wrenchSpace.type = WrenchSpaceType::L1;
        break;
      case GRASPKIT_GWS_LINF:
        request.wrenchSpace.type = WrenchSpaceType::LInfinity;
        break;
      default:
        throw Failure{GRASPKIT_ERROR_INVALID_ARGUMENT,
                      fmt::format("wrench space {} is not GRASPKIT_GWS_L1 or GRASPKIT_GWS_LINF",
                                  static_cast<int>(wrench_space))};
    }
    *grasp = new graspkit_grasp{analyzeGrasp(w, robot, BodyRef::body(object), request)};
  });
}

graspkit_status graspkit_grasp_quality(const graspkit_grasp* grasp, graspkit_quality* quality) {
  return guarded([&] {
    const Grasp& g = graspOf(grasp);
    require(quality, "quality");
    quality->epsilon = g.epsilon;
    quality->volume = g.volume;
    quality->force_closure = g.forceClosure ? 1 : 0;
  });
}

graspkit_status graspkit_grasp_contact_count(const graspkit_grasp* grasp, size_t* count) {
  return guarded([&] {
    const Grasp& g = graspOf(grasp);
    *require(count, "count") = g.contacts.size();
  });
}

graspkit_status graspkit_grasp_contacts(const graspkit_grasp* grasp, graspkit_contact* contacts,
                                        size_t capacity, size_t* copied) {
  return guarded([&] {
    const Grasp& g = graspOf(grasp);
    if (capacity > 0) require(contacts, "contacts");
    const std::size_t n = std::min(capacity, g.contacts.size());
    for (std::size_t i = 0; i < n; ++i) contacts[i] = toContact(g.contacts[i]);
    if (copied) *copied = n;
  });
}

graspkit_status graspkit_grasp_failure(const graspkit_grasp* grasp, char* buffer, size_t capacity,
                                       size_t* length) {
  return guarded([&] {
    const Grasp& g = graspOf(grasp);
    copyString(g.wrenchSpace.built ? std::string() : g.wrenchSpace.failure, buffer, capacity,
               length);
  });
}

void graspkit_grasp_free(graspkit_grasp* grasp) {
  delete grasp;
}

}  // extern "C"
