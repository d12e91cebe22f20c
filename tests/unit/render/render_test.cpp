// Pictures against closed forms: a sphere seen head-on covers the disc its silhouette cone
// cuts from the image plane, a box seen along an axis is a rectangle of the size its face
// projects to, a contact marker lands on the contact's projected pixel, and a framed sphere
// fills the view. PNG, tiles, Inventor colours and glTF are read back and compared.
#include <cmath>
#include <fstream>
#include <memory>

#include <gtest/gtest.h>
#include <tiny_gltf.h>
#include <nlohmann/json.hpp>

#include "graspkit/base/error.hpp"
#include "graspkit/geometry/mesh_loader.hpp"
#include "graspkit/io/gltf/gltf_file.hpp"
#include "graspkit/io/graspit/world_file.hpp"
#include "graspkit/model/body.hpp"
#include "graspkit/model/robot.hpp"
#include "graspkit/model/world.hpp"
#include "graspkit/render/image.hpp"
#include "graspkit/render/render.hpp"
#include "graspkit/render/text.hpp"
#include "test_meshes.hpp"
#include "test_paths.hpp"

namespace graspkit {
namespace {

// A box of half extents `h` about the origin, faces counter-clockwise seen from outside.
std::shared_ptr<TriangleMesh> box(const Vector3& h) {
  auto mesh = std::make_shared<TriangleMesh>();
  for (int i = 0; i < 8; ++i)
    mesh->vertices.push_back(
        Vector3(i & 1 ? h.x() : -h.x(), i & 2 ? h.y() : -h.y(), i & 4 ? h.z() : -h.z()));
  mesh->triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                     {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  return mesh;
}

int addBody(World& world, std::shared_ptr<TriangleMesh> mesh, const Vector3& at,
            Material material = Material::Plastic) {
  auto model = std::make_shared<BodyModel>();
  model->name = "shape";
  model->mesh = std::move(mesh);
  model->material = material;
  Body body;
  body.model = model;
  body.kind = BodyKind::Graspable;
  body.name = "shape";
  body.setPose(makeTransform(at, Quaternion::Identity()));
  return world.addBody(std::move(body));
}

bool isBackground(const Image& image, int x, int y) {
  const auto p = image.pixel(x, y);
  return p[0] == 255 && p[1] == 255 && p[2] == 255;
}

// The camera at the origin looking down -z (Inventor's default frame).
RenderRequest headOn(int width, int height, double heightAngle) {
  RenderRequest request;
  request.width = width;
  request.height = height;
  request.camera.heightAngle = heightAngle;
  return request;
}

// Pixels from the image centre to the pixel's centre.
double radiusOf(const Image& image, int x, int y) {
  return std::hypot(x + 0.5 - image.width / 2.0, y + 0.5 - image.height / 2.0);
}

TEST(Render, SphereCoversTheDiscOfItsSilhouette) {
  const double R = 50.0, D = 400.0, angle = 0.5;
  auto mesh = test::icosphere(R, 4);
  World world;
  addBody(world, mesh, Vector3(0, 0, -D));
  const Image image = render(world, headOn(201, 151, angle));
  // The silhouette cone has half angle asin(r/D); the image plane at unit distance spans
  // tan(angle/2) over half the height. The tessellated sphere lies between its inscribed
  // radius (level 4: > 0.998 R) and R.
  const double pixelsPerUnit = (151 / 2.0) / std::tan(angle / 2.0);
  const double outer = std::tan(std::asin(R / D)) * pixelsPerUnit;
  const double inner = std::tan(std::asin(0.998 * R / D)) * pixelsPerUnit;
  ASSERT_GT(inner, 30.0);
  int checked = 0;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const double r = radiusOf(image, x, y);
      if (r < inner - 1.0) {
        EXPECT_FALSE(isBackground(image, x, y)) << x << "," << y;
        ++checked;
      }
      if (r > outer + 1.0) {
        EXPECT_TRUE(isBackground(image, x, y)) << x << "," << y;
        ++checked;
      }
    }
  }
  EXPECT_GT(checked, 201 * 151 - 2 * M_PI * outer * 3);
}

TEST(Render, BoxSeenAlongAnAxisIsARectangleInItsColour) {
  const Vector3 half(40.0, 25.0, 10.0);
  auto mesh = box(half);
  mesh->triangleColours.assign(mesh->triangles.size(), Colour{1.0f, 0.0f, 0.0f});
  World world;
  addBody(world, mesh, Vector3(0, 0, -300.0));
  const double angle = 0.6;
  const Image image = render(world, headOn(240, 180, angle));
  // The front face (z = -290) projects to a rectangle of half sizes h / 290 on the unit plane.
  const double pixelsPerUnit = (180 / 2.0) / std::tan(angle / 2.0);
  const double halfWidth = half.x() / 290.0 * pixelsPerUnit;
  const double halfHeight = half.y() / 290.0 * pixelsPerUnit;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const double dx = std::abs(x + 0.5 - 120.0), dy = std::abs(y + 0.5 - 90.0);
      if (dx < halfWidth - 1.0 && dy < halfHeight - 1.0) {
        const auto p = image.pixel(x, y);
        EXPECT_GT(p[0], 100) << x << "," << y;  // the file's red, shaded
        EXPECT_EQ(p[1], 0) << x << "," << y;
        EXPECT_EQ(p[2], 0) << x << "," << y;
      }
      if (dx > halfWidth + 1.0 || dy > halfHeight + 1.0)
        EXPECT_TRUE(isBackground(image, x, y)) << x << "," << y;
    }
  }
}

TEST(Render, BodiesWithoutFileColoursTakeTheirMaterialColour) {
  World world;
  addBody(world, box(Vector3(40, 40, 10)), Vector3(0, 0, -300.0), Material::Glass);
  const Image image = render(world, headOn(64, 48, 0.6));
  const auto p = image.pixel(32, 24);
  const Colour glass = materialColour(Material::Glass);
  // Shading scales all three channels alike: the ratios are the material's.
  EXPECT_NEAR(static_cast<double>(p[0]) / p[2], glass.r / glass.b, 0.02);
  EXPECT_NEAR(static_cast<double>(p[1]) / p[2], glass.g / glass.b, 0.02);
}

TEST(Render, ContactMarkerLandsOnTheContactsPixel) {
  World world;
  addBody(world, box(Vector3(40, 25, 10)), Vector3(0, 0, -300.0), Material::Metal);
  RenderRequest request = headOn(320, 240, 0.6);
  Contact contact;
  contact.position2 = Vector3(17.0, -9.0, -290.0);  // on the front face
  contact.normal = Vector3::UnitZ();
  contact.mu = 0.5;
  const auto at = projectPoint(request.camera, 320, 240, contact.position2);
  ASSERT_TRUE(at);
  const int x = static_cast<int>(at->x()), y = static_cast<int>(at->y());
  const auto before = render(world, request).pixel(x, y);
  request.contacts = {contact};
  const auto after = render(world, request).pixel(x, y);
  EXPECT_NEAR(before[0], before[2], 30);  // metal grey
  EXPECT_GT(after[0], 2 * after[1]);      // the marker's red
  EXPECT_GT(after[0], 2 * after[2]);
  // The projection is the render's: x = f tan(atan(17/290)) + W/2 with f = H/2 / tan(angle/2).
  const double f = 120.0 / std::tan(0.3);
  EXPECT_NEAR(at->x(), 160.0 + f * 17.0 / 290.0, 1e-9);
  EXPECT_NEAR(at->y(), 120.0 + f * 9.0 / 290.0, 1e-9);
  EXPECT_FALSE(projectPoint(request.camera, 320, 240, Vector3(0, 0, 10)));  // behind
}

// A hand of one link, its palm a box of half extents `h` at `at`, in `material`'s colour.
void addPalmHand(World& world, const Vector3& h, const Vector3& at, Material material) {
  auto palm = std::make_shared<BodyModel>();
  palm->name = "palm";
  palm->mesh = box(h);
  palm->material = material;
  auto model = std::make_shared<RobotModel>();
  model->name = "paddle";
  model->palm = palm;
  const int robot = world.addRobot(Robot(model));
  world.setRobotPose(robot, makeTransform(at, Quaternion::Identity()));
}

int redness(const std::array<std::uint8_t, 3>& p) {
  return p[0] - std::max(p[1], p[2]);
}

// A metal box with a contact on its face, seen head-on, and a metal palm between the camera and
// the contact: solid, the palm hides the contact's marker; outline and transparent show it.
TEST(Render, OutlineHandShowsAContactTheFingerHides) {
  World world;
  addBody(world, box(Vector3(40, 25, 10)), Vector3(0, 0, -300.0), Material::Metal);
  addPalmHand(world, Vector3(20, 20, 5), Vector3(0, 0, -250.0), Material::Metal);
  RenderRequest request = headOn(320, 240, 0.6);
  Contact contact;
  contact.body2 = BodyRef::body(0);
  contact.position2 = Vector3(3.0, -2.0, -290.0);
  contact.normal = Vector3::UnitZ();
  contact.mu = 0.5;
  request.contacts = {contact};
  const auto at = projectPoint(request.camera, 320, 240, contact.position2);
  ASSERT_TRUE(at);
  const int x = static_cast<int>(at->x()), y = static_cast<int>(at->y());
  const auto solid = render(world, request).pixel(x, y);
  EXPECT_LT(redness(solid), 10) << "solid palm: " << +solid[0] << " " << +solid[1];
  request.hand = HandStyle::Outline;
  const Image outline = render(world, request);
  EXPECT_GT(redness(outline.pixel(x, y)), 100);
  request.hand = HandStyle::Transparent;
  EXPECT_GT(redness(render(world, request).pixel(x, y)), 40);
  // The palm's silhouette is drawn dark in outline: its left edge (x = -20 at z = -245) is a
  // dark line where the box behind it shows grey on both sides.
  const auto edge = projectPoint(request.camera, 320, 240, Vector3(-20.0, 10.0, -245.0));
  ASSERT_TRUE(edge);
  int darkest = 255;
  for (int dx = -2; dx <= 2; ++dx)
    darkest = std::min<int>(
        darkest, outline.pixel(static_cast<int>(edge->x()) + dx, static_cast<int>(edge->y()))[1]);
  const auto inside = outline.pixel(static_cast<int>(edge->x()) + 8, static_cast<int>(edge->y()));
  EXPECT_LT(darkest, inside[1] / 2);
  // Without a hand in the way, the solid picture shows the marker too.
  World bare;
  addBody(bare, box(Vector3(40, 25, 10)), Vector3(0, 0, -300.0), Material::Metal);
  request.hand = HandStyle::Solid;
  EXPECT_GT(redness(render(bare, request).pixel(x, y)), 100);
}

// A sphere floating over the floor (a small cube lower down sets the floor's height): the floor
// straight under the sphere is in its shadow, darker than the floor to its left and right.
TEST(Render, FloorShowsTheShadowUnderABody) {
  World world;
  const double R = 30.0;
  const int sphere = addBody(world, test::icosphere(R, 3), Vector3(0, 0, 30.0));
  const int cube = addBody(world, box(Vector3(5, 5, 5)), Vector3(0, -160.0, -15.0));
  RenderRequest request;
  request.width = 320;
  request.height = 240;
  request.camera = frameBodies(world, {}, Vector3(1.0, -1.3, 0.9), 320.0 / 240.0);
  request.focus = {BodyRef::body(sphere), BodyRef::body(cube)};
  const Image bare = render(world, request);
  request.floor = true;
  const Image floor = render(world, request);
  // The floor lies just under the cube's bottom (z = -20), by at most 1 % of the focus radius.
  const double z = -20.5;
  const Matrix3 axes = request.camera.orientation.toRotationMatrix();
  const Vector3 right(axes(0, 0), axes(1, 0), 0.0);
  const auto pixelOf = [&](const Vector3& p) {
    const auto at = projectPoint(request.camera, 320, 240, p);
    EXPECT_TRUE(at);
    return std::pair<int, int>(static_cast<int>(at->x()), static_cast<int>(at->y()));
  };
  const auto luminance = [](const std::array<std::uint8_t, 3>& p) { return p[0] + p[1] + p[2]; };
  const auto [bx, by] = pixelOf(Vector3(0, 0, z));
  EXPECT_TRUE(isBackground(bare, bx, by)) << "the sphere covers the point under it";
  const int under = luminance(floor.pixel(bx, by));
  for (const double side : {-90.0, 90.0}) {
    const auto [sx, sy] = pixelOf(Vector3(0, 0, z) + side * right.normalized());
    EXPECT_TRUE(isBackground(bare, sx, sy));
    const int lit = luminance(floor.pixel(sx, sy));
    EXPECT_LT(lit, 3 * 250) << "the floor is drawn beside the sphere";
    EXPECT_GT(lit, 3 * 150);
    EXPECT_LT(under, 0.8 * lit) << "side " << side;
  }
  // A camera below the floor sees no floor.
  request.camera = frameBodies(world, {}, Vector3(1.0, -1.3, -0.9), 320.0 / 240.0);
  request.floor = false;
  const Image below = render(world, request);
  request.floor = true;
  EXPECT_EQ(render(world, request).rgb, below.rgb);
}

TEST(Render, AlikeHandAndObjectColoursArePulledApart) {
  // The project's bh8 palm and its mug: greys 0.3 apart in lightness, alike once shaded.
  const Colour grey{0.55f, 0.57f, 0.6f}, lightGrey{0.85f, 0.88f, 0.92f};
  ASSERT_LT(colourDistance(grey, lightGrey), kAlikeColourDistance);
  const Colour hand = separatedColour(grey, lightGrey);
  EXPECT_GT(colourDistance(hand, lightGrey), kAlikeColourDistance);
  EXPECT_EQ(hand, kHandPalette[0]);
  // Colours already apart stay as they are.
  const Colour dark{0.1f, 0.1f, 0.1f};
  EXPECT_EQ(separatedColour(dark, lightGrey), dark);
  const Colour red{0.9f, 0.1f, 0.1f};
  EXPECT_EQ(separatedColour(red, grey), red);
  // An object in the palette's first colour: the hand takes the next one apart from it.
  const Colour blue = separatedColour(kHandPalette[0], kHandPalette[0]);
  EXPECT_GT(colourDistance(blue, kHandPalette[0]), kAlikeColourDistance);
  // Any object colour leaves some palette colour apart from it.
  for (float r = 0.0f; r <= 1.0f; r += 0.25f)
    for (float g = 0.0f; g <= 1.0f; g += 0.25f)
      for (float b = 0.0f; b <= 1.0f; b += 0.25f)
        EXPECT_GE(colourDistance(separatedColour(Colour{r, g, b}, Colour{r, g, b}), {r, g, b}),
                  kAlikeColourDistance);

  // In a picture: a metal palm before a metal box is drawn in the palette's colour when asked.
  World world;
  addBody(world, box(Vector3(40, 25, 10)), Vector3(0, 0, -300.0), Material::Metal);
  addPalmHand(world, Vector3(20, 20, 5), Vector3(0, 0, -250.0), Material::Metal);
  const Colour metal = surfaceColour(world, BodyRef::body(0));
  EXPECT_EQ(metal, materialColour(Material::Metal));
  RenderRequest request = headOn(160, 120, 0.6);
  const Image files = render(world, request);
  request.separateColours = true;
  const Image apart = render(world, request);
  const auto palm = files.pixel(80, 60), bluePalm = apart.pixel(80, 60);
  EXPECT_NEAR(palm[0], palm[2], 30);         // the files' grey
  EXPECT_GT(bluePalm[2], bluePalm[0] + 60);  // the palette's blue
  // The box beside the palm (x = 58: inside the box's 27 pixels, outside the palm's 16) keeps
  // its own colour.
  EXPECT_EQ(files.pixel(58, 60), apart.pixel(58, 60));
  EXPECT_FALSE(isBackground(files, 58, 60));
}

// GraspIt!'s plannerMug: the Barrett's palm is near black, its mug glass light blue; colours
// already apart are kept, and the palm stays apart from the mug.
TEST(Render, PlannerMugKeepsColoursAlreadyApart) {
  GRASPKIT_REQUIRE_SHARED();
  const World world = loadWorldFile(*test::graspitDataDir() / "worlds" / "plannerMug.xml");
  const GraspSubject subject = graspSubject(world);
  ASSERT_TRUE(subject.hand && subject.object);
  const Colour mug = surfaceColour(world, *subject.object);
  const Colour palm = surfaceColour(world, BodyRef::robotBase(*subject.hand));
  EXPECT_GT(colourDistance(palm, mug), kAlikeColourDistance);
  EXPECT_EQ(separatedColour(palm, mug), palm);
  // The same palm beside a mug of its own colour is pulled apart.
  EXPECT_GT(colourDistance(separatedColour(palm, palm), palm), kAlikeColourDistance);
}

TEST(Render, FramedSphereFillsTheViewFromEverySide) {
  World world;
  addBody(world, test::icosphere(30.0, 4), Vector3(100, -50, 20));
  for (const Vector3& side : {Vector3(1, 0, 0), Vector3(0, 0, 1), Vector3(1, -1.3, 0.9)}) {
    RenderRequest request;
    request.width = 160;
    request.height = 120;
    request.camera = frameBodies(world, {}, side, 160.0 / 120.0);
    const Image image = render(world, request);
    // The bounding sphere is the mesh's circumsphere: its silhouette touches the top and
    // bottom edges, a disc of radius ~ H/2 (the inscribed sphere a little less).
    int covered = 0;
    for (int y = 0; y < 120; ++y)
      for (int x = 0; x < 160; ++x) covered += isBackground(image, x, y) ? 0 : 1;
    EXPECT_NEAR(covered, M_PI * 60.0 * 60.0, 0.04 * M_PI * 60.0 * 60.0) << side.transpose();
    EXPECT_TRUE(isBackground(image, 0, 0));
    EXPECT_FALSE(isBackground(image, 80, 60));
  }
}

TEST(Render, RefusesBadRequests) {
  World world;
  RenderRequest request;
  request.width = 0;
  EXPECT_THROW(render(world, request), Error);
  request.width = 10;
  request.samples = 9;
  EXPECT_THROW(render(world, request), Error);
  request.samples = 1;
  request.camera.position.x() = std::nan("");
  EXPECT_THROW(render(world, request), Error);
  EXPECT_THROW(frameBodies(world, {}, Vector3::Zero(), 1.0), Error);
}

TEST(Image, PngRoundTripAndErrors) {
  Image image(7, 5, {10, 20, 30});
  image.setPixel(3, 2, {255, 0, 128});
  const auto file = test::scratchDir() / "round.png";
  writePng(image, file);
  const Image back = readPng(file);
  EXPECT_EQ(back.width, 7);
  EXPECT_EQ(back.height, 5);
  EXPECT_EQ(back.rgb, image.rgb);
  std::ofstream(test::scratchDir() / "bad.png") << "not a picture";
  try {
    readPng(test::scratchDir() / "bad.png");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("bad.png"), std::string::npos) << e.what();
  }
  EXPECT_THROW(writePng(image, test::scratchDir() / "no" / "such" / "folder.png"), Error);
  EXPECT_THROW(writePng(Image(), file), Error);
  // A truncated PNG is damaged, not a crash.
  std::ifstream in(file, std::ios::binary);
  std::string bytes{std::istreambuf_iterator<char>(in), {}};
  std::ofstream(test::scratchDir() / "cut.png", std::ios::binary) << bytes.substr(0, 40);
  EXPECT_THROW(readPng(test::scratchDir() / "cut.png"), Error);
}

TEST(Image, TilesGoRowByRow) {
  std::vector<Image> tiles = {Image(4, 3, {1, 1, 1}), Image(4, 3, {2, 2, 2}),
                              Image(4, 3, {3, 3, 3})};
  const Image sheet = tileImages(tiles, 2, 1, {0, 0, 0});
  EXPECT_EQ(sheet.width, 9);
  EXPECT_EQ(sheet.height, 7);
  EXPECT_EQ(sheet.pixel(0, 0)[0], 1);
  EXPECT_EQ(sheet.pixel(5, 0)[0], 2);
  EXPECT_EQ(sheet.pixel(0, 4)[0], 3);
  EXPECT_EQ(sheet.pixel(4, 0)[0], 0);  // the gap
  EXPECT_EQ(sheet.pixel(5, 4)[0], 0);  // no fourth tile
}

TEST(InventorColours, MaterialsGiveTriangleColours) {
  const auto dir = test::scratchDir();
  std::ofstream(dir / "red.iv") << "#Inventor V2.1 ascii\nSeparator { Material { diffuseColor 1 0 "
                                   "0 } Cube {} Material { diffuseColor 0 0.5 1 } Sphere {} }\n";
  std::ofstream(dir / "plain.iv") << "#Inventor V2.1 ascii\nSeparator { Cube {} }\n";
  const TriangleMesh red = loadMesh(dir / "red.iv");
  ASSERT_EQ(red.triangleColours.size(), red.triangles.size());
  EXPECT_EQ(red.triangleColours.front(), (Colour{1.0f, 0.0f, 0.0f}));
  EXPECT_EQ(red.triangleColours.back(), (Colour{0.0f, 0.5f, 1.0f}));
  EXPECT_TRUE(loadMesh(dir / "plain.iv").triangleColours.empty());
}

// glTF written here, read back by tinygltf: the same vertices, triangles, poses and extras.
TEST(Gltf, RoundTripKeepsMeshesPosesAndExtras) {
  World world;
  auto sphere = test::icosphere(30.0, 2);
  auto red = box(Vector3(10, 20, 30));
  red->triangleColours.assign(red->triangles.size(), Colour{1.0f, 0.0f, 0.0f});
  addBody(world, sphere, Vector3(100, 0, 0));
  const int moved = addBody(world, red, Vector3(0, 50, 0));
  World second = world.clone();
  const Transform turned = makeTransform(
      Vector3(-20, 5, 7.5), Quaternion(Eigen::AngleAxisd(0.7, Vector3(1, 2, 3).normalized())));
  second.bodies()[static_cast<std::size_t>(moved)].setPose(turned);
  const auto file = test::scratchDir() / "scene.glb";
  const std::vector<GltfScene> scenes = {{"first", &world, R"({"epsilon": 0.25})"},
                                         {"second", &second, ""}};
  saveGltf(scenes, file);

  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  std::string err, warn;
  ASSERT_TRUE(loader.LoadBinaryFromFile(&model, &err, &warn, file.string())) << err;
  ASSERT_EQ(model.scenes.size(), 2u);
  EXPECT_EQ(model.scenes[0].name, "first");
  EXPECT_DOUBLE_EQ(model.scenes[0].extras.Get("epsilon").GetNumberAsDouble(), 0.25);
  ASSERT_EQ(model.scenes[1].nodes.size(), 2u);
  EXPECT_EQ(model.meshes.size(), 2u);  // shared by both scenes
  const tinygltf::Node& node = model.nodes[static_cast<std::size_t>(model.scenes[1].nodes[1])];
  const Quaternion q(turned.linear());
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(node.translation[static_cast<std::size_t>(k)] * 1000.0, turned.translation()[k],
                1e-9);
  EXPECT_NEAR(std::abs(node.rotation[0] * q.x() + node.rotation[1] * q.y() +
                       node.rotation[2] * q.z() + node.rotation[3] * q.w()),
              1.0, 1e-12);
  const tinygltf::Mesh& boxMesh = model.meshes[static_cast<std::size_t>(node.mesh)];
  ASSERT_EQ(boxMesh.primitives.size(), 1u);  // one colour
  const auto& positions =
      model.accessors[static_cast<std::size_t>(boxMesh.primitives[0].attributes.at("POSITION"))];
  EXPECT_EQ(positions.count, red->vertices.size());
  EXPECT_NEAR(positions.maxValues[2] * 1000.0, 30.0, 1e-4);
  EXPECT_EQ(model.accessors[static_cast<std::size_t>(boxMesh.primitives[0].indices)].count,
            3 * red->triangles.size());
  const auto& colour = model.materials[static_cast<std::size_t>(boxMesh.primitives[0].material)]
                           .pbrMetallicRoughness.baseColorFactor;
  EXPECT_DOUBLE_EQ(colour[0], 1.0);
  EXPECT_DOUBLE_EQ(colour[1], 0.0);
  EXPECT_THROW(gltfBinary(std::vector<GltfScene>{{"bad", &world, "[1, 2]"}}), Error);
}

// GraspIt!'s plannerMug: every body with a mesh is one node, with its vertex count and pose.
TEST(Gltf, PlannerMugExportsEveryBody) {
  GRASPKIT_REQUIRE_SHARED();
  const World world = loadWorldFile(*test::graspitDataDir() / "worlds" / "plannerMug.xml");
  const auto file = test::scratchDir() / "mug.glb";
  saveGltf(std::vector<GltfScene>{{"mug", &world, ""}}, file);
  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  std::string err, warn;
  ASSERT_TRUE(loader.LoadBinaryFromFile(&model, &err, &warn, file.string())) << err;
  std::size_t expected = 0;
  for (const BodyRef& body : worldBodies(world)) {
    const auto& mesh = bodyModel(world, body).mesh;
    if (!mesh || mesh->empty()) continue;
    const tinygltf::Node& node = model.nodes.at(expected++);
    EXPECT_EQ(node.name, bodyName(world, body));
    const auto& primitive = model.meshes.at(static_cast<std::size_t>(node.mesh)).primitives.at(0);
    EXPECT_EQ(
        model.accessors.at(static_cast<std::size_t>(primitive.attributes.at("POSITION"))).count,
        mesh->vertices.size());
    std::size_t indices = 0;
    for (const auto& p : model.meshes.at(static_cast<std::size_t>(node.mesh)).primitives)
      indices += model.accessors.at(static_cast<std::size_t>(p.indices)).count;
    EXPECT_EQ(indices, 3 * mesh->triangles.size());
    const Vector3 t = bodyPose(world, body).translation();
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(node.translation.at(static_cast<std::size_t>(k)) * 1000.0, t[k], 1e-9);
  }
  EXPECT_EQ(model.scenes.at(0).nodes.size(), expected);
  EXPECT_GE(expected, 10u);  // the mug, the palm and 3 fingers of 3 links
}

}  // namespace
}  // namespace graspkit

namespace graspkit {
namespace {

int inkCount(const Image& image) {
  int n = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) n += image.pixel(x, y)[0] == 0 ? 1 : 0;
  return n;
}

TEST(Text, StaysInItsBoxAndScalesByArea) {
  const std::string text = "#1 eps 0.394";
  const auto [w, h] = textSize(text, 1);
  EXPECT_EQ(w, 12 * 6 - 1);
  EXPECT_EQ(h, 7);
  Image one(100, 20);
  drawText(one, 3, 4, text);
  for (int y = 0; y < one.height; ++y)
    for (int x = 0; x < one.width; ++x)
      if (one.pixel(x, y)[0] == 0) {
        EXPECT_GE(x, 3);
        EXPECT_LT(x, 3 + w);
        EXPECT_GE(y, 4);
        EXPECT_LT(y, 4 + h);
      }
  Image three(300, 40);
  drawText(three, 0, 0, text, {0, 0, 0}, 3);
  EXPECT_GT(inkCount(one), 50);
  EXPECT_EQ(inkCount(three), 9 * inkCount(one));
  // Lower case draws as upper case; different characters differ; clipping is harmless.
  Image a(20, 10), b(20, 10), c(20, 10);
  drawText(a, 0, 0, "e");
  drawText(b, 0, 0, "E");
  drawText(c, 0, 0, "8");
  EXPECT_EQ(a.rgb, b.rgb);
  EXPECT_NE(a.rgb, c.rgb);
  drawText(a, -3, -4, "clipped \x01", {0, 0, 0}, 2);
  drawText(a, 1000, 1000, "far away");
}

}  // namespace
}  // namespace graspkit
