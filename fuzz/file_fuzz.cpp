// libFuzzer target for one of graspkit's file readers, chosen at compile time by
// GRASPKIT_FUZZ_READER (see CMakeLists.txt). Any bytes must give a result that keeps the
// reader's promises (mesh indices in range, finite vertices) or a graspkit::Error. A crash, a
// sanitizer report, a hang, or any other exception is a bug.
//
// The readers take files, so each input is written to one scratch file first; the file's name
// carries the extension the reader dispatches on.

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "graspkit/base/error.hpp"
#include "graspkit/base/log.hpp"
#include "graspkit/geometry/mesh_loader.hpp"
#include "graspkit/io/dataset/grasp_dataset_file.hpp"
#include "graspkit/io/graspit/body_file.hpp"
#include "graspkit/io/graspit/eigengrasp_file.hpp"
#include "graspkit/io/graspit/robot_export.hpp"
#include "graspkit/io/graspit/robot_file.hpp"
#include "graspkit/io/graspit/virtual_contact_file.hpp"
#include "graspkit/io/graspit/world_file.hpp"
#include "graspkit/io/mjcf/mjcf_export.hpp"
#include "graspkit/io/mjcf/mjcf_file.hpp"
#include "graspkit/io/urdf/urdf_export.hpp"
#include "graspkit/io/urdf/urdf_file.hpp"
#include "graspkit/model/world.hpp"

namespace {

namespace fs = std::filesystem;

// A scratch folder of this process, removed at exit.
const fs::path& scratchFolder() {
  static const fs::path folder = [] {
    std::string pattern = (fs::temp_directory_path() / "graspkit_fuzz_XXXXXX").string();
    if (mkdtemp(pattern.data()) == nullptr) std::abort();
    std::atexit([] {
      std::error_code ec;
      fs::remove_all(scratchFolder(), ec);
    });
    return fs::path(pattern);
  }();
  return folder;
}

void checkMesh(const graspkit::TriangleMesh& mesh) {
  for (const auto& triangle : mesh.triangles)
    for (const std::uint32_t index : triangle)
      if (index >= mesh.vertices.size()) std::abort();
  for (const auto& vertex : mesh.vertices)
    if (!vertex.allFinite()) std::abort();
}

void checkWorld(const graspkit::World& world) {
  for (const graspkit::Body& body : world.bodies())
    if (body.model && body.model->mesh) checkMesh(*body.model->mesh);
}

void read(const fs::path& file) {
  const std::string reader = GRASPKIT_FUZZ_READER;
  if (reader == "body") {
    const auto body = graspkit::loadBodyFile(file);
    if (body->mesh) checkMesh(*body->mesh);
  } else if (reader == "robot") {
    graspkit::LoadOptions options;
    options.useEnvironment = false;
    options.genericRobotFallback = true;
    graspkit::loadRobotFile(file, options);
  } else if (reader == "world") {
    graspkit::LoadOptions options;
    options.useEnvironment = false;
    options.genericRobotFallback = true;
    checkWorld(graspkit::loadWorldFile(file, options));
  } else if (reader == "dataset") {
    // Whatever loads must save and load back to the same grasps.
    const graspkit::GraspDataset dataset = graspkit::loadGraspDataset(file);
    const fs::path again = scratchFolder() / "again.h5";
    graspkit::saveGraspDataset(dataset, again);
    const graspkit::GraspDataset back = graspkit::loadGraspDataset(again);
    if (back.grasps.size() != dataset.grasps.size() || back.objectName != dataset.objectName)
      std::abort();
  } else if (reader == "export") {
    // A robot that loads is written as URDF, MJCF and GraspIt! XML, and each must load back
    // with its DOFs: an exporter may refuse a robot (an Error), never write what cannot be read.
    graspkit::LoadOptions options;
    options.useEnvironment = false;
    options.genericRobotFallback = true;
    const auto robot = graspkit::loadRobotFile(file, options);
    using Save = fs::path (*)(const graspkit::RobotModel&, const fs::path&);
    const Save savers[] = {graspkit::saveUrdf, graspkit::saveMjcf, graspkit::saveRobotFile};
    for (const Save save : savers) {
      const fs::path folder = scratchFolder() / "export";
      std::error_code ignored;
      fs::remove_all(folder, ignored);
      fs::path written;
      try {
        written = save(*robot, folder);
      } catch (const graspkit::Error&) {
        continue;
      }
      try {
        const auto back = graspkit::loadRobotFile(written, options);
        if (back->dofs.size() != robot->dofs.size()) std::abort();
      } catch (const graspkit::Error& e) {
        std::fprintf(stderr, "an exported robot does not load back: %s\n", e.what());
        std::abort();
      }
    }
  } else if (reader == "eigengrasp") {
    graspkit::loadEigengraspFile(file, 4);
  } else if (reader == "virtual_contact") {
    graspkit::loadVirtualContactFile(file);
  } else {  // a mesh format: the extension chooses the reader
    checkMesh(graspkit::loadMesh(file));
  }
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int* /*argc*/, char*** /*argv*/) {
  graspkit::setWarningHandler([](const graspkit::Warning&) {});
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const fs::path file = scratchFolder() / ("input" GRASPKIT_FUZZ_EXTENSION);
  {
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  try {
    read(file);
  } catch (const graspkit::Error&) {
    // Refused with a located error: the expected outcome for most inputs.
  }
  return 0;
}
