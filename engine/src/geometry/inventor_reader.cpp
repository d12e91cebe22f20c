// Inventor (.iv) and VRML 2 (.wrl) through Coin3D. Coin parses the scene and tessellates every
// shape node (Cube, Sphere, Cylinder, Cone, face sets, VRML geometry); an SoCallbackAction hands
// us each triangle, which we move into the scene's root frame with the model matrix in effect
// (so Transform, Scale and friends apply) and weld into an indexed mesh. GraspIt! collects its
// triangles the same way, so triangle counts match it one for one.

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <mutex>
#include <string>
#include <vector>

#include <Inventor/SoDB.h>
#include <Inventor/SoInput.h>
#include <Inventor/SoPrimitiveVertex.h>
#include <Inventor/actions/SoCallbackAction.h>
#include <Inventor/errors/SoDebugError.h>
#include <Inventor/errors/SoError.h>
#include <Inventor/errors/SoReadError.h>
#include <Inventor/nodes/SoSeparator.h>
#include <Inventor/nodes/SoShape.h>

#include "geometry/mesh_readers.hpp"
#include "graspkit/error.hpp"
#include "graspkit/log.hpp"
#include "graspkit/mesh_loader.hpp"

namespace graspkit {
namespace {

// Coin keeps global parser state and its error handlers are process-wide, so one file is read
// at a time. Loads are short (milliseconds) and usually happen once per model.
std::mutex coin_mutex;

// Messages Coin posts while a file is being read; null when no read is in progress.
std::vector<std::string>* coin_messages = nullptr;

void onCoinMessage(const SoError* error, void* /*data*/) {
  std::string message = error->getDebugString().getString();
  while (!message.empty() && (message.back() == '\n' || message.back() == ' ')) {
    message.pop_back();
  }
  if (coin_messages != nullptr) {
    coin_messages->push_back(std::move(message));
  } else {
    warn(detail::locationIn("Coin3D"), message);
  }
}

// Routes Coin's messages into `messages` for as long as it lives (under coin_mutex).
class CoinMessageCapture {
 public:
  explicit CoinMessageCapture(std::vector<std::string>& messages) { coin_messages = &messages; }
  ~CoinMessageCapture() { coin_messages = nullptr; }
  CoinMessageCapture(const CoinMessageCapture&) = delete;
  CoinMessageCapture& operator=(const CoinMessageCapture&) = delete;
};

void installCoinHandlers() {
  SoError::setHandlerCallback(onCoinMessage, nullptr);
  SoReadError::setHandlerCallback(onCoinMessage, nullptr);
  SoDebugError::setHandlerCallback(onCoinMessage, nullptr);
}

// A world-space corner as the bit patterns of its float coordinates: equality is exact, and
// -0 and +0 (the same point) are made the same by adding +0.
using CornerKey = std::array<std::uint32_t, 3>;

CornerKey cornerKey(const SbVec3f& p) {
  return {std::bit_cast<std::uint32_t>(p[0] + 0.0f), std::bit_cast<std::uint32_t>(p[1] + 0.0f),
          std::bit_cast<std::uint32_t>(p[2] + 0.0f)};
}

// Merges bit-identical corners, which is how shared corners arrive from Coin (the same float
// through the same matrix). An open-addressing table over flat arrays keeps it free of
// per-vertex allocations.
class VertexWelder {
 public:
  std::uint32_t add(const CornerKey& key) {
    if (2 * (keys_.size() + 1) > slots_.size()) grow();
    std::size_t slot = hash(key) & (slots_.size() - 1);
    while (slots_[slot] != kEmpty) {
      if (keys_[slots_[slot]] == key) return slots_[slot];
      slot = (slot + 1) & (slots_.size() - 1);
    }
    slots_[slot] = static_cast<std::uint32_t>(keys_.size());
    keys_.push_back(key);
    return slots_[slot];
  }

  std::vector<Vector3> vertices() const {
    std::vector<Vector3> out;
    out.reserve(keys_.size());
    for (const CornerKey& key : keys_) {
      out.emplace_back(std::bit_cast<float>(key[0]), std::bit_cast<float>(key[1]),
                       std::bit_cast<float>(key[2]));
    }
    return out;
  }

 private:
  static constexpr std::uint32_t kEmpty = 0xffffffffu;

  static std::size_t hash(const CornerKey& key) {
    std::uint64_t h = key[0];
    h = h * 0x9e3779b97f4a7c15ull ^ key[1];
    h = h * 0x9e3779b97f4a7c15ull ^ key[2];
    h *= 0x9e3779b97f4a7c15ull;
    return static_cast<std::size_t>(h ^ (h >> 29));
  }

  void grow() {
    slots_.assign(std::max<std::size_t>(1024, 2 * slots_.size()), kEmpty);
    for (std::uint32_t i = 0; i < keys_.size(); ++i) {
      std::size_t slot = hash(keys_[i]) & (slots_.size() - 1);
      while (slots_[slot] != kEmpty) slot = (slot + 1) & (slots_.size() - 1);
      slots_[slot] = i;
    }
  }

  std::vector<CornerKey> keys_;
  std::vector<std::uint32_t> slots_;
};

struct TriangleCollector {
  VertexWelder welder;
  std::vector<std::array<std::uint32_t, 3>> triangles;
  bool non_finite = false;
};

double determinant3x3(const SbMatrix& m) {
  return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
         m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
         m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

void onTriangle(void* data, SoCallbackAction* action, const SoPrimitiveVertex* v1,
                const SoPrimitiveVertex* v2, const SoPrimitiveVertex* v3) {
  auto& collector = *static_cast<TriangleCollector*>(data);
  const SbMatrix& model = action->getModelMatrix();
  std::array<CornerKey, 3> corners;
  const SoPrimitiveVertex* sources[3] = {v1, v2, v3};
  for (int i = 0; i < 3; ++i) {
    SbVec3f world;
    model.multVecMatrix(sources[i]->getPoint(), world);
    if (!std::isfinite(world[0]) || !std::isfinite(world[1]) || !std::isfinite(world[2])) {
      collector.non_finite = true;
      return;
    }
    corners[i] = cornerKey(world);
  }
  // Two coincident corners make a triangle with no area that bounds nothing. GraspIt! leaves
  // these out too: its triangle counts for glass.iv and Robonaut are Coin's minus exactly these.
  if (corners[0] == corners[1] || corners[1] == corners[2] || corners[2] == corners[0]) return;
  std::array<std::uint32_t, 3> triangle;
  for (int i = 0; i < 3; ++i) triangle[i] = collector.welder.add(corners[i]);
  // A mirroring transform turns Coin's counter-clockwise shapes inside out; undo that so the
  // mesh keeps outward winding and a positive volume.
  if (determinant3x3(model) < 0) std::swap(triangle[1], triangle[2]);
  collector.triangles.push_back(triangle);
}

std::string joined(const std::vector<std::string>& messages) {
  std::string out;
  for (const std::string& message : messages) {
    if (!out.empty()) out += "; ";
    out += message;
  }
  return out;
}

// Reads the scene graph; throws with Coin's own diagnostics (which carry the line) on failure.
SoSeparator* readScene(const std::filesystem::path& path, std::vector<std::string>& messages) {
  SoInput input;
  if (!input.openFile(path.c_str())) {
    throw Error(detail::locationIn(path.string()), "cannot open the file: " + joined(messages));
  }
  SoSeparator* root = SoDB::readAll(&input);
  input.closeFile();
  if (root == nullptr) {
    const std::string reason = messages.empty() ? "not an Inventor or VRML file" : joined(messages);
    throw Error(detail::locationIn(path.string()), "cannot parse the scene: " + reason);
  }
  return root;
}

TriangleCollector collectTriangles(SoSeparator* root) {
  TriangleCollector collector;
  SoCallbackAction action;
  action.addTriangleCallback(SoShape::getClassTypeId(), onTriangle, &collector);
  root->ref();
  action.apply(root);
  root->unref();
  return collector;
}

}  // namespace

void initInventorReader() {
  static std::once_flag once;
  std::call_once(once, [] {
    SoDB::init();
    installCoinHandlers();
  });
}

namespace detail {

TriangleMesh readInventor(const std::filesystem::path& path) {
  initInventorReader();
  std::vector<std::string> messages;
  TriangleCollector collector;
  {
    std::lock_guard lock(coin_mutex);
    CoinMessageCapture capture(messages);
    collector = collectTriangles(readScene(path, messages));
  }
  const SourceLocation where = locationIn(path.string());
  if (collector.non_finite) throw Error(where, "a vertex has a non-finite coordinate");
  if (collector.triangles.empty()) throw Error(where, "the scene holds no triangles");
  // Coin accepted the file; whatever it said along the way is worth a look, not a failure.
  for (const std::string& message : messages) warn(where, message);
  TriangleMesh mesh;
  mesh.vertices = collector.welder.vertices();
  mesh.triangles = std::move(collector.triangles);
  return mesh;
}

}  // namespace detail
}  // namespace graspkit
