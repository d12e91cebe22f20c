#pragma once
// Coin trusts its scene graphs: an IndexedFaceSet whose coordIndex points past its Coordinate3,
// a FaceSet that counts more vertices than there are, or a normalIndex past its Normal node
// make Coin read outside its arrays while it tessellates, and crash. The Inventor reader runs
// these checks on every node just before Coin traverses it.

#include <string>

class SoCallbackAction;
class SoNode;

namespace graspkit::detail {

struct ShapeVerdict {
  enum Kind { Traverse, Skip, Reject };
  Kind kind = Traverse;
  std::string problem;  // for Reject: what is wrong, naming the node type and field
};

// True for nodes that only affect appearance (normals, material and texture bindings, textures,
// texture coordinates): geometry never needs them, and they are where indices into short arrays
// hide, so the reader skips them and Coin generates its own normals from the coordinates. A
// VertexProperty also holds coordinates: it is kept (false) but loses its appearance fields.
bool pruneAppearance(SoNode& node);

// Decides whether Coin may tessellate `shape` in the traversal state of `action`. Shapes that
// yield no triangles (points, lines, 2-D text) are skipped; vertex shapes have their coordinate
// indices and counts checked, and their own appearance fields cleared (they belong to a scene
// that is discarded after loading); shape types we cannot check (NURBS) are rejected.
ShapeVerdict checkShape(SoCallbackAction& action, SoNode& shape);

}  // namespace graspkit::detail
