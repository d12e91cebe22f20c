// Versions, status names and the log callback (the last error is in c_api_support.cpp).

#include "c_api_support.hpp"
#include "graspkit/base/log.hpp"
#include "graspkit/base/version.hpp"

extern "C" {

uint32_t graspkit_abi_version(void) {
  return GRASPKIT_ABI_VERSION;
}

const char* graspkit_version(void) {
  return graspkit::engineVersion();
}

const char* graspkit_status_name(int32_t status) {
  switch (status) {
    case GRASPKIT_OK:
      return "ok";
    case GRASPKIT_ERROR_INVALID_ARGUMENT:
      return "invalid argument";
    case GRASPKIT_ERROR_OUT_OF_RANGE:
      return "index out of range";
    case GRASPKIT_ERROR_NOT_FOUND:
      return "not found";
    case GRASPKIT_ERROR_INPUT:
      return "input error";
    case GRASPKIT_ERROR_BUFFER_TOO_SMALL:
      return "buffer too small";
    case GRASPKIT_ERROR_SCRIPT:
      return "script error";
    case GRASPKIT_ERROR_INTERNAL:
      return "internal error";
  }
  return "unknown status";
}

graspkit_status graspkit_set_log_callback(graspkit_log_fn fn, void* user) {
  return graspkit::c_api::guarded([&] {
    if (!fn) {
      graspkit::setWarningHandler({});
      return;
    }
    graspkit::setWarningHandler([fn, user](const graspkit::Warning& warning) {
      const std::string kind(graspkit::nameOf(warning.kind));
      fn(GRASPKIT_LOG_WARNING, kind.c_str(), warning.where.file.c_str(), warning.where.line,
         warning.where.element.c_str(), warning.message.c_str(), user);
    });
  });
}

}  // extern "C"
