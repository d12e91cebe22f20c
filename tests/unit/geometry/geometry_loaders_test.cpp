// Geometry loaders: OFF text, Inventor and VRML through Coin, STL/OBJ/PLY through assimp, and
// the errors for bad input, which must name the file (and the line where the reader knows it).
// Truths: hand-counted triangles, closed-form volumes, and GraspIt!'s own triangle counts for
// its models (reference/graspit-figures.json).

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "graspkit/base/error.hpp"
#include "graspkit/base/log.hpp"
#include "graspkit/geometry/mass_properties.hpp"
#include "graspkit/geometry/mesh_loader.hpp"
#include "test_paths.hpp"
#include "xml_scan.hpp"

namespace graspkit {
namespace {

namespace fs = std::filesystem;
using test::readText;
using test::tagTexts;

fs::path writeFile(const fs::path& dir, const std::string& name, const std::string& text) {
  const fs::path path = dir / name;
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

// Runs `load` and returns the graspkit::Error it must throw; fails the test otherwise.
template <typename Load>
Error expectError(Load&& load) {
  try {
    load();
  } catch (const Error& error) {
    return error;
  }
  ADD_FAILURE() << "expected a graspkit::Error";
  return Error("no error");
}

void expectLocatedError(const Error& error, const std::string& file, int line,
                        const std::string& says) {
  const std::string what = error.what();
  EXPECT_NE(what.find(file), std::string::npos) << what;
  if (line > 0) {
    EXPECT_EQ(error.where().line, line) << what;
    EXPECT_NE(what.find(file + ":" + std::to_string(line) + ":"), std::string::npos) << what;
  }
  EXPECT_NE(what.find(says), std::string::npos) << what;
}

Vector3 boundsMin(const TriangleMesh& mesh) {
  Vector3 low = mesh.vertices.front();
  for (const Vector3& v : mesh.vertices) low = low.cwiseMin(v);
  return low;
}

Vector3 boundsMax(const TriangleMesh& mesh) {
  Vector3 high = mesh.vertices.front();
  for (const Vector3& v : mesh.vertices) high = high.cwiseMax(v);
  return high;
}

// ---------------------------------------------------------------------------------------------
// OFF

constexpr const char* kOffCube = R"(OFF
# a unit cube, one quad per face
8 6 12
0 0 0
1 0 0
1 1 0
0 1 0
0 0 1
1 0 1
1 1 1
0 1 1   # vertex 7
4 0 3 2 1
4 4 5 6 7
4 0 1 5 4
4 2 3 7 6
4 1 2 6 5
4 0 4 7 3
)";

TEST(OffParser, CubeQuadsBecomeTwelveTrianglesOfVolumeOne) {
  const TriangleMesh cube = parseOff(kOffCube, "cube.off");
  EXPECT_EQ(cube.vertices.size(), 8u);
  EXPECT_EQ(cube.triangleCount(), 12u);
  EXPECT_TRUE(isClosed(cube));
  const MassProperties props = computeMassProperties(cube);
  ASSERT_TRUE(props.valid);
  EXPECT_NEAR(props.volume, 1.0, 1e-12);
  EXPECT_NEAR((props.centroid - Vector3(0.5, 0.5, 0.5)).norm(), 0.0, 1e-12);
}

TEST(OffParser, PolygonIsTriangulatedAsFanFromFirstVertex) {
  const TriangleMesh hexagon =
      parseOff("OFF\n6 1 0\n2 0 0\n1 2 0\n-1 2 0\n-2 0 0\n-1 -2 0\n1 -2 0\n6 0 1 2 3 4 5\n", "h");
  ASSERT_EQ(hexagon.triangleCount(), 4u);
  for (std::uint32_t k = 0; k < 4; ++k) {
    EXPECT_EQ(hexagon.triangles[k], (std::array<std::uint32_t, 3>{0, k + 1, k + 2}));
  }
}

TEST(OffParser, HeaderVariantsAreAccepted) {
  const char* tetra_body = "0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
  for (const std::string header : {"OFF\n4 4 6\n", "4 4 6\n", "OFF 4 4 6\n", "OFF4 4 6\n",
                                   "# leading comment\n\nOFF\r\n4 4\n"}) {
    SCOPED_TRACE(header);
    const TriangleMesh tetra = parseOff(header + tetra_body, "t.off");
    ASSERT_EQ(tetra.triangleCount(), 4u);
    EXPECT_NEAR(computeMassProperties(tetra).volume, 1.0 / 6.0, 1e-12);
  }
}

TEST(OffParser, ColoursAfterCoordinatesAndIndicesAreIgnored) {
  const TriangleMesh tetra = parseOff(
      "COFF\n4 4 6\n0 0 0 255 0 0 255\n1 0 0 0 255 0 255\n0 1 0 0 0 255 255\n0 0 1 9 9 9 9\n"
      "3 0 2 1 0.5 0.5 0.5\n3 0 1 3 1 0 0\n3 0 3 2 0 1 0\n3 1 2 3 0 0 1\n",
      "colour.off");
  EXPECT_EQ(tetra.triangleCount(), 4u);
  EXPECT_EQ(tetra.vertices[3], Vector3(0, 0, 1));
}

struct BadOff {
  const char* name;
  const char* text;
  int line;
  const char* says;
};

class OffParserErrors : public ::testing::TestWithParam<BadOff> {};

TEST_P(OffParserErrors, NameFileAndLine) {
  const BadOff& bad = GetParam();
  const Error error = expectError([&] { parseOff(bad.text, "model.off"); });
  expectLocatedError(error, "model.off", bad.line, bad.says);
}

INSTANTIATE_TEST_SUITE_P(
    Off, OffParserErrors,
    ::testing::Values(
        BadOff{"Empty", "", 0, "empty file"}, BadOff{"UnknownHeader", "PLY\n3 1 0\n", 1, "'PLY'"},
        BadOff{"FourD", "4OFF\n1 1 0\n", 1, "only 3-D OFF"},
        BadOff{"Binary", "OFF BINARY\n", 1, "binary OFF"},
        BadOff{"CountNotInteger", "OFF\n8 six 0\n", 2, "face count 'six' is not an integer"},
        BadOff{"NegativeCount", "OFF\n-8 6 0\n", 2, "vertex count -8 is out of range"},
        BadOff{"CountTooLarge", "OFF\n99999999999 6 0\n", 2, "out of range"},
        BadOff{"TooFewCounts", "OFF\n8\n", 2, "found 1 numbers"},
        BadOff{"ShortVertex", "OFF\n3 1 0\n0 0 0\n1 0\n0 1 0\n3 0 1 2\n", 4, "vertex 1 has 2"},
        BadOff{"NaN", "OFF\n3 1 0\n0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n", 4, "non-finite"},
        BadOff{"Inf", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 -inf\n3 0 1 2\n", 5, "non-finite"},
        BadOff{"Overflow", "OFF\n3 1 0\n0 0 1e999\n1 0 0\n0 1 0\n3 0 1 2\n", 3, "non-finite"},
        BadOff{"NotANumber", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 zero\n3 0 1 2\n", 5, "'zero'"},
        BadOff{"MissingVertices", "OFF\n8 1 0\n0 0 0\n1 0 0\n", 4, "after 2 of 8 vertices"},
        BadOff{"MissingFaces", "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", 6, "after 1 of 2"},
        BadOff{"IndexTooLarge",
               "OFF\n8 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n4 0 1 2 99\n",
               11, "face 0 has vertex index 99, the file has 8 vertices"},
        BadOff{"NegativeIndex", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n", 6, "index -1"},
        BadOff{"TwoCornerFace", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n", 6, "at least 3"},
        BadOff{"FaceShorterThanCount", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n5 0 1 2\n", 6,
               "lists 5 vertices but the line holds only 3"},
        BadOff{"HugeCornerCount", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n9223372036854775807 0\n", 6,
               "lists 9223372036854775807"}),
    [](const ::testing::TestParamInfo<BadOff>& info) { return std::string(info.param.name); });

// Geometry with no triangles loads, as in GraspIt! (which says "No triangles found" and goes
// on): an empty mesh and one warning naming the file, for each format.
TEST(EmptyGeometry, LoadsEmptyWithAWarning) {
  const fs::path folder = test::scratchDir();
  const std::pair<const char*, const char*> files[] = {
      {"separator.iv", "#Inventor V2.1 ascii\nSeparator { }\n"},
      {"comments.wrl", "#VRML V1.0 ascii\n# nothing but comments\n"},
      {"faceset.wrl",
       "#VRML V2.0 utf8\nShape { geometry IndexedFaceSet { coord Coordinate { "
       "point [ ] } coordIndex [ ] } }\n"},
      {"nofaces.off", "OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n"}};
  for (const auto& [name, text] : files) {
    SCOPED_TRACE(name);
    std::vector<std::string> warnings;
    const WarningHandler previous = setWarningHandler([&](const Warning& warning) {
      EXPECT_EQ(warning.kind, WarningKind::Geometry);
      warnings.push_back(describe(warning));
    });
    const TriangleMesh mesh = loadMesh(writeFile(folder, name, text));
    setWarningHandler(previous);
    EXPECT_TRUE(mesh.triangles.empty());
    ASSERT_EQ(warnings.size(), 1u) << ::testing::PrintToString(warnings);
    EXPECT_NE(warnings[0].find(name), std::string::npos) << warnings[0];
    EXPECT_NE(warnings[0].find("holds no triangles"), std::string::npos) << warnings[0];
  }
}

TEST(OffParser, HugeDeclaredCountsDoNotAllocateUpFront) {
  // 4e9 vertices would be ~100 GB reserved up front; the parser must fail on the missing lines.
  const Error error = expectError([] { parseOff("OFF\n4000000000 4000000000 0\n0 0 0\n", "big"); });
  expectLocatedError(error, "big", 3, "after 1 of 4000000000 vertices");
}

TEST(OffParser, GarbageNeverEscapesAsAnythingButError) {
  const std::string samples[] = {std::string("OFF\n3 1 0\n\0\0\0\n", 14), "OFF\n\xff\xfe\n",
                                 "OFF\n3 1 0\n0 0 0\n0 0 0\n0 0 0\n3 0 0 0\n", "}}}}{{{{",
                                 "OFF\n1 1 0\n+-1 0 0\n3 0 0 0\n"};
  for (const std::string& text : samples) {
    try {
      const TriangleMesh mesh = parseOff(text, "garbage");
      for (const auto& t : mesh.triangles) {
        for (std::uint32_t i : t) EXPECT_LT(i, mesh.vertices.size());
      }
    } catch (const Error& error) {
      EXPECT_NE(std::string(error.what()).find("garbage"), std::string::npos);
    }
  }
}

TEST(MeshLoader, OffFileLoadsThroughLoadMesh) {
  const fs::path path = writeFile(test::scratchDir(), "cube.OFF", kOffCube);
  EXPECT_EQ(meshFormatFromExtension(path), MeshFormat::Off);
  const TriangleMesh cube = loadMesh(path);
  EXPECT_EQ(cube.triangleCount(), 12u);
  EXPECT_NEAR(computeMassProperties(cube).volume, 1.0, 1e-12);
}

TEST(MeshLoader, FormatFollowsExtensionCaseInsensitively) {
  EXPECT_EQ(meshFormatFromExtension("a/b.iv"), MeshFormat::Inventor);
  EXPECT_EQ(meshFormatFromExtension("ashtray.IV"), MeshFormat::Inventor);
  EXPECT_EQ(meshFormatFromExtension("shoe.wrl"), MeshFormat::Inventor);
  EXPECT_EQ(meshFormatFromExtension("m.off"), MeshFormat::Off);
  EXPECT_EQ(meshFormatFromExtension("m.Ply"), MeshFormat::Ply);
  EXPECT_EQ(meshFormatFromExtension("m.stl"), MeshFormat::Stl);
  EXPECT_EQ(meshFormatFromExtension("m.STLB"), MeshFormat::Stl);
  EXPECT_EQ(meshFormatFromExtension("m.obj"), MeshFormat::Obj);
  EXPECT_EQ(meshFormatFromExtension("m.xyz"), MeshFormat::Inventor);
  EXPECT_EQ(meshFormatFromExtension("noextension"), MeshFormat::Inventor);
}

TEST(MeshLoader, MissingFileIsNamed) {
  const fs::path path = test::scratchDir() / "no_such_mesh.iv";
  expectLocatedError(expectError([&] { loadMesh(path); }), path.string(), 0, "file not found");
}

TEST(MeshLoader, DirectoryIsRejected) {
  const fs::path dir = test::scratchDir();
  expectLocatedError(expectError([&] { loadMesh(dir); }), dir.string(), 0, "not a regular file");
}

// ---------------------------------------------------------------------------------------------
// Inventor and VRML

constexpr const char* kInventorHeader = "#Inventor V2.1 ascii\n\n";
constexpr const char* kTetraCoordinates =
    "Coordinate3 { point [ 0 0 0, 10 0 0, 0 10 0, 0 0 10 ] }\n";

TriangleMesh loadInventorText(const std::string& name, const std::string& body) {
  return loadMesh(writeFile(test::scratchDir(), name, kInventorHeader + body));
}

TEST(InventorLoader, CubeNodeIsTwelveTrianglesOfItsVolume) {
  const TriangleMesh cube = loadInventorText("cube.iv", "Cube { width 2 height 4 depth 6 }\n");
  EXPECT_EQ(cube.triangleCount(), 12u);
  EXPECT_EQ(cube.vertices.size(), 8u);
  EXPECT_TRUE(isClosed(cube));
  const MassProperties props = computeMassProperties(cube);
  ASSERT_TRUE(props.valid);
  EXPECT_NEAR(props.volume, 48.0, 1e-9);
  EXPECT_NEAR(props.inertia(0, 0), (16.0 + 36.0) / 12.0, 1e-9);
  EXPECT_NEAR(props.inertia(2, 2), (4.0 + 16.0) / 12.0, 1e-9);
}

TEST(InventorLoader, TransformMovesAndScalesTheShapes) {
  const TriangleMesh cube = loadInventorText(
      "moved.iv", "Transform { translation 10 0 0 scaleFactor 2 2 2 }\nCube { }\n");
  EXPECT_EQ(boundsMin(cube), Vector3(8, -2, -2));
  EXPECT_EQ(boundsMax(cube), Vector3(12, 2, 2));
  const MassProperties props = computeMassProperties(cube);
  EXPECT_NEAR(props.volume, 64.0, 1e-9);
  EXPECT_NEAR((props.centroid - Vector3(10, 0, 0)).norm(), 0.0, 1e-9);
}

TEST(InventorLoader, SeparatorScopesTransforms) {
  const TriangleMesh cubes = loadInventorText(
      "scoped.iv",
      "Separator { Translation { translation 0 0 100 } Cube { } }\nCube { width 4 }\n");
  EXPECT_EQ(cubes.triangleCount(), 24u);
  EXPECT_EQ(boundsMin(cubes), Vector3(-2, -1, -1));
  EXPECT_EQ(boundsMax(cubes), Vector3(2, 1, 101));
}

TEST(InventorLoader, MirroringScaleKeepsOutwardWinding) {
  const TriangleMesh cube =
      loadInventorText("mirror.iv", "Scale { scaleFactor -1 1 1 }\nCube {}\n");
  const MassProperties props = computeMassProperties(cube);
  ASSERT_TRUE(props.valid);
  EXPECT_NEAR(props.volume, 8.0, 1e-9);
}

TEST(InventorLoader, SphereIsTessellatedOnItsRadius) {
  const TriangleMesh sphere = loadInventorText("sphere.iv", "Sphere { radius 5 }\n");
  EXPECT_GT(sphere.triangleCount(), 100u);
  for (const Vector3& v : sphere.vertices) EXPECT_NEAR(v.norm(), 5.0, 1e-5);
  const MassProperties props = computeMassProperties(sphere);
  ASSERT_TRUE(props.valid);  // closed geometrically, though Coin leaves its seams unwelded
  EXPECT_LT(props.volume, 4.0 / 3.0 * M_PI * 125.0);
  EXPECT_GT(props.volume, 0.9 * 4.0 / 3.0 * M_PI * 125.0);
}

TEST(InventorLoader, IndexedFaceSetTetrahedronHasClosedFormMassProperties) {
  // Right tetrahedron with legs 10: volume 1000/6, centroid 10/4, and per unit mass
  // Ixx = 3/40 * 10^2, Ixy = 1/80 * 10^2.
  const TriangleMesh tetra = loadInventorText(
      "tetra.iv", std::string(kTetraCoordinates) +
                      "IndexedFaceSet { coordIndex [ 0 2 1 -1, 0 1 3 -1, 0 3 2 -1, 1 2 3 -1 ] }\n");
  EXPECT_EQ(tetra.triangleCount(), 4u);
  EXPECT_EQ(tetra.vertices.size(), 4u);
  EXPECT_TRUE(isClosed(tetra));
  const MassProperties props = computeMassProperties(tetra);
  ASSERT_TRUE(props.valid);
  EXPECT_NEAR(props.volume, 1000.0 / 6.0, 1e-9);
  EXPECT_NEAR((props.centroid - Vector3(2.5, 2.5, 2.5)).norm(), 0.0, 1e-9);
  EXPECT_NEAR(props.inertia(0, 0), 7.5, 1e-9);
  EXPECT_NEAR(props.inertia(0, 1), 1.25, 1e-9);
}

TEST(InventorLoader, FaceSetQuadsAreSplitInTwo) {
  const TriangleMesh quads = loadInventorText(
      "quads.iv",
      "Coordinate3 { point [ 0 0 0, 1 0 0, 1 1 0, 0 1 0, 0 0 1, 1 0 1, 1 1 1, 0 1 1 ] }\n"
      "FaceSet { numVertices [ 4, 4 ] }\n");
  EXPECT_EQ(quads.triangleCount(), 4u);
}

TEST(InventorLoader, UpperCaseExtensionIsInventor) {
  const TriangleMesh cube = loadInventorText("CUBE.IV", "Cube { }\n");
  EXPECT_EQ(cube.triangleCount(), 12u);
}

TEST(InventorLoader, VrmlBoxLoads) {
  const TriangleMesh box = loadMesh(writeFile(
      test::scratchDir(), "box.wrl", "#VRML V2.0 utf8\nShape { geometry Box { size 2 4 6 } }\n"));
  EXPECT_EQ(box.triangleCount(), 12u);
  EXPECT_NEAR(computeMassProperties(box).volume, 48.0, 1e-9);
}

TEST(InventorLoader, VrmlTransformedIndexedFaceSetLoads) {
  const TriangleMesh tetra = loadMesh(
      writeFile(test::scratchDir(), "tetra.wrl",
                "#VRML V2.0 utf8\nTransform { translation 1 2 3 children [ Shape { geometry "
                "IndexedFaceSet { coord Coordinate { point [ 0 0 0, 1 0 0, 0 1 0, 0 0 1 ] } "
                "coordIndex [ 0 2 1 -1, 0 1 3 -1, 0 3 2 -1, 1 2 3 -1 ] } } ] }\n"));
  EXPECT_EQ(tetra.triangleCount(), 4u);
  const MassProperties props = computeMassProperties(tetra);
  EXPECT_NEAR(props.volume, 1.0 / 6.0, 1e-9);
  EXPECT_NEAR((props.centroid - Vector3(1.25, 2.25, 3.25)).norm(), 0.0, 1e-7);
}

TEST(InventorLoader, AppearanceWithBadIndicesDoesNotMatter) {
  // Normals and materials are never needed for geometry; a normalIndex past the Normal node
  // would crash Coin if it were used.
  const TriangleMesh triangle = loadInventorText(
      "normals.iv",
      std::string(kTetraCoordinates) +
          "Normal { vector [ 0 0 1 ] } NormalBinding { value PER_VERTEX_INDEXED }\n"
          "IndexedFaceSet { coordIndex [ 0 1 2 -1 ] normalIndex [ 0 5000000 0 -1 ] }\n");
  EXPECT_EQ(triangle.triangleCount(), 1u);
}

struct BadScene {
  const char* name;
  const char* file;
  const char* text;
  int line;
  const char* says;
};

class InventorLoaderErrors : public ::testing::TestWithParam<BadScene> {};

TEST_P(InventorLoaderErrors, NameTheFile) {
  const BadScene& bad = GetParam();
  const fs::path path = writeFile(test::scratchDir(), bad.file, bad.text);
  expectLocatedError(expectError([&] { loadMesh(path); }), path.string(), bad.line, bad.says);
}

INSTANTIATE_TEST_SUITE_P(
    Inventor, InventorLoaderErrors,
    ::testing::Values(
        BadScene{"Truncated", "truncated.iv", "#Inventor V2.1 ascii\nSeparator {\n Cube {\n", 4,
                 "Expected '}'"},
        BadScene{"UnknownField", "field.iv", "#Inventor V2.1 ascii\nCube {\n bogus 3\n}\n", 3,
                 "Unknown field"},
        BadScene{"UnknownNode", "node.iv", "#Inventor V2.1 ascii\nNoSuchNode { }\n", 2,
                 "NoSuchNode"},
        BadScene{"NotInventor", "text.iv", "hello\n", 1, "not an Inventor or VRML file"},
        BadScene{"Binary", "binary.iv", "#Inventor V2.1 binary\n\x01\x02", 1, "binary"},
        BadScene{"CoordIndexPastCoordinates", "index.iv",
                 "#Inventor V2.1 ascii\nCoordinate3 { point [ 0 0 0, 1 0 0, 0 1 0 ] }\n"
                 "IndexedFaceSet { coordIndex [ 0 1 2 -1, 0 1 99 -1 ] }\n",
                 0, "coordIndex[6] is 99, there are 3 coordinates"},
        BadScene{"FaceSetPastCoordinates", "faceset.iv",
                 "#Inventor V2.1 ascii\nCoordinate3 { point [ 0 0 0, 1 0 0, 0 1 0 ] }\n"
                 "FaceSet { numVertices [ 3, 3 ] }\n",
                 0, "numVertices uses 6 coordinates"},
        BadScene{"VrmlCoordIndexPastCoordinates", "index.wrl",
                 "#VRML V2.0 utf8\nShape { geometry IndexedFaceSet { coord Coordinate { point "
                 "[ 0 0 0, 1 0 0, 0 1 0 ] } coordIndex [ 0 1 2 -1, 0 1 57 -1 ] } }\n",
                 0, "coordIndex[6] is 57"},
        BadScene{"UseCycle", "cycle.iv",
                 "#Inventor V2.1 ascii\nDEF a Separator { Cube {} USE a }\n", 0, "cycle"},
        // File nodes are read by graspkit, not by Coin, however they are spelled or spaced: a
        // file that includes itself is a cycle, never a stack overflow.
        BadScene{"FileNodeSelfInclude", "file.iv",
                 "#Inventor V2.1 ascii\nFile { name \"file.iv\" }\n", 2, "a cycle"},
        BadScene{"FileNodeBehindComment", "file_comment.iv",
                 "#Inventor V2.1 ascii\nFile # a comment\n{ name \"file_comment.iv\" }\n", 2,
                 "a cycle"},
        BadScene{"FileNodeBehindFormFeed", "file_ff.iv",
                 "#Inventor V2.1 ascii\nFile\f{ name \"file_ff.iv\" }\n", 2, "a cycle"},
        BadScene{"FileNodeBehindComma", "file_comma.iv",
                 "#Inventor V2.1 ascii\nFile , { name \"file_comma.iv\" }\n", 2, "a cycle"},
        BadScene{"SoFileSpelling", "sofile.iv",
                 "#Inventor V2.1 ascii\nSeparator {\n SoFile { name \"sofile.iv\" }\n}\n", 3,
                 "a cycle"},
        BadScene{"FileNodeAbsoluteName", "absolute.iv",
                 "#Inventor V2.1 ascii\nCube { }\nFile { name \"/etc/hostname\" }\n", 3,
                 "absolute path"},
        BadScene{"FileNodeOtherField", "field.iv", "#Inventor V2.1 ascii\nFile { url \"x.iv\" }\n",
                 2, "one field"},
        BadScene{"VrmlInline", "inline.wrl", "#VRML V2.0 utf8\nInline { url \"other.wrl\" }\n", 2,
                 "Inline nodes"},
        BadScene{"Vrml1WwwInline", "wwwinline.wrl",
                 "#VRML V1.0 ascii\nWWWInline { name \"other.wrl\" }\n", 2, "WWWInline nodes"},
        BadScene{"ExternProto", "extern.wrl",
                 "#VRML V2.0 utf8\nEXTERNPROTO Thing [ ] \"other.wrl\"\nThing { }\n", 2,
                 "EXTERNPROTO"},
        BadScene{"FontNode", "font.iv",
                 "#Inventor V2.1 ascii\nFont { name \"/dev/zero\" }\nText3 { string \"a\" }\n", 2,
                 "node type 'Font' is not supported"},
        BadScene{"Nurbs", "nurbs.iv",
                 "#Inventor V2.1 ascii\nCoordinate3 { point [ 0 0 0, 1 0 0, 0 1 0, 1 1 0 ] }\n"
                 "NurbsSurface { numUControlPoints 2 numVControlPoints 2 uKnotVector [ 0 0 1 1 ] "
                 "vKnotVector [ 0 0 1 1 ] }\n",
                 0, "not supported"}),
    [](const ::testing::TestParamInfo<BadScene>& info) { return std::string(info.param.name); });

TEST(InventorLoader, DeepNestingIsRejectedBeforeCoinRecurses) {
  // 200000 levels overflow Coin's recursive parser; the reader must refuse before that.
  std::string text = "#Inventor V2.1 ascii\n";
  for (int i = 0; i < 200000; ++i) text += "Separator {\n";
  const fs::path path = writeFile(test::scratchDir(), "deep.iv", text);
  expectLocatedError(expectError([&] { loadMesh(path); }), path.string(), 1002,
                     "nesting deeper than 1000 levels");
}

// An Array of spheres multiplies a few bytes into millions of shapes: bounded by the node and
// triangle limits, never by the machine's memory.
TEST(InventorLoader, AmplifyingArrayIsRejected) {
  const fs::path path = writeFile(
      test::scratchDir(), "array.iv",
      "#Inventor V2.1 ascii\nComplexity { value 1 }\nArray { numElements1 1000 numElements2 1000 "
      "numElements3 100 Sphere { } }\n");
  expectLocatedError(expectError([&] { loadMesh(path); }), path.string(), 0, "more than");
}

// Coin builds an extrusion's whole surface at once: its size is checked before. The issue's
// reproducer: 2000 by 2000 points in 60 KB ran for over 30 s.
TEST(InventorLoader, HugeExtrusionIsRejected) {
  std::string text = "#VRML V2.0 utf8\nShape { geometry Extrusion { crossSection [";
  for (int i = 0; i < 2000; ++i)
    text += fmt::format(" {} {},", std::cos(i * 0.002), std::sin(i * 0.002));
  text += " ] spine [";
  for (int i = 0; i < 2000; ++i) text += fmt::format(" 0 {} 0,", i);
  text += " ] } }\n";
  const fs::path path = writeFile(test::scratchDir(), "extrusion.wrl", text);
  expectLocatedError(expectError([&] { loadMesh(path); }), path.string(), 0,
                     "more than 250000 quadrilaterals");
}

// Loads `path`, which names the FIFO `fifo` somewhere inside, and checks the load never opened
// it: a reader that opens a FIFO blocks until a writer comes. A writer comes after 5 s to free a
// blocked reader, so a regression fails the test (the load took too long) instead of hanging it.
TriangleMesh loadWithoutOpeningFifo(const fs::path& path, const fs::path& fifo) {
  std::atomic<bool> loaded{false};
  std::thread unblock([&] {
    for (int i = 0; i < 50 && !loaded; ++i)
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    if (!loaded) {
      const int fd = open(fifo.c_str(), O_WRONLY | O_NONBLOCK);
      if (fd >= 0) close(fd);
    }
  });
  const auto start = std::chrono::steady_clock::now();
  TriangleMesh mesh;
  EXPECT_NO_THROW(mesh = loadMesh(path));
  loaded = true;
  unblock.join();
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(4));
  return mesh;
}

// A fresh FIFO in the scratch folder.
fs::path makeFifo(const std::string& name) {
  const fs::path fifo = test::scratchDir() / name;
  fs::remove(fifo);
  EXPECT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  return fifo;
}

// A texture's file name is blanked before Coin parses (textures are never used): a FIFO there
// would block Coin's image loader forever.
TEST(InventorLoader, TextureFileNamesAreNeverOpened) {
  const fs::path fifo = makeFifo("texture.fifo");
  const fs::path path = writeFile(test::scratchDir(), "texture.iv",
                                  "#Inventor V2.1 ascii\nSeparator {\n Texture2 { filename \"" +
                                      fifo.string() + "\" }\n Cube { }\n}\n");
  EXPECT_EQ(loadWithoutOpeningFifo(path, fifo).triangles.size(), 12u);  // the cube
  fs::remove(fifo);
}

TEST(InventorLoader, SelfMultiplyingSceneIsRejected) {
  // Each group USEs the previous one twice: 2^40 cubes if traversed.
  std::string text = "#Inventor V2.1 ascii\nDEF g0 Group { Cube { } }\n";
  for (int i = 1; i <= 40; ++i) {
    text += "DEF g" + std::to_string(i) + " Group { USE g" + std::to_string(i - 1) + " USE g" +
            std::to_string(i - 1) + " }\n";
  }
  const fs::path path = writeFile(test::scratchDir(), "bomb.iv", text);
  expectLocatedError(expectError([&] { loadMesh(path); }), path.string(), 0, "more than");
}

// ---------------------------------------------------------------------------------------------
// File nodes: geometry split over several files

// Coin reads an unquoted string as one word: `File { name sub/b.wrl }` (as GraspIt!'s ARMAR
// hand writes it) includes the same file as the quoted form, and gives the same mesh.
TEST(InventorFileNodes, AnUnquotedNameIncludesTheSameFile) {
  const fs::path folder = test::scratchDir();
  fs::create_directory(folder / "sub");
  writeFile(folder / "sub", "b.wrl", "#VRML V1.0 ascii\nSeparator { Cube { width 3 } }\n");
  writeFile(folder, "quoted.iv",
            "#Inventor V2.1 ascii\nSeparator {\n Sphere { }\n File { name \"sub/b.wrl\" }\n}\n");
  writeFile(folder, "unquoted.iv",
            "#Inventor V2.1 ascii\nSeparator {\n Sphere { }\n File { name sub/b.wrl }\n}\n");
  const TriangleMesh quoted = loadMesh(folder / "quoted.iv");
  const TriangleMesh unquoted = loadMesh(folder / "unquoted.iv");
  ASSERT_GT(quoted.triangles.size(), 12u);
  EXPECT_EQ(unquoted.triangles.size(), quoted.triangles.size());
  EXPECT_EQ(unquoted.vertices, quoted.vertices);
}

// A scene split over files (an Inventor file including a VRML 1.0 file and an Inventor file that
// includes the VRML one again, DEF'd and USEd) gives what Coin gives for the same scene written
// in one file: the second method. Included nodes go where the File node was, without a
// separator, as Coin's SoFile adds them (the Translation in c.iv moves what follows it).
TEST(InventorFileNodes, SplitSceneEqualsTheSameSceneInOneFile) {
  const fs::path folder = test::scratchDir();
  writeFile(folder, "a.iv",
            "#Inventor V2.1 ascii\nSeparator {\n Cube { }\n Translation { translation 5 0 0 }\n"
            " File { name \"sub/b.wrl\" }\n DEF again File { name \"sub/c.iv\" }\n USE again\n}\n");
  fs::create_directory(folder / "sub");
  writeFile(folder / "sub", "b.wrl", "#VRML V1.0 ascii\nSeparator { Cube { width 3 } }\n");
  writeFile(folder / "sub", "c.iv",
            "#Inventor V2.1 ascii\nTranslation { translation 0 5 0 }\nSphere { }\n"
            "File { name \"b.wrl\" }\n");
  const fs::path one =
      writeFile(test::scratchDir(), "one.iv",
                "#Inventor V2.1 ascii\nSeparator {\n Cube { }\n Translation { translation 5 0 0 }\n"
                " Group { Separator { Cube { width 3 } } }\n"
                " DEF again Group { Translation { translation 0 5 0 } Sphere { }\n"
                "   Group { Separator { Cube { width 3 } } } }\n USE again\n}\n");
  const TriangleMesh split = loadMesh(folder / "a.iv");
  const TriangleMesh whole = loadMesh(one);
  ASSERT_GT(whole.triangles.size(), 36u);
  EXPECT_EQ(split.triangles.size(), whole.triangles.size());
  auto sorted = [](std::vector<Vector3> points) {
    std::sort(points.begin(), points.end(), [](const Vector3& p, const Vector3& q) {
      return std::lexicographical_compare(p.data(), p.data() + 3, q.data(), q.data() + 3);
    });
    return points;
  };
  EXPECT_EQ(sorted(split.vertices), sorted(whole.vertices));
}

// A name found nowhere is skipped with a warning (as in Coin); the rest of the scene loads.
TEST(InventorFileNodes, MissingIncludeWarnsAndIsSkipped) {
  const fs::path path = writeFile(test::scratchDir(), "missing.iv",
                                  "#Inventor V2.1 ascii\nCube { }\nFile { name \"nope.iv\" }\n");
  std::vector<std::string> warnings;
  const WarningHandler previous = setWarningHandler([&](const Warning& warning) {
    EXPECT_EQ(warning.kind, WarningKind::Geometry);
    warnings.push_back(describe(warning));
  });
  const TriangleMesh mesh = loadMesh(path);
  setWarningHandler(previous);
  EXPECT_EQ(mesh.triangles.size(), 12u);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("missing.iv:3"), std::string::npos) << warnings[0];
  EXPECT_NE(warnings[0].find("'nope.iv'"), std::string::npos) << warnings[0];
}

// An include that leaves the model's folder, by `..` or through a symbolic link, is refused; so
// is a FIFO (it would block), and a chain of includes deeper than the bound.
TEST(InventorFileNodes, IncludesStayInTheModelFolderAndAreBounded) {
  const fs::path root = test::scratchDir();
  fs::create_directories(root / "model");
  fs::create_directories(root / "elsewhere");
  writeFile(root / "elsewhere", "secret.iv", "#Inventor V2.1 ascii\nCube { }\n");
  const fs::path up = writeFile(root / "model", "up.iv",
                                "#Inventor V2.1 ascii\nFile { name \"../elsewhere/secret.iv\" }\n");
  expectLocatedError(expectError([&] { loadMesh(up); }), up.string(), 2, "outside the model's");
  fs::create_directory_symlink(root / "elsewhere", root / "model" / "link");
  const fs::path linked = writeFile(root / "model", "linked.iv",
                                    "#Inventor V2.1 ascii\nFile { name \"link/secret.iv\" }\n");
  expectLocatedError(expectError([&] { loadMesh(linked); }), linked.string(), 2,
                     "outside the model's");

  const fs::path fifo = root / "model" / "part.fifo";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  const fs::path via_fifo =
      writeFile(root / "model", "fifo.iv", "#Inventor V2.1 ascii\nFile { name \"part.fifo\" }\n");
  EXPECT_THROW(loadMesh(via_fifo), Error);

  for (int i = 0; i <= 20; ++i) {
    writeFile(root / "model", "chain" + std::to_string(i) + ".iv",
              "#Inventor V2.1 ascii\nCube { }\nFile { name \"chain" + std::to_string(i + 1) +
                  ".iv\" }\n");
  }
  expectLocatedError(expectError([&] { loadMesh(root / "model" / "chain0.iv"); }), "", 3,
                     "nest deeper than 16 files");
}

// ---------------------------------------------------------------------------------------------
// STL, OBJ, PLY through assimp

constexpr const char* kAsciiStlTetra = R"(solid tetra
facet normal 0 0 -1
 outer loop
  vertex 0 0 0
  vertex 0 10 0
  vertex 10 0 0
 endloop
endfacet
facet normal 0 -1 0
 outer loop
  vertex 0 0 0
  vertex 10 0 0
  vertex 0 0 10
 endloop
endfacet
facet normal -1 0 0
 outer loop
  vertex 0 0 0
  vertex 0 0 10
  vertex 0 10 0
 endloop
endfacet
facet normal 1 1 1
 outer loop
  vertex 10 0 0
  vertex 0 10 0
  vertex 0 0 10
 endloop
endfacet
endsolid tetra
)";

TEST(AssimpLoader, AsciiStlTetrahedron) {
  const TriangleMesh tetra = loadMesh(writeFile(test::scratchDir(), "tetra.stl", kAsciiStlTetra));
  EXPECT_EQ(tetra.triangleCount(), 4u);
  EXPECT_EQ(tetra.vertices.size(), 4u);  // welded by aiProcess_JoinIdenticalVertices
  EXPECT_TRUE(isClosed(tetra));
  const MassProperties props = computeMassProperties(tetra);
  ASSERT_TRUE(props.valid);
  EXPECT_NEAR(props.volume, 1000.0 / 6.0, 1e-6);
  EXPECT_NEAR(props.inertia(0, 0), 7.5, 1e-6);
}

TEST(AssimpLoader, BinaryStlWithStlbExtension) {
  // 80-byte header, triangle count, then per triangle: normal, three corners, attribute word.
  std::string data(80, ' ');
  auto put_u32 = [&](std::uint32_t v) { data.append(reinterpret_cast<const char*>(&v), 4); };
  auto put_f32 = [&](float v) { data.append(reinterpret_cast<const char*>(&v), 4); };
  const float corners[4][3] = {{0, 0, 0}, {10, 0, 0}, {0, 10, 0}, {0, 0, 10}};
  const int faces[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  put_u32(4);
  for (const auto& face : faces) {
    for (int k = 0; k < 3; ++k) put_f32(0);
    for (int corner : face) {
      for (float c : corners[corner]) put_f32(c);
    }
    data.append(2, '\0');
  }
  const TriangleMesh tetra = loadMesh(writeFile(test::scratchDir(), "tetra.stlb", data));
  EXPECT_EQ(tetra.triangleCount(), 4u);
  EXPECT_NEAR(computeMassProperties(tetra).volume, 1000.0 / 6.0, 1e-6);
}

TEST(AssimpLoader, ObjQuadsAreTriangulated) {
  const TriangleMesh cube = loadMesh(writeFile(test::scratchDir(), "cube.obj",
                                               "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                                               "v 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
                                               "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\n"
                                               "f 3 4 8 7\nf 2 3 7 6\nf 1 5 8 4\n"));
  EXPECT_EQ(cube.triangleCount(), 12u);
  EXPECT_NEAR(computeMassProperties(cube).volume, 1.0, 1e-9);
}

TEST(AssimpLoader, AsciiPlyTetrahedron) {
  const TriangleMesh tetra = loadMesh(
      writeFile(test::scratchDir(), "tetra.ply",
                "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                "property float z\nelement face 4\nproperty list uchar int vertex_indices\n"
                "end_header\n0 0 0\n10 0 0\n0 10 0\n0 0 10\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n"));
  EXPECT_EQ(tetra.triangleCount(), 4u);
  EXPECT_NEAR(computeMassProperties(tetra).volume, 1000.0 / 6.0, 1e-6);
}

// A header that promises more data than the file holds is refused before assimp reserves it:
// a billion vertices of 12 bytes in a file of a hundred bytes.
TEST(AssimpLoader, PlyHeaderPromisingMoreThanTheFileIsRefused) {
  const fs::path path = writeFile(
      test::scratchDir(), "promise.ply",
      "ply\nformat binary_little_endian 1.0\nelement vertex 1000000000\nproperty float x\n"
      "property float y\nproperty float z\nend_header\n0123456789");
  expectLocatedError(expectError([&] { loadMesh(path); }), path.string(), 7,
                     "1000000000 instances needs at least 12 bytes each");
  const fs::path typo = writeFile(test::scratchDir(), "typo.ply",
                                  "ply\nformat ascii 1.0\nelement vertex 1\nproperty flaot x\n"
                                  "end_header\n0\n");
  expectLocatedError(expectError([&] { loadMesh(typo); }), typo.string(), 4,
                     "unknown property type 'flaot'");
}

// An OBJ's material library is never opened (the geometry is all that is kept): a FIFO there
// would block the reader.
TEST(AssimpLoader, ObjMaterialLibraryIsNeverOpened) {
  const fs::path fifo = makeFifo("materials.fifo");
  const fs::path path = writeFile(test::scratchDir(), "with_mtl.obj",
                                  "mtllib " + fifo.filename().string() +
                                      "\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
                                      "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n");
  EXPECT_EQ(loadWithoutOpeningFifo(path, fifo).triangleCount(), 4u);
  fs::remove(fifo);
}

TEST(AssimpLoader, CorruptStlIsNamed) {
  const fs::path path = writeFile(test::scratchDir(), "broken.stl", "solid x\nfacet normal\n");
  const Error error = expectError([&] { loadMesh(path); });
  expectLocatedError(error, path.string(), 0, "");
}

// ---------------------------------------------------------------------------------------------
// GraspIt!'s models against GraspIt!'s own triangle counts

nlohmann::json referenceFigures() {
  std::ifstream in(*test::referenceFigures());
  return nlohmann::json::parse(in);
}

const nlohmann::json* massPropertiesEntry(const nlohmann::json& figures, const std::string& xml) {
  for (const auto& entry : figures["mass_properties"]) {
    if (entry["file"] == xml) return &entry;
  }
  return nullptr;
}

TEST(InventorLoaderGraspItModels, ObjectTriangleCountsMatchGraspIt) {
  GRASPKIT_REQUIRE_SHARED();
  const nlohmann::json figures = referenceFigures();
  const fs::path objects = *test::graspitDataDir() / "models" / "objects";
  for (const std::string geometry : {"mug.iv", "cube.iv", "sphere.iv", "box.iv", "flask.iv",
                                     "shoe_1741.wrl", "p51_small_jet_2.wrl"}) {
    SCOPED_TRACE(geometry);
    const std::string stem = fs::path(geometry).stem().string();
    const nlohmann::json* entry = massPropertiesEntry(figures, "models/objects/" + stem + ".xml");
    ASSERT_NE(entry, nullptr);
    const TriangleMesh mesh = loadMesh(objects / geometry);
    EXPECT_EQ(mesh.triangleCount(), (*entry)["triangles"].get<std::size_t>());
  }
}

TEST(InventorLoaderGraspItModels, BarrettHandTrianglesMatchGraspIt) {
  GRASPKIT_REQUIRE_SHARED();
  const fs::path barrett = *test::graspitDataDir() / "models" / "robots" / "Barrett";
  for (const auto& file : fs::directory_iterator(barrett / "iv")) {
    if (file.path().extension() != ".iv") continue;
    SCOPED_TRACE(file.path().string());
    EXPECT_FALSE(loadMesh(file.path()).empty());
  }
  // GraspIt!'s total for the hand counts the palm once and every link once per chain using it.
  const std::string robot = readText(barrett / "Barrett.xml");
  std::vector<std::string> bodies = tagTexts(robot, "palm");
  for (const std::string& link : tagTexts(robot, "link")) bodies.push_back(link);
  std::size_t total = 0;
  for (const std::string& body : bodies) {
    const std::string geometry = tagTexts(readText(barrett / "iv" / body), "geometryFile").at(0);
    total += loadMesh(barrett / "iv" / geometry).triangleCount();
  }
  std::size_t expected = 0;
  const nlohmann::json figures = referenceFigures();
  for (const auto& entry : figures["robot_survey_shared"]) {
    if (entry["file"] == "models/robots/Barrett/Barrett.xml") expected = entry["total_triangles"];
  }
  EXPECT_EQ(bodies.size(), 9u);
  EXPECT_EQ(total, expected);
}

}  // namespace
}  // namespace graspkit
