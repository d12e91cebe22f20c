#pragma once
// Generated objects (model/object_generator.hpp) written as GraspIt! bodies, as `graspkit
// objects`, Lua, Python and the C ABI write them: FOLDER/NAME.off and FOLDER/NAME.xml.

#include <cstddef>
#include <filesystem>
#include <string>

#include "graspkit/model/object_generator.hpp"

namespace graspkit::host {

struct SavedObject {
  std::string name;            // object_<index>_<kind>
  std::filesystem::path file;  // the Body XML
  ObjectKind kind = ObjectKind::Box;
  double mass = 0.0;  // g
  std::string shape;  // the drawn parameters
};

// Object `index` of the set `options` describes, saved in `folder` (which must exist), each file
// atomically. Throws graspkit::Error as generateObject and saveBodyFiles do.
SavedObject saveGeneratedObject(const std::filesystem::path& folder,
                                const ObjectGeneratorOptions& options, std::size_t index);

}  // namespace graspkit::host
