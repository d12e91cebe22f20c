#include "c_api_support.hpp"
#include "graspkit/base/enum_names.hpp"
#include "graspkit/model/material.hpp"

#include <cmath>

#include <fmt/format.h>

namespace graspkit::c_api {

LastError& lastError() {
  thread_local LastError error;
  return error;
}

void setLastError(graspkit_status status, const std::string& message, const SourceLocation& where) {
  LastError& e = lastError();
  const std::string prefix = where.str();
  e.message = prefix.empty() ? message : prefix + ": " + message;
  if (e.message.empty()) e.message = graspkit_status_name(status);
  e.file = where.file;
  e.line = where.line;
  e.element = where.element;
}

void clearLastError() {
  LastError& e = lastError();
  e.message.clear();
  e.file.clear();
  e.line = 0;
  e.element.clear();
}

const Body& checkedBody(const World& world, std::int32_t body) {
  const auto count = static_cast<std::int32_t>(world.bodies().size());
  if (body < 0 || body >= count)
    throw Failure{GRASPKIT_ERROR_OUT_OF_RANGE,
                  fmt::format("body {} does not exist (the world has {} bodies)", body, count)};
  return world.bodies()[static_cast<std::size_t>(body)];
}

const Robot& checkedRobot(const World& world, std::int32_t robot) {
  if (robot < 0 || robot >= world.robotCount())
    throw Failure{GRASPKIT_ERROR_OUT_OF_RANGE,
                  fmt::format("robot {} does not exist (the world has {} robots)", robot,
                              world.robotCount())};
  return world.robot(robot);
}

void checkCount(std::size_t given, std::size_t expected, const char* what) {
  if (given != expected)
    throw Failure{GRASPKIT_ERROR_INVALID_ARGUMENT,
                  fmt::format("{}: {} values given, {} expected", what, given, expected)};
}

void copyString(std::string_view text, char* buffer, std::size_t capacity, std::size_t* length) {
  if (length) *length = text.size();
  if (capacity > 0) {
    require(buffer, "buffer");
    const std::size_t n = std::min(text.size(), capacity - 1);
    std::memcpy(buffer, text.data(), n);
    buffer[n] = '\0';
  }
  if (text.size() >= capacity)
    throw Failure{
        GRASPKIT_ERROR_BUFFER_TOO_SMALL,
        fmt::format("a string of {} bytes does not fit a buffer of {}", text.size() + 1, capacity)};
}

Transform toTransform(const graspkit_pose& pose) {
  const Vector3 t(pose.translation[0], pose.translation[1], pose.translation[2]);
  if (!t.allFinite()) throw Error("the pose has a value that is not a finite number");
  if (const char* why = translationProblem(t))
    throw Error(fmt::format("the pose's translation {}", why));
  const std::optional<Quaternion> q =
      unitQuaternion(pose.rotation[0], pose.rotation[1], pose.rotation[2], pose.rotation[3]);
  if (!q) throw Error("the pose's quaternion is zero or not finite: it names no rotation");
  return makeTransform(t, *q);
}

graspkit_pose toPose(const Transform& transform) {
  graspkit_pose pose{};
  const Vector3 t = transform.translation();
  const Quaternion q(transform.rotation());
  for (int i = 0; i < 3; ++i) pose.translation[i] = t[i];
  pose.rotation[0] = q.w();
  pose.rotation[1] = q.x();
  pose.rotation[2] = q.y();
  pose.rotation[3] = q.z();
  return pose;
}

graspkit_body_ref toRef(const BodyRef& ref) {
  graspkit_body_ref out{};
  out.kind = static_cast<std::int32_t>(ref.kind);
  out.index = ref.index;
  out.chain = ref.isLink() ? ref.link.chain : -1;
  out.link = ref.isLink() ? ref.link.link : -1;
  return out;
}

BodyRef fromRef(const graspkit_body_ref& ref) {
  switch (ref.kind) {
    case GRASPKIT_BODY:
      return BodyRef::body(ref.index);
    case GRASPKIT_LINK:
      return BodyRef::robotLink(ref.index, LinkRef{ref.chain, ref.link});
    case GRASPKIT_MOUNT:
      return BodyRef::mount(ref.index);
    default:
      throw Failure{GRASPKIT_ERROR_INVALID_ARGUMENT,
                    fmt::format("body reference kind {} is not 0, 1 or 2", ref.kind)};
  }
}

LoadOptions loadOptions(const graspkit_load_options* options) {
  LoadOptions result;
  if (!options) return result;
  auto paths = [](const char* const* list, std::size_t count, const char* what) {
    std::vector<std::filesystem::path> out;
    if (count > 0) require(list, what);
    for (std::size_t i = 0; i < count; ++i) out.emplace_back(require(list[i], what));
    return out;
  };
  result.roots = paths(options->roots, options->root_count, "options->roots");
  result.genericRobotFallback = options->generic_robots != 0;
  result.packagePaths =
      paths(options->package_paths, options->package_path_count, "options->package_paths");
  if (options->palm) result.urdfPalm = options->palm;
  if (options->srdf) result.srdf = options->srdf;
  if (options->urdf_material)
    result.urdfMaterial = parseNamed<Material>(options->urdf_material, "material");
  if (options->close_count > 0) require(options->closing, "options->closing");
  for (std::size_t i = 0; i < options->close_count; ++i) {
    const std::int32_t sign = options->closing[i];
    if (sign < -1 || sign > 1)
      throw Failure{GRASPKIT_ERROR_INVALID_ARGUMENT,
                    fmt::format("options->closing[{}] is {}: -1, 0 or +1 expected", i, sign)};
    if (sign != 0) result.closingDirections[static_cast<int>(i)] = sign;
  }
  return result;
}

}  // namespace graspkit::c_api

extern "C" {

const char* graspkit_last_error(void) {
  return graspkit::c_api::lastError().message.c_str();
}

const char* graspkit_last_error_file(void) {
  return graspkit::c_api::lastError().file.c_str();
}

int graspkit_last_error_line(void) {
  return graspkit::c_api::lastError().line;
}

const char* graspkit_last_error_element(void) {
  return graspkit::c_api::lastError().element.c_str();
}

}  // extern "C"
