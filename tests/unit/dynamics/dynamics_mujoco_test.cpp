// A second method for the dynamics: MuJoCo (Debian's libmujoco) runs the same convex scenes, and
// both engines are checked against each other and the closed form. MuJoCo works in SI units
// (m, kg, s); graspkit in mm, g, s.

#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

#include "graspkit/collision/contact.hpp"
#include "graspkit/dynamics/dynamics.hpp"
#include "graspkit/geometry/mass_properties.hpp"
#include "graspkit/model/world.hpp"
#include "test_meshes.hpp"
#include "test_paths.hpp"

namespace graspkit {
namespace {

constexpr double kSide = 50.0;   // mm, the cube's edge
constexpr double kMass = 200.0;  // g

Body cubeBody() {
  auto model = std::make_shared<BodyModel>();
  model->name = "cube";
  model->mesh = test::box(Vector3::Constant(-kSide / 2), Vector3::Constant(kSide / 2));
  model->material = Material::Wood;
  model->mass = kMass;
  const MassProperties properties = computeMassProperties(*model->mesh);
  model->inertia = properties.inertia;
  model->maxRadius = maxRadius(*model->mesh, Vector3::Zero());
  Body body;
  body.model = model;
  body.kind = BodyKind::Graspable;
  body.name = "cube";
  return body;
}

Body floorBody() {
  auto model = std::make_shared<BodyModel>();
  model->name = "floor";
  model->mesh = test::box(Vector3(-2000, -500, -20), Vector3(2000, 500, 0));
  model->material = Material::Wood;
  Body body;
  body.model = model;
  body.kind = BodyKind::Obstacle;
  body.name = "floor";
  body.setPose(Transform::Identity());
  return body;
}

// The cube slid along +x at `speed` mm/s, resting on the floor; where it stops (mm travelled).
double graspkitSlide(double speed, double seconds) {
  World world;
  world.addBody(floorBody());
  Body cube = cubeBody();
  Transform start = Transform::Identity();
  start.translation() = Vector3(0, 0, kSide / 2 + kRestingSeparation);
  cube.setPose(start);
  cube.state.v << speed, 0, 0, 0, 0, 0;
  const int index = world.addBody(cube);
  simulate(world, {.seconds = seconds});
  return world.bodies()[index].pose.translation().x();
}

// The same in MuJoCo: a free box on a plane, friction mu (condim 3, elliptic cones), and a
// small timestep so that its soft contacts are stiff.
double mujocoSlide(double speed, double seconds, double mu) {
  const std::string xml = std::string(R"(<mujoco>
  <option timestep="0.0005" gravity="0 0 -9.81" cone="elliptic"/>
  <worldbody>
    <geom type="plane" size="5 5 0.1" friction=")") +
                          std::to_string(mu) + R"( 0 0"/>
    <body pos="0 0 0.025">
      <freejoint/>
      <geom type="box" size="0.025 0.025 0.025" mass="0.2" friction=")" +
                          std::to_string(mu) + R"( 0 0"/>
    </body>
  </worldbody>
</mujoco>)";
  const std::filesystem::path file = test::scratchDir() / "slide.xml";
  std::ofstream(file) << xml;
  char error[1000] = "";
  mjModel* model = mj_loadXML(file.c_str(), nullptr, error, sizeof error);
  EXPECT_NE(model, nullptr) << error;
  if (!model) return NAN;
  mjData* data = mj_makeData(model);
  // Let the box settle into its contact before it is pushed.
  for (int i = 0; i < 200; ++i) mj_step(model, data);
  const double x0 = data->qpos[0];
  data->qvel[0] = speed / 1000.0;
  const int steps = static_cast<int>(std::lround(seconds / model->opt.timestep));
  for (int i = 0; i < steps; ++i) mj_step(model, data);
  const double travelled = (data->qpos[0] - x0) * 1000.0;
  mj_deleteData(data);
  mj_deleteModel(model);
  return travelled;
}

TEST(DynamicsSecondMethod, SlidingBoxStopsWhereMuJoCoAndTheClosedFormSay) {
  const double speed = 500.0;  // mm/s
  const double mu = kineticFriction(Material::Wood, Material::Wood);
  const double closed_form = speed * speed / (2.0 * mu * kStandardGravity);  // 42.5 mm
  const double ours = graspkitSlide(speed, 0.5);
  const double theirs = mujocoSlide(speed, 0.5, mu);
  std::printf("slide: closed form %.3f mm, graspkit %.3f mm, MuJoCo %.3f mm\n", closed_form, ours,
              theirs);
  EXPECT_NEAR(ours, closed_form, 0.02 * closed_form);
  EXPECT_NEAR(theirs, closed_form, 0.03 * closed_form);
  EXPECT_NEAR(ours, theirs, 0.03 * closed_form);
}

}  // namespace
}  // namespace graspkit
