#include "geometry/inventor_shape_check.hpp"

#include <cstdint>
#include <initializer_list>

#include <fmt/format.h>

#include <Inventor/VRMLnodes/SoVRMLBox.h>
#include <Inventor/VRMLnodes/SoVRMLCone.h>
#include <Inventor/VRMLnodes/SoVRMLCoordinate.h>
#include <Inventor/VRMLnodes/SoVRMLCylinder.h>
#include <Inventor/VRMLnodes/SoVRMLElevationGrid.h>
#include <Inventor/VRMLnodes/SoVRMLExtrusion.h>
#include <Inventor/VRMLnodes/SoVRMLIndexedLine.h>
#include <Inventor/VRMLnodes/SoVRMLIndexedShape.h>
#include <Inventor/VRMLnodes/SoVRMLSphere.h>
#include <Inventor/VRMLnodes/SoVRMLText.h>
#include <Inventor/VRMLnodes/SoVRMLVertexPoint.h>
#include <Inventor/actions/SoCallbackAction.h>
#include <Inventor/elements/SoCoordinateElement.h>
#include <Inventor/nodes/SoAsciiText.h>
#include <Inventor/nodes/SoBumpMapCoordinate.h>
#include <Inventor/nodes/SoCone.h>
#include <Inventor/nodes/SoCube.h>
#include <Inventor/nodes/SoCylinder.h>
#include <Inventor/nodes/SoFaceSet.h>
#include <Inventor/nodes/SoImage.h>
#include <Inventor/nodes/SoIndexedFaceSet.h>
#include <Inventor/nodes/SoIndexedLineSet.h>
#include <Inventor/nodes/SoIndexedPointSet.h>
#include <Inventor/nodes/SoIndexedTriangleStripSet.h>
#include <Inventor/nodes/SoLineSet.h>
#include <Inventor/nodes/SoMaterialBinding.h>
#include <Inventor/nodes/SoNormal.h>
#include <Inventor/nodes/SoNormalBinding.h>
#include <Inventor/nodes/SoPointSet.h>
#include <Inventor/nodes/SoQuadMesh.h>
#include <Inventor/nodes/SoSphere.h>
#include <Inventor/nodes/SoText2.h>
#include <Inventor/nodes/SoText3.h>
#include <Inventor/nodes/SoTexture.h>
#include <Inventor/nodes/SoTextureCoordinate2.h>
#include <Inventor/nodes/SoTextureCoordinate3.h>
#include <Inventor/nodes/SoTextureCoordinateBinding.h>
#include <Inventor/nodes/SoTextureCoordinateFunction.h>
#include <Inventor/nodes/SoTriangleStripSet.h>
#include <Inventor/nodes/SoVertexAttributeBinding.h>
#include <Inventor/nodes/SoVertexProperty.h>

namespace graspkit::detail {
namespace {

bool isOfAnyType(const SoNode& node, std::initializer_list<SoType> types) {
  for (const SoType& type : types) {
    if (node.isOfType(type)) return true;
  }
  return false;
}

std::string typeName(const SoNode& node) {
  return node.getTypeId().getName().getString();
}

ShapeVerdict reject(const SoNode& node, const std::string& problem) {
  return {ShapeVerdict::Reject, fmt::format("{}: {}", typeName(node), problem)};
}

// Points, lines and 2-D text bound no area.
bool yieldsNoTriangles(const SoNode& node) {
  return isOfAnyType(node,
                     {SoPointSet::getClassTypeId(), SoIndexedPointSet::getClassTypeId(),
                      SoLineSet::getClassTypeId(), SoIndexedLineSet::getClassTypeId(),
                      SoText2::getClassTypeId(), SoImage::getClassTypeId(),
                      SoVRMLVertexPoint::getClassTypeId(), SoVRMLIndexedLine::getClassTypeId()});
}

// An extrusion's surface grows as the product of two lists that the file holds end to end: 2000
// points each (45 KB) would make 8 million triangles and a minute's work. 250,000 quadrilaterals
// (500 by 500) stay within a few seconds and far above any hand or object model's need.
constexpr std::int64_t kMaxExtrusionQuads = 250'000;

// Shapes tessellated from their own fields only, which Coin handles for any values.
bool isParametric(const SoNode& node) {
  return isOfAnyType(
      node, {SoCube::getClassTypeId(), SoSphere::getClassTypeId(), SoCone::getClassTypeId(),
             SoCylinder::getClassTypeId(), SoText3::getClassTypeId(), SoAsciiText::getClassTypeId(),
             SoVRMLBox::getClassTypeId(), SoVRMLSphere::getClassTypeId(),
             SoVRMLCone::getClassTypeId(), SoVRMLCylinder::getClassTypeId(),
             SoVRMLText::getClassTypeId(), SoVRMLExtrusion::getClassTypeId()});
}

void clearAppearance(SoVertexProperty& properties) {
  properties.normal.setNum(0);
  properties.texCoord.setNum(0);
  properties.texCoord3.setNum(0);
  properties.orderedRGBA.setNum(0);
  properties.normalBinding = SoVertexProperty::OVERALL;
  properties.materialBinding = SoVertexProperty::OVERALL;
}

// The number of coordinates an Inventor vertex shape draws from: its own vertexProperty when
// that holds vertices, else the Coordinate3/Coordinate4 in effect. -1 when vertexProperty holds
// a node of another type, which Coin would cast blindly.
std::int64_t coordinateCount(SoCallbackAction& action, SoVertexShape& shape) {
  SoNode* node = shape.vertexProperty.getValue();
  if (node != nullptr) {
    if (!node->isOfType(SoVertexProperty::getClassTypeId())) return -1;
    auto& properties = static_cast<SoVertexProperty&>(*node);
    clearAppearance(properties);
    if (properties.vertex.getNum() > 0) return properties.vertex.getNum();
  }
  return SoCoordinateElement::getInstance(action.getState())->getNum();
}

// Every index must name a coordinate, or be -1 (the end of a face or strip).
std::string checkIndices(const SoMFInt32& indices, const char* field, std::int64_t count) {
  const std::int32_t* values = indices.getValues(0);
  for (int i = 0; i < indices.getNum(); ++i) {
    if (values[i] < -1 || values[i] >= count) {
      return fmt::format("{}[{}] is {}, there are {} coordinates", field, i, values[i], count);
    }
  }
  return {};
}

// FaceSet and TriangleStripSet consume numVertices[i] coordinates each from startIndex on; -1
// last means "the rest".
std::string checkVertexCounts(const SoMFInt32& counts, std::int64_t start, std::int64_t available) {
  if (start < 0) return fmt::format("startIndex is {}", start);
  std::int64_t used = start;
  for (int i = 0; i < counts.getNum(); ++i) {
    const std::int32_t n = counts[i];
    if (n == -1 && i == counts.getNum() - 1) return {};
    if (n < 3) return fmt::format("numVertices[{}] is {}, a face needs at least 3", i, n);
    used += n;
    if (used > available) {
      return fmt::format("numVertices uses {} coordinates from startIndex {}, there are {}",
                         used - start, start, available);
    }
  }
  return {};
}

std::string checkQuadMesh(const SoQuadMesh& mesh, std::int64_t start, std::int64_t available) {
  const std::int64_t rows = mesh.verticesPerColumn.getValue();
  const std::int64_t columns = mesh.verticesPerRow.getValue();
  if (start < 0 || rows < 0 || columns < 0) return "startIndex or vertex counts are negative";
  if (start + rows * columns > available) {
    return fmt::format("the mesh needs {} coordinates from startIndex {}, there are {}",
                       rows * columns, start, available);
  }
  return {};
}

ShapeVerdict checkInventorVertexShape(SoCallbackAction& action, SoVertexShape& shape) {
  const std::int64_t count = coordinateCount(action, shape);
  if (count < 0) return reject(shape, "vertexProperty holds a node that is not a VertexProperty");
  std::string problem;
  if (shape.isOfType(SoIndexedShape::getClassTypeId())) {
    auto& indexed = static_cast<SoIndexedShape&>(shape);
    indexed.normalIndex.setValue(-1);
    indexed.materialIndex.setValue(-1);
    indexed.textureCoordIndex.setValue(-1);
    problem = checkIndices(indexed.coordIndex, "coordIndex", count);
  } else if (shape.isOfType(SoFaceSet::getClassTypeId())) {
    const auto& faces = static_cast<const SoFaceSet&>(shape);
    problem = checkVertexCounts(faces.numVertices, faces.startIndex.getValue(), count);
  } else if (shape.isOfType(SoTriangleStripSet::getClassTypeId())) {
    const auto& strips = static_cast<const SoTriangleStripSet&>(shape);
    problem = checkVertexCounts(strips.numVertices, strips.startIndex.getValue(), count);
  } else if (shape.isOfType(SoQuadMesh::getClassTypeId())) {
    const auto& quads = static_cast<const SoQuadMesh&>(shape);
    problem = checkQuadMesh(quads, quads.startIndex.getValue(), count);
  } else {
    return reject(shape, "this vertex shape type is not supported");
  }
  if (!problem.empty()) return reject(shape, problem);
  return {};
}

ShapeVerdict checkVrmlIndexedShape(SoVRMLIndexedShape& shape) {
  shape.normal.setValue(nullptr);
  shape.color.setValue(nullptr);
  shape.texCoord.setValue(nullptr);
  shape.normalIndex.setNum(0);
  shape.colorIndex.setNum(0);
  shape.texCoordIndex.setNum(0);
  const SoNode* coord = shape.coord.getValue();
  if (coord == nullptr) {
    if (shape.coordIndex.getNum() == 0) return {ShapeVerdict::Skip, {}};
    return reject(shape, "coordIndex without a coord Coordinate node");
  }
  if (!coord->isOfType(SoVRMLCoordinate::getClassTypeId())) {
    return reject(shape, "coord holds a node that is not a Coordinate");
  }
  const std::int64_t count = static_cast<const SoVRMLCoordinate*>(coord)->point.getNum();
  if (std::string problem = checkIndices(shape.coordIndex, "coordIndex", count); !problem.empty()) {
    return reject(shape, problem);
  }
  return {};
}

ShapeVerdict checkElevationGrid(SoVRMLElevationGrid& grid) {
  grid.normal.setValue(nullptr);
  grid.color.setValue(nullptr);
  grid.texCoord.setValue(nullptr);
  const std::int64_t x = grid.xDimension.getValue();
  const std::int64_t z = grid.zDimension.getValue();
  if (x < 2 || z < 2) return {ShapeVerdict::Skip, {}};
  if (grid.height.getNum() < x * z) {
    return reject(grid, fmt::format("xDimension x zDimension is {} but there are {} heights", x * z,
                                    grid.height.getNum()));
  }
  return {};
}

}  // namespace

bool pruneAppearance(SoNode& node) {
  if (node.isOfType(SoVertexProperty::getClassTypeId())) {
    clearAppearance(static_cast<SoVertexProperty&>(node));
    return false;
  }
  return isOfAnyType(
      node,
      {SoNormal::getClassTypeId(), SoNormalBinding::getClassTypeId(),
       SoMaterialBinding::getClassTypeId(), SoTexture::getClassTypeId(),
       SoTextureCoordinate2::getClassTypeId(), SoTextureCoordinate3::getClassTypeId(),
       SoTextureCoordinateBinding::getClassTypeId(), SoTextureCoordinateFunction::getClassTypeId(),
       SoBumpMapCoordinate::getClassTypeId(), SoVertexAttributeBinding::getClassTypeId()});
}

ShapeVerdict checkShape(SoCallbackAction& action, SoNode& shape) {
  if (yieldsNoTriangles(shape)) return {ShapeVerdict::Skip, {}};
  if (shape.isOfType(SoVRMLExtrusion::getClassTypeId())) {
    // Coin builds the whole swept surface before handing out a triangle: bound it first.
    const auto& extrusion = static_cast<const SoVRMLExtrusion&>(shape);
    const std::int64_t quads = static_cast<std::int64_t>(extrusion.spine.getNum()) *
                               static_cast<std::int64_t>(extrusion.crossSection.getNum());
    if (quads > kMaxExtrusionQuads) {
      return reject(shape, fmt::format("the extrusion sweeps {} cross-section points along {} "
                                       "spine points, more than {} quadrilaterals",
                                       extrusion.crossSection.getNum(), extrusion.spine.getNum(),
                                       kMaxExtrusionQuads));
    }
  }
  if (isParametric(shape)) return {};
  if (shape.isOfType(SoVertexShape::getClassTypeId())) {
    return checkInventorVertexShape(action, static_cast<SoVertexShape&>(shape));
  }
  if (shape.isOfType(SoVRMLIndexedShape::getClassTypeId())) {
    return checkVrmlIndexedShape(static_cast<SoVRMLIndexedShape&>(shape));
  }
  if (shape.isOfType(SoVRMLElevationGrid::getClassTypeId())) {
    return checkElevationGrid(static_cast<SoVRMLElevationGrid&>(shape));
  }
  return reject(shape, "this shape type is not supported (only polygonal and primitive shapes)");
}

}  // namespace graspkit::detail
