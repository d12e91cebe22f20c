#include "graspkit/host/object_task.hpp"

#include "graspkit/io/graspit/body_file.hpp"

namespace graspkit::host {

SavedObject saveGeneratedObject(const std::filesystem::path& folder,
                                const ObjectGeneratorOptions& options, std::size_t index) {
  const GeneratedObject object = generateObject(options, index);
  BodyXmlOptions body;
  body.material = options.material;
  body.massGrams = object.mass;
  const std::filesystem::path file = saveBodyFiles(folder, object.name, object.mesh, body);
  return SavedObject{object.name, file, object.kind, object.mass, object.shape};
}

}  // namespace graspkit::host
