// libFuzzer target for the OFF parser: any bytes must yield a mesh whose indices are in range,
// or a graspkit::Error. Anything else (a crash, a sanitizer report, another exception) is a bug.

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "graspkit/error.hpp"
#include "graspkit/mesh_loader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const graspkit::TriangleMesh mesh = graspkit::parseOff(text, "fuzz.off");
    for (const auto& triangle : mesh.triangles) {
      for (const std::uint32_t index : triangle) {
        if (index >= mesh.vertices.size()) std::abort();
      }
    }
    for (const auto& vertex : mesh.vertices) {
      if (!vertex.allFinite()) std::abort();
    }
  } catch (const graspkit::Error&) {
    // Rejected with a located error: the expected outcome for most inputs.
  }
  return 0;
}
