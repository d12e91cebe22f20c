// Worlds, bodies and robots.

#include <fmt/format.h>

#include "c_api_support.hpp"
#include "graspkit/io/graspit/world_file.hpp"

using namespace graspkit;
using namespace graspkit::c_api;

namespace {

World& worldOf(graspkit_world* world) {
  return require(world, "world")->world;
}
const World& worldOf(const graspkit_world* world) {
  return require(world, "world")->world;
}

// Finds a body or robot by name: NOT_FOUND listing the names there are.
template <class Names>
[[noreturn]] void notFound(const char* what, const std::string& name, const Names& names) {
  std::string known;
  for (const std::string& n : names) known += (known.empty() ? "" : ", ") + n;
  throw Failure{GRASPKIT_ERROR_NOT_FOUND, fmt::format("no {} named '{}' (the world has: {})", what,
                                                      name, known.empty() ? "none" : known)};
}

}  // namespace

extern "C" {

graspkit_status graspkit_world_new(graspkit_world** world) {
  return guarded([&] {
    // Checked first: in `*p = new T`, the new is evaluated before p, and would leak.
    require(world, "world");
    *world = new graspkit_world;
  });
}

graspkit_status graspkit_world_load(const char* path, const graspkit_load_options* options,
                                    graspkit_world** world) {
  return guarded([&] {
    require(world, "world");
    host::WorldSession loaded =
        host::WorldSession::load(require(path, "path"), loadOptions(options));
    *world = newWorld(std::move(loaded));
  });
}

graspkit_status graspkit_world_clone(const graspkit_world* world, graspkit_world** clone) {
  return guarded([&] {
    require(clone, "clone");
    *clone = newWorld(require(world, "world")->clone());
  });
}

graspkit_status graspkit_world_save(const graspkit_world* world, const char* path) {
  // A copy of the handle, so that saving from a const handle does not record the file.
  return guarded([&] { require(world, "world")->clone().save(require(path, "path")); });
}

graspkit_status graspkit_world_add_file(graspkit_world* world, const char* path,
                                        const graspkit_load_options* options, int32_t* first_body,
                                        int32_t* first_robot) {
  return guarded([&] {
    const auto [bodies, robots] =
        require(world, "world")->addFile(require(path, "path"), loadOptions(options));
    if (first_body) *first_body = bodies;
    if (first_robot) *first_robot = robots;
  });
}

void graspkit_world_free(graspkit_world* world) {
  delete world;
}

graspkit_status graspkit_world_remove_body(graspkit_world* world, int32_t body) {
  return guarded([&] {
    graspkit_world& handle = *require(world, "world");
    checkedBody(handle.world, body);
    handle.removeBody(body);
  });
}

graspkit_status graspkit_world_body_count(const graspkit_world* world, int32_t* count) {
  return guarded(
      [&] { *require(count, "count") = static_cast<int32_t>(worldOf(world).bodies().size()); });
}

graspkit_status graspkit_world_find_body(const graspkit_world* world, const char* name,
                                         int32_t* body) {
  return guarded([&] {
    const World& w = worldOf(world);
    const std::string wanted = require(name, "name");
    require(body, "body");
    std::vector<std::string> names;
    for (std::size_t i = 0; i < w.bodies().size(); ++i) {
      if (w.bodies()[i].name == wanted) {
        *body = static_cast<int32_t>(i);
        return;
      }
      names.push_back(w.bodies()[i].name);
    }
    notFound("body", wanted, names);
  });
}

graspkit_status graspkit_body_name(const graspkit_world* world, int32_t body, char* buffer,
                                   size_t capacity, size_t* length) {
  return guarded(
      [&] { copyString(checkedBody(worldOf(world), body).name, buffer, capacity, length); });
}

graspkit_status graspkit_body_is_graspable(const graspkit_world* world, int32_t body,
                                           int* graspable) {
  return guarded([&] {
    const Body& b = checkedBody(worldOf(world), body);
    *require(graspable, "graspable") = b.isDynamic() ? 1 : 0;
  });
}

graspkit_status graspkit_body_mass(const graspkit_world* world, int32_t body, double* mass,
                                   double cog[3]) {
  return guarded([&] {
    const Body& b = checkedBody(worldOf(world), body);
    require(mass, "mass");
    *mass = b.model->mass;
    if (cog)
      for (int i = 0; i < 3; ++i) cog[i] = b.model->cog[i];
  });
}

graspkit_status graspkit_body_get_pose(const graspkit_world* world, int32_t body,
                                       graspkit_pose* pose) {
  return guarded([&] {
    const Body& b = checkedBody(worldOf(world), body);
    *require(pose, "pose") = toPose(b.pose);
  });
}

graspkit_status graspkit_body_set_pose(graspkit_world* world, int32_t body,
                                       const graspkit_pose* pose) {
  return guarded([&] {
    World& w = worldOf(world);
    checkedBody(w, body);
    const Transform t = toTransform(*require(pose, "pose"));
    w.bodies()[static_cast<std::size_t>(body)].setPose(t);
  });
}

graspkit_status graspkit_body_ref_name(const graspkit_world* world, const graspkit_body_ref* ref,
                                       char* buffer, size_t capacity, size_t* length) {
  return guarded([&] {
    const World& w = worldOf(world);
    const BodyRef r = fromRef(*require(ref, "ref"));
    if (!isValid(w, r))
      throw Failure{GRASPKIT_ERROR_OUT_OF_RANGE,
                    fmt::format("body reference (kind {}, index {}, chain {}, link {}) names "
                                "nothing in the world",
                                ref->kind, ref->index, ref->chain, ref->link)};
    copyString(bodyName(w, r), buffer, capacity, length);
  });
}

graspkit_status graspkit_world_robot_count(const graspkit_world* world, int32_t* count) {
  return guarded([&] { *require(count, "count") = worldOf(world).robotCount(); });
}

graspkit_status graspkit_world_find_robot(const graspkit_world* world, const char* name,
                                          int32_t* robot) {
  return guarded([&] {
    const World& w = worldOf(world);
    const std::string wanted = require(name, "name");
    require(robot, "robot");
    if (const auto found = w.findRobot(wanted)) {
      *robot = *found;
      return;
    }
    std::vector<std::string> names;
    for (int r = 0; r < w.robotCount(); ++r) names.push_back(w.robot(r).name());
    notFound("robot", wanted, names);
  });
}

graspkit_status graspkit_world_first_hand(const graspkit_world* world, int32_t* robot) {
  return guarded([&] {
    require(robot, "robot");
    const auto hand = worldOf(world).firstHand();
    if (!hand) throw Failure{GRASPKIT_ERROR_NOT_FOUND, "no robot of the world is a hand"};
    *robot = *hand;
  });
}

graspkit_status graspkit_robot_name(const graspkit_world* world, int32_t robot, char* buffer,
                                    size_t capacity, size_t* length) {
  return guarded(
      [&] { copyString(checkedRobot(worldOf(world), robot).name(), buffer, capacity, length); });
}

graspkit_status graspkit_robot_dof_count(const graspkit_world* world, int32_t robot,
                                         int32_t* count) {
  return guarded([&] {
    const Robot& r = checkedRobot(worldOf(world), robot);
    *require(count, "count") = r.dofCount();
  });
}

graspkit_status graspkit_robot_get_dofs(const graspkit_world* world, int32_t robot, double* values,
                                        size_t count) {
  return guarded([&] {
    const Robot& r = checkedRobot(worldOf(world), robot);
    checkCount(count, static_cast<std::size_t>(r.dofCount()), "graspkit_robot_get_dofs");
    if (count > 0) require(values, "values");
    std::copy(r.dofValues().begin(), r.dofValues().end(), values);
  });
}

graspkit_status graspkit_robot_set_dofs(graspkit_world* world, int32_t robot, const double* values,
                                        size_t count) {
  return guarded([&] {
    World& w = worldOf(world);
    const Robot& r = checkedRobot(w, robot);
    checkCount(count, static_cast<std::size_t>(r.dofCount()), "graspkit_robot_set_dofs");
    if (count > 0) require(values, "values");
    w.setDofValues(robot, std::span<const double>(values, count));
  });
}

graspkit_status graspkit_robot_dof_limits(const graspkit_world* world, int32_t robot, double* min,
                                          double* max, size_t count) {
  return guarded([&] {
    const Robot& r = checkedRobot(worldOf(world), robot);
    checkCount(count, static_cast<std::size_t>(r.dofCount()), "graspkit_robot_dof_limits");
    if (count > 0) {
      require(min, "min");
      require(max, "max");
    }
    for (std::size_t d = 0; d < count; ++d) {
      min[d] = r.model().dofs[d].min;
      max[d] = r.model().dofs[d].max;
    }
  });
}

graspkit_status graspkit_robot_get_pose(const graspkit_world* world, int32_t robot,
                                        graspkit_pose* pose) {
  return guarded([&] {
    const Robot& r = checkedRobot(worldOf(world), robot);
    *require(pose, "pose") = toPose(r.pose());
  });
}

graspkit_status graspkit_robot_set_pose(graspkit_world* world, int32_t robot,
                                        const graspkit_pose* pose) {
  return guarded([&] {
    World& w = worldOf(world);
    checkedRobot(w, robot);
    w.setRobotPose(robot, toTransform(*require(pose, "pose")));
  });
}

graspkit_status graspkit_robot_chain_count(const graspkit_world* world, int32_t robot,
                                           int32_t* count) {
  return guarded([&] {
    const Robot& r = checkedRobot(worldOf(world), robot);
    *require(count, "count") = static_cast<int32_t>(r.model().chains.size());
  });
}

graspkit_status graspkit_robot_link_count(const graspkit_world* world, int32_t robot, int32_t chain,
                                          int32_t* count) {
  return guarded([&] {
    const Robot& r = checkedRobot(worldOf(world), robot);
    const auto chains = static_cast<int32_t>(r.model().chains.size());
    if (chain < 0 || chain >= chains)
      throw Failure{
          GRASPKIT_ERROR_OUT_OF_RANGE,
          fmt::format("chain {} does not exist ({} has {} chains)", chain, r.name(), chains)};
    *require(count, "count") =
        static_cast<int32_t>(r.model().chains[static_cast<std::size_t>(chain)].links.size());
  });
}

graspkit_status graspkit_robot_link_pose(const graspkit_world* world, int32_t robot, int32_t chain,
                                         int32_t link, graspkit_pose* pose) {
  return guarded([&] {
    const Robot& r = checkedRobot(worldOf(world), robot);
    require(pose, "pose");
    if (chain == -1 && link == -1) {
      *pose = toPose(r.pose());
      return;
    }
    const LinkRef ref{chain, link};
    if (chain < 0 || !r.model().hasLink(ref))
      throw Failure{GRASPKIT_ERROR_OUT_OF_RANGE,
                    fmt::format("{} has no link {} in chain {}", r.name(), link, chain)};
    *pose = toPose(r.linkPose(ref));
  });
}

}  // extern "C"
