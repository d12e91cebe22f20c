#include "io/common/stl_bytes.hpp"

#include "graspkit/math/units.hpp"

#include <cstdint>

namespace graspkit::io {

std::string stlBytes(const TriangleMesh& mesh) {
  std::string bytes(80, '\0');
  const auto count = static_cast<std::uint32_t>(mesh.triangles.size());
  bytes.append(reinterpret_cast<const char*>(&count), 4);
  for (const auto& t : mesh.triangles) {
    const Vector3& a = mesh.vertices[t[0]];
    const Vector3& b = mesh.vertices[t[1]];
    const Vector3& c = mesh.vertices[t[2]];
    Vector3 n = (b - a).cross(c - a);
    if (n.norm() > 0) n.normalize();
    float values[12];
    for (int k = 0; k < 3; ++k) {
      values[k] = static_cast<float>(n[k]);
      values[3 + k] = static_cast<float>(a[k] / units::kMetre);
      values[6 + k] = static_cast<float>(b[k] / units::kMetre);
      values[9 + k] = static_cast<float>(c[k] / units::kMetre);
    }
    bytes.append(reinterpret_cast<const char*>(values), sizeof(values));
    bytes.append(2, '\0');
  }
  return bytes;
}

}  // namespace graspkit::io
