#pragma once
// What every C ABI function shares: the handles' definitions, the per-thread last error, and
// guarded(), which turns any C++ exception into a status so that none crosses into C.

#include <cstring>
#include <memory>
#include <new>
#include <string>
#include <string_view>
#include <vector>

#include "graspkit.h"
#include "graspkit/base/error.hpp"
#include "graspkit/grasp/grasp.hpp"
#include "graspkit/host/invalid_setting.hpp"
#include "graspkit/host/world_session.hpp"
#include "graspkit/model/world.hpp"
#include "graspkit/planning/planner.hpp"
#include "graspkit/raycast/ray_scene.hpp"

// The host layer's world handle: the world, its file, its model cache.
struct graspkit_world : graspkit::host::WorldSession {};

struct graspkit_grasp {
  graspkit::Grasp grasp;
};

struct graspkit_ray_scene {
  graspkit::RayScene scene;
};

struct graspkit_plan {
  graspkit::PlanningRequest request;
  std::vector<graspkit::PlannedGrasp> grasps;
};

namespace graspkit::c_api {

// A failure the C layer detects itself (null pointers, bad indices), with the status to return.
struct Failure {
  graspkit_status status;
  std::string message;
};

// The last failure on this thread, as graspkit_last_error() and its parts report it.
struct LastError {
  std::string message;
  std::string file;
  int line = 0;
  std::string element;
};
LastError& lastError();

void setLastError(graspkit_status status, const std::string& message,
                  const SourceLocation& where = {});
void clearLastError();

// Runs `body` (which returns nothing or throws): GRASPKIT_OK, or the status of what it threw
// with the message kept for graspkit_last_error().
template <class Body>
graspkit_status guarded(Body&& body) noexcept {
  try {
    clearLastError();
    body();
    return GRASPKIT_OK;
  } catch (const Failure& f) {
    setLastError(f.status, f.message);
    return f.status;
  } catch (const graspkit::host::InvalidSetting& e) {
    setLastError(GRASPKIT_ERROR_INVALID_ARGUMENT, e.message(), e.where());
    return GRASPKIT_ERROR_INVALID_ARGUMENT;
  } catch (const graspkit::Error& e) {
    setLastError(GRASPKIT_ERROR_INPUT, e.message(), e.where());
    return GRASPKIT_ERROR_INPUT;
  } catch (const std::bad_alloc&) {
    setLastError(GRASPKIT_ERROR_INTERNAL, "out of memory");
    return GRASPKIT_ERROR_INTERNAL;
  } catch (const std::exception& e) {
    setLastError(GRASPKIT_ERROR_INTERNAL, std::string("internal error: ") + e.what());
    return GRASPKIT_ERROR_INTERNAL;
  } catch (...) {
    setLastError(GRASPKIT_ERROR_INTERNAL, "internal error: an exception of unknown type");
    return GRASPKIT_ERROR_INTERNAL;
  }
}

// Throws a Failure naming `what` when `pointer` is null.
template <class T>
T* require(T* pointer, const char* what) {
  if (!pointer) throw Failure{GRASPKIT_ERROR_INVALID_ARGUMENT, std::string(what) + " is NULL"};
  return pointer;
}

// Index checks: a Failure (GRASPKIT_ERROR_OUT_OF_RANGE) naming the index and the valid range.
const Body& checkedBody(const World& world, std::int32_t body);
const Robot& checkedRobot(const World& world, std::int32_t robot);
void checkCount(std::size_t given, std::size_t expected, const char* what);

// Copies `text` into the caller's buffer by the header's string rule; a Failure
// (GRASPKIT_ERROR_BUFFER_TOO_SMALL) after writing what fits when it does not.
void copyString(std::string_view text, char* buffer, std::size_t capacity, std::size_t* length);

Transform toTransform(const graspkit_pose& pose);
graspkit_pose toPose(const Transform& transform);
graspkit_body_ref toRef(const BodyRef& ref);
BodyRef fromRef(const graspkit_body_ref& ref);

// The load options a graspkit_load_options describes (NULL: the defaults).
LoadOptions loadOptions(const graspkit_load_options* options);

// A new C handle holding `session`.
inline graspkit_world* newWorld(host::WorldSession session) {
  auto* world = new graspkit_world;
  static_cast<host::WorldSession&>(*world) = std::move(session);
  return world;
}

}  // namespace graspkit::c_api
