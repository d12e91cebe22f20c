// The C ABI (bindings/c/include/graspkit.h), called as a C host calls it: every function, its
// results against independent truth (GraspIt!'s reference figures, closed forms of the project's
// own box), and its error paths (null handles and pointers, bad indices, missing files, wrong
// counts, NaN), each giving a status and a message, never a crash.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "graspkit.h"
#include "test_paths.hpp"

namespace fs = std::filesystem;
using graspkit::test::modelsDir;
using graspkit::test::scratchDir;

// A world handle freed at scope exit. Not in the anonymous namespace: the CAbiPlannerMug fixture
// holds one.
struct WorldPtr {
  graspkit_world* w = nullptr;
  ~WorldPtr() { graspkit_world_free(w); }
  operator graspkit_world*() const { return w; }
};

namespace {

constexpr double kInf = INFINITY;

std::string lastError() {
  return graspkit_last_error();
}

std::string plannerMugPath() {
  return (*graspkit::test::graspitDataDir() / "worlds/plannerMug.xml").string();
}

nlohmann::json reference() {
  std::ifstream in(*graspkit::test::referenceFigures());
  return nlohmann::json::parse(in);
}

void loadOrFail(const std::string& path, WorldPtr& world) {
  ASSERT_EQ(graspkit_world_load(path.c_str(), nullptr, &world.w), GRASPKIT_OK) << lastError();
}

std::string writeFile(const fs::path& path, const std::string& text) {
  std::ofstream(path) << text;
  return path.string();
}

double quaternionDistance(const double a[4], const double b[4]) {
  double dot = 0;
  for (int i = 0; i < 4; ++i) dot += a[i] * b[i];
  return 1.0 - std::abs(dot);  // q and -q are one rotation
}

}  // namespace

TEST(CAbi, VersionsMatchTheHeaderAndTheProject) {
  EXPECT_EQ(graspkit_abi_version(), static_cast<uint32_t>(GRASPKIT_ABI_VERSION));
  EXPECT_STREQ(graspkit_version(), GRASPKIT_PROJECT_VERSION);
}

TEST(CAbi, StatusNamesAreDistinct) {
  std::set<std::string> names;
  for (int s = GRASPKIT_OK; s <= GRASPKIT_ERROR_INTERNAL; ++s)
    names.insert(graspkit_status_name(static_cast<graspkit_status>(s)));
  EXPECT_EQ(names.size(), 8u);
  EXPECT_STREQ(graspkit_status_name(99), "unknown status");
}

TEST(CAbi, NullHandlesAndPointersAreInvalidArguments) {
  graspkit_world* w = nullptr;
  int32_t i = 0;
  size_t n = 0;
  double d = 0;
  int flag = 0;
  graspkit_pose pose{};
  char buffer[8];
  const graspkit_body_ref ref{};
  // Every function taking a handle, given none.
  const std::vector<std::pair<const char*, graspkit_status>> calls = {
      {"world_new", graspkit_world_new(nullptr)},
      {"world_load path", graspkit_world_load(nullptr, nullptr, &w)},
      {"world_load out", graspkit_world_load("x.xml", nullptr, nullptr)},
      {"world_clone", graspkit_world_clone(nullptr, &w)},
      {"world_save", graspkit_world_save(nullptr, "x.xml")},
      {"world_add_file", graspkit_world_add_file(nullptr, "x.xml", nullptr, &i, &i)},
      {"world_body_count", graspkit_world_body_count(nullptr, &i)},
      {"world_find_body", graspkit_world_find_body(nullptr, "mug", &i)},
      {"body_name", graspkit_body_name(nullptr, 0, buffer, sizeof buffer, &n)},
      {"body_is_graspable", graspkit_body_is_graspable(nullptr, 0, &flag)},
      {"body_mass", graspkit_body_mass(nullptr, 0, &d, nullptr)},
      {"body_get_pose", graspkit_body_get_pose(nullptr, 0, &pose)},
      {"body_set_pose", graspkit_body_set_pose(nullptr, 0, &pose)},
      {"body_ref_name", graspkit_body_ref_name(nullptr, &ref, buffer, sizeof buffer, &n)},
      {"world_robot_count", graspkit_world_robot_count(nullptr, &i)},
      {"world_find_robot", graspkit_world_find_robot(nullptr, "Barrett", &i)},
      {"world_first_hand", graspkit_world_first_hand(nullptr, &i)},
      {"robot_name", graspkit_robot_name(nullptr, 0, buffer, sizeof buffer, &n)},
      {"robot_dof_count", graspkit_robot_dof_count(nullptr, 0, &i)},
      {"robot_get_dofs", graspkit_robot_get_dofs(nullptr, 0, &d, 1)},
      {"robot_set_dofs", graspkit_robot_set_dofs(nullptr, 0, &d, 1)},
      {"robot_dof_limits", graspkit_robot_dof_limits(nullptr, 0, &d, &d, 1)},
      {"robot_get_pose", graspkit_robot_get_pose(nullptr, 0, &pose)},
      {"robot_set_pose", graspkit_robot_set_pose(nullptr, 0, &pose)},
      {"robot_chain_count", graspkit_robot_chain_count(nullptr, 0, &i)},
      {"robot_link_count", graspkit_robot_link_count(nullptr, 0, 0, &i)},
      {"robot_link_pose", graspkit_robot_link_pose(nullptr, 0, 0, 0, &pose)},
      {"robot_autograsp", graspkit_robot_autograsp(nullptr, 0, nullptr)},
      {"grasp_analyze", graspkit_grasp_analyze(nullptr, 0, 0, GRASPKIT_GWS_L1, nullptr)},
      {"grasp_quality", graspkit_grasp_quality(nullptr, nullptr)},
      {"grasp_contact_count", graspkit_grasp_contact_count(nullptr, &n)},
      {"grasp_contacts", graspkit_grasp_contacts(nullptr, nullptr, 0, &n)},
      {"grasp_failure", graspkit_grasp_failure(nullptr, buffer, sizeof buffer, &n)},
      {"ray_scene_new", graspkit_ray_scene_new(nullptr, 1, nullptr)},
      {"ray_scene_update", graspkit_ray_scene_update(nullptr, nullptr)},
      {"ray_scene_intersect", graspkit_ray_scene_intersect(nullptr, nullptr, nullptr, 1)},
      {"ray_scene_nearest", graspkit_ray_scene_nearest(nullptr, nullptr, 1, kInf, nullptr)},
      {"plan_options_default", graspkit_plan_options_default(nullptr)},
      {"plan_grasps", graspkit_plan_grasps(nullptr, 0, 0, nullptr, nullptr)},
      {"plan_count", graspkit_plan_count(nullptr, &n)},
      {"plan_grasp", graspkit_plan_grasp(nullptr, 0, nullptr)},
      {"plan_grasp_dofs", graspkit_plan_grasp_dofs(nullptr, 0, &d, 1)},
      {"plan_grasp_world", graspkit_plan_grasp_world(nullptr, 0, &w)},
      {"run_script", graspkit_run_script(nullptr, nullptr, &flag)},
      {"plugins_scan", graspkit_plugins_scan(nullptr)},
      {"plugin_load", graspkit_plugin_load(nullptr)},
      {"plugin_info", graspkit_plugin_info(0, buffer, sizeof buffer, nullptr, nullptr, 0)},
      {"plugin_search_path", graspkit_plugin_search_path(nullptr, 4, &n)},
  };
  for (const auto& [name, status] : calls) {
    EXPECT_EQ(status, GRASPKIT_ERROR_INVALID_ARGUMENT) << name;
  }
  EXPECT_NE(lastError().find("is NULL"), std::string::npos) << lastError();
  // Freeing nothing is allowed.
  graspkit_world_free(nullptr);
  graspkit_grasp_free(nullptr);
  graspkit_ray_scene_free(nullptr);
  graspkit_plan_free(nullptr);
}

TEST(CAbi, MissingFileNamesTheFile) {
  WorldPtr world;
  const std::string path = (scratchDir() / "no_such_world.xml").string();
  EXPECT_EQ(graspkit_world_load(path.c_str(), nullptr, &world.w), GRASPKIT_ERROR_INPUT);
  EXPECT_EQ(world.w, nullptr);
  EXPECT_NE(lastError().find("no_such_world.xml"), std::string::npos) << lastError();
  EXPECT_STRNE(graspkit_last_error_file(), "");
}

TEST(CAbi, MalformedXmlGivesFileLineAndElement) {
  const fs::path dir = scratchDir();
  const std::string path =
      writeFile(dir / "bad.xml",
                "<?xml version=\"1.0\" ?>\n<root>\n  <material>glass</material>\n"
                "  <mass>heavy</mass>\n</root>\n");
  WorldPtr world;
  EXPECT_EQ(graspkit_world_load(path.c_str(), nullptr, &world.w), GRASPKIT_ERROR_INPUT);
  EXPECT_NE(std::string(graspkit_last_error_file()).find("bad.xml"), std::string::npos);
  EXPECT_EQ(graspkit_last_error_line(), 4) << lastError();
  EXPECT_STREQ(graspkit_last_error_element(), "mass") << lastError();
}

TEST(CAbi, TheLastErrorIsPerThreadAndClearedBySuccess) {
  WorldPtr world;
  ASSERT_EQ(graspkit_world_load("/no/such/file.xml", nullptr, &world.w), GRASPKIT_ERROR_INPUT);
  std::string other_thread = "unset";
  std::thread([&] {
    WorldPtr w;
    graspkit_world_new(&w.w);
    other_thread = graspkit_last_error();
  }).join();
  EXPECT_EQ(other_thread, "");
  EXPECT_NE(lastError().find("file.xml"), std::string::npos);
  int32_t count = -1;
  ASSERT_EQ(graspkit_world_new(&world.w), GRASPKIT_OK);
  EXPECT_EQ(graspkit_world_body_count(world, &count), GRASPKIT_OK);
  EXPECT_EQ(count, 0);
  EXPECT_EQ(lastError(), "");
  EXPECT_EQ(graspkit_last_error_line(), 0);
}

namespace {

struct Captured {
  int calls = 0;
  std::string kind, file, element, message;
  int line = 0;
};

void capture(graspkit_log_level level, const char* kind, const char* file, int line,
             const char* element, const char* message, void* user) {
  auto* c = static_cast<Captured*>(user);
  EXPECT_EQ(level, GRASPKIT_LOG_WARNING);
  ++c->calls;
  c->kind = kind;
  c->file = file;
  c->line = line;
  c->element = element;
  c->message = message;
}

}  // namespace

TEST(CAbi, WarningsReachTheCallbackAndNeverStdout) {
  const fs::path dir = scratchDir();
  std::ofstream(dir / "cube.off")
      << "OFF\n8 12 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n"
         "1 1 1\n0 1 1\n3 0 2 1\n3 0 3 2\n3 4 5 6\n3 4 6 7\n3 0 1 5\n"
         "3 0 5 4\n3 1 2 6\n3 1 6 5\n3 2 3 7\n3 2 7 6\n3 3 0 4\n3 3 4 7\n";
  const std::string path =
      writeFile(dir / "odd.xml",
                "<?xml version=\"1.0\" ?>\n<root>\n  <material>wood</material>\n"
                "  <colour>red</colour>\n"
                "  <geometryFile type=\"off\">cube.off</geometryFile>\n</root>\n");
  Captured captured;
  ASSERT_EQ(graspkit_set_log_callback(&capture, &captured), GRASPKIT_OK);
  {
    WorldPtr world;
    ASSERT_EQ(graspkit_world_load(path.c_str(), nullptr, &world.w), GRASPKIT_OK) << lastError();
  }
  ASSERT_GE(captured.calls, 1);
  EXPECT_NE(captured.file.find("odd.xml"), std::string::npos);
  EXPECT_EQ(captured.line, 4);
  EXPECT_EQ(captured.element, "colour");
  EXPECT_EQ(captured.kind, "unknown-element");

  // The default handler writes to stderr only: a host printing JSON on stdout stays clean.
  ASSERT_EQ(graspkit_set_log_callback(nullptr, nullptr), GRASPKIT_OK);
  testing::internal::CaptureStdout();
  testing::internal::CaptureStderr();
  {
    WorldPtr world;
    ASSERT_EQ(graspkit_world_load(path.c_str(), nullptr, &world.w), GRASPKIT_OK);
  }
  const std::string out = testing::internal::GetCapturedStdout();
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_EQ(out, "");
  EXPECT_NE(err.find("graspkit: warning: "), std::string::npos) << err;
  EXPECT_NE(err.find("colour"), std::string::npos) << err;
}

TEST(CAbi, BodiesOfTheProjectBox) {
  WorldPtr world;
  loadOrFail((modelsDir() / "objects/box.xml").string(), world);
  int32_t count = 0;
  ASSERT_EQ(graspkit_world_body_count(world, &count), GRASPKIT_OK);
  ASSERT_EQ(count, 1);
  int32_t index = -1;
  ASSERT_EQ(graspkit_world_find_body(world, "box", &index), GRASPKIT_OK) << lastError();
  EXPECT_EQ(index, 0);
  EXPECT_EQ(graspkit_world_find_body(world, "mug", &index), GRASPKIT_ERROR_NOT_FOUND);
  EXPECT_NE(lastError().find("box"), std::string::npos) << "lists the bodies there are";

  // The string rule: the whole length, what fits, and a status when it did not fit.
  char name[16];
  size_t length = 0;
  ASSERT_EQ(graspkit_body_name(world, 0, name, sizeof name, &length), GRASPKIT_OK);
  EXPECT_STREQ(name, "box");
  EXPECT_EQ(length, 3u);
  char small[3];
  EXPECT_EQ(graspkit_body_name(world, 0, small, sizeof small, &length),
            GRASPKIT_ERROR_BUFFER_TOO_SMALL);
  EXPECT_STREQ(small, "bo");
  EXPECT_EQ(graspkit_body_name(world, 0, nullptr, 0, &length), GRASPKIT_ERROR_BUFFER_TOO_SMALL);
  EXPECT_EQ(length, 3u);
  EXPECT_EQ(graspkit_body_name(world, 1, name, sizeof name, &length), GRASPKIT_ERROR_OUT_OF_RANGE);
  EXPECT_EQ(graspkit_body_name(world, -1, name, sizeof name, &length), GRASPKIT_ERROR_OUT_OF_RANGE);

  int graspable = -1;
  ASSERT_EQ(graspkit_body_is_graspable(world, 0, &graspable), GRASPKIT_OK);
  EXPECT_EQ(graspable, 1);  // a Body file loads as one graspable body
  EXPECT_EQ(graspkit_body_is_graspable(world, 5, &graspable), GRASPKIT_ERROR_OUT_OF_RANGE);

  double mass = 0, cog[3] = {1, 1, 1};
  ASSERT_EQ(graspkit_body_mass(world, 0, &mass, cog), GRASPKIT_OK);
  EXPECT_EQ(mass, 300.0);  // box.xml: <mass>300</mass>
  EXPECT_EQ(cog[0], 0.0);
  EXPECT_EQ(graspkit_body_mass(world, 0, nullptr, cog), GRASPKIT_ERROR_INVALID_ARGUMENT);

  // A pose set is the pose read back, the quaternion normalised.
  const graspkit_pose set{{10, -20, 30}, {2, 0, 0, 2}};
  ASSERT_EQ(graspkit_body_set_pose(world, 0, &set), GRASPKIT_OK);
  graspkit_pose got{};
  ASSERT_EQ(graspkit_body_get_pose(world, 0, &got), GRASPKIT_OK);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(got.translation[i], set.translation[i], 1e-12);
  const double half = std::sqrt(0.5);
  const double expected[4] = {half, 0, 0, half};
  EXPECT_LT(quaternionDistance(got.rotation, expected), 1e-12);
  graspkit_pose bad = set;
  bad.rotation[0] = bad.rotation[3] = 0;
  EXPECT_EQ(graspkit_body_set_pose(world, 0, &bad), GRASPKIT_ERROR_INPUT);
  bad = set;
  bad.translation[1] = NAN;
  EXPECT_EQ(graspkit_body_set_pose(world, 0, &bad), GRASPKIT_ERROR_INPUT);
  // Past the 1e9 mm every front end takes (transform.hpp, kMaxCoordinate).
  bad = set;
  bad.translation[0] = 1e300;
  EXPECT_EQ(graspkit_body_set_pose(world, 0, &bad), GRASPKIT_ERROR_INPUT);
  EXPECT_NE(lastError().find("lies past 1e9 mm"), std::string::npos) << lastError();
  EXPECT_EQ(graspkit_body_set_pose(world, 0, nullptr), GRASPKIT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(graspkit_body_get_pose(world, 3, &got), GRASPKIT_ERROR_OUT_OF_RANGE);
  ASSERT_EQ(graspkit_body_get_pose(world, 0, &got), GRASPKIT_OK);
  EXPECT_NEAR(got.translation[1], -20, 1e-12) << "a refused pose changed nothing";

  graspkit_body_ref ref{GRASPKIT_BODY, 0, -1, -1};
  ASSERT_EQ(graspkit_body_ref_name(world, &ref, name, sizeof name, &length), GRASPKIT_OK);
  EXPECT_STREQ(name, "box");
  ref.index = 4;
  EXPECT_EQ(graspkit_body_ref_name(world, &ref, name, sizeof name, &length),
            GRASPKIT_ERROR_OUT_OF_RANGE);
  ref.kind = 7;
  EXPECT_EQ(graspkit_body_ref_name(world, &ref, name, sizeof name, &length),
            GRASPKIT_ERROR_INVALID_ARGUMENT);
}

TEST(CAbi, AddFileAppendsAndAFailureChangesNothing) {
  WorldPtr world;
  ASSERT_EQ(graspkit_world_new(&world.w), GRASPKIT_OK);
  int32_t first_body = -1, first_robot = -1;
  const std::string box = (modelsDir() / "objects/box.xml").string();
  const std::string sphere = (modelsDir() / "objects/sphere.xml").string();
  ASSERT_EQ(graspkit_world_add_file(world, box.c_str(), nullptr, &first_body, &first_robot),
            GRASPKIT_OK)
      << lastError();
  EXPECT_EQ(first_body, 0);
  EXPECT_EQ(first_robot, 0);
  ASSERT_EQ(graspkit_world_add_file(world, sphere.c_str(), nullptr, &first_body, nullptr),
            GRASPKIT_OK);
  EXPECT_EQ(first_body, 1);
  ASSERT_EQ(graspkit_world_add_file(world, box.c_str(), nullptr, nullptr, nullptr), GRASPKIT_OK);
  int32_t count = 0;
  graspkit_world_body_count(world, &count);
  EXPECT_EQ(count, 3);
  char name[32];
  graspkit_body_name(world, 2, name, sizeof name, nullptr);
  EXPECT_STRNE(name, "box") << "a second box gets a name of its own";
  EXPECT_EQ(graspkit_world_add_file(world, "/no/such.xml", nullptr, &first_body, nullptr),
            GRASPKIT_ERROR_INPUT);
  graspkit_world_body_count(world, &count);
  EXPECT_EQ(count, 3);
  const char* bad_roots[] = {nullptr};
  const graspkit_load_options options{bad_roots, 1, 0};
  EXPECT_EQ(graspkit_world_add_file(world, box.c_str(), &options, nullptr, nullptr),
            GRASPKIT_ERROR_INVALID_ARGUMENT);
}

// The project's URDF gripper, loaded through the C ABI as any robot file: by hand, each finger's
// link frame is its joint origin slid along its x axis by the DOF (the right one turned half
// round about z, so its slide closes towards the centre too).
TEST(CAbi, UrdfRobotLoadsWithTheUrdfLinkFrames) {
  WorldPtr world;
  loadOrFail((modelsDir() / "robots/urdf_gripper/urdf_gripper.urdf").string(), world);
  int32_t robot = -1, dofs = 0, chains = 0;
  ASSERT_EQ(graspkit_world_find_robot(world, "urdf_gripper", &robot), GRASPKIT_OK) << lastError();
  graspkit_robot_dof_count(world, robot, &dofs);
  graspkit_robot_chain_count(world, robot, &chains);
  ASSERT_EQ(dofs, 1);
  ASSERT_EQ(chains, 2);
  const double slide = 15.0;
  ASSERT_EQ(graspkit_robot_set_dofs(world, robot, &slide, 1), GRASPKIT_OK) << lastError();
  graspkit_pose left{}, right{};
  ASSERT_EQ(graspkit_robot_link_pose(world, robot, 0, 0, &left), GRASPKIT_OK);
  ASSERT_EQ(graspkit_robot_link_pose(world, robot, 1, 0, &right), GRASPKIT_OK);
  const double left_at[3] = {-40.0 + slide, 0.0, 1.0}, right_at[3] = {40.0 - slide, 0.0, 1.0};
  const double unturned[4] = {1, 0, 0, 0}, half_turn_z[4] = {0, 0, 0, 1};
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(left.translation[i], left_at[i], 1e-9);
    EXPECT_NEAR(right.translation[i], right_at[i], 1e-9);
  }
  EXPECT_LT(quaternionDistance(left.rotation, unturned), 1e-12);
  EXPECT_LT(quaternionDistance(right.rotation, half_turn_z), 1e-12);
}

class CAbiPlannerMug : public testing::Test {
 protected:
  void SetUp() override {
    GRASPKIT_REQUIRE_SHARED();
    loadOrFail(plannerMugPath(), world);
  }
  WorldPtr world;
};

TEST_F(CAbiPlannerMug, RobotsAndGraspItsForwardKinematics) {
  int32_t robots = 0, hand = -1, found = -1;
  ASSERT_EQ(graspkit_world_robot_count(world, &robots), GRASPKIT_OK);
  EXPECT_EQ(robots, 1);
  ASSERT_EQ(graspkit_world_first_hand(world, &hand), GRASPKIT_OK);
  EXPECT_EQ(hand, 0);
  ASSERT_EQ(graspkit_world_find_robot(world, "Barrett", &found), GRASPKIT_OK);
  EXPECT_EQ(found, 0);
  EXPECT_EQ(graspkit_world_find_robot(world, "Puma", &found), GRASPKIT_ERROR_NOT_FOUND);
  char name[32];
  ASSERT_EQ(graspkit_robot_name(world, 0, name, sizeof name, nullptr), GRASPKIT_OK);
  EXPECT_STREQ(name, "Barrett");
  EXPECT_EQ(graspkit_robot_name(world, 1, name, sizeof name, nullptr), GRASPKIT_ERROR_OUT_OF_RANGE);
  EXPECT_NE(lastError().find("1 robots"), std::string::npos) << lastError();

  int32_t dofs = 0, chains = 0;
  ASSERT_EQ(graspkit_robot_dof_count(world, 0, &dofs), GRASPKIT_OK);
  ASSERT_EQ(graspkit_robot_chain_count(world, 0, &chains), GRASPKIT_OK);

  // GraspIt!'s own link poses of its Barrett at configuration B (base at the origin).
  const nlohmann::json fk =
      reference()["forward_kinematics"]["models/robots/Barrett/Barrett.xml"]["configs"]["B"];
  const std::vector<double> values = fk["requested_dof_values"];
  ASSERT_EQ(static_cast<size_t>(dofs), values.size());
  const graspkit_pose origin{{0, 0, 0}, {1, 0, 0, 0}};
  ASSERT_EQ(graspkit_robot_set_pose(world, 0, &origin), GRASPKIT_OK);
  ASSERT_EQ(graspkit_robot_set_dofs(world, 0, values.data(), values.size()), GRASPKIT_OK);
  const auto& chain_list = fk["state"]["chains"];
  ASSERT_EQ(chains, static_cast<int32_t>(chain_list.size()));
  int checked = 0;
  for (int32_t c = 0; c < chains; ++c) {
    int32_t links = 0;
    ASSERT_EQ(graspkit_robot_link_count(world, 0, c, &links), GRASPKIT_OK);
    ASSERT_EQ(links, static_cast<int32_t>(chain_list[c]["links"].size()));
    for (int32_t l = 0; l < links; ++l) {
      graspkit_pose pose{};
      ASSERT_EQ(graspkit_robot_link_pose(world, 0, c, l, &pose), GRASPKIT_OK);
      const auto& tran = chain_list[c]["links"][l]["tran"];
      for (int i = 0; i < 3; ++i)
        EXPECT_NEAR(pose.translation[i], tran["t_mm"][i].get<double>(), 1e-6);
      const std::vector<double> q = tran["q_wxyz"];
      EXPECT_LT(quaternionDistance(pose.rotation, q.data()), 1e-9);
      ++checked;
    }
  }
  EXPECT_EQ(checked, 8);
  graspkit_pose palm{};
  ASSERT_EQ(graspkit_robot_link_pose(world, 0, -1, -1, &palm), GRASPKIT_OK);
  EXPECT_EQ(palm.rotation[0], 1.0);
  graspkit_pose pose{};
  EXPECT_EQ(graspkit_robot_link_pose(world, 0, 0, 9, &pose), GRASPKIT_ERROR_OUT_OF_RANGE);
  EXPECT_EQ(graspkit_robot_link_pose(world, 0, -1, 0, &pose), GRASPKIT_ERROR_OUT_OF_RANGE);
  EXPECT_EQ(graspkit_robot_link_count(world, 0, 3, &chains), GRASPKIT_ERROR_OUT_OF_RANGE);
  EXPECT_EQ(graspkit_robot_chain_count(world, 2, &chains), GRASPKIT_ERROR_OUT_OF_RANGE);
}

TEST_F(CAbiPlannerMug, DofsLimitsAndTheirErrors) {
  int32_t dofs = 0;
  ASSERT_EQ(graspkit_robot_dof_count(world, 0, &dofs), GRASPKIT_OK);
  ASSERT_EQ(dofs, 4);
  std::vector<double> min(4), max(4), values(4);
  ASSERT_EQ(graspkit_robot_dof_limits(world, 0, min.data(), max.data(), 4), GRASPKIT_OK);
  // Barrett.xml, as GraspIt! reports it: spread 0..pi, flexions 0..0.8 pi.
  EXPECT_NEAR(max[0], 3.14159265359, 1e-9);
  EXPECT_NEAR(max[1], 2.51327412287, 1e-9);
  EXPECT_EQ(min[2], 0.0);
  const std::vector<double> wanted = {0.3, 0.5, 0.7, 9.0};
  ASSERT_EQ(graspkit_robot_set_dofs(world, 0, wanted.data(), 4), GRASPKIT_OK);
  ASSERT_EQ(graspkit_robot_get_dofs(world, 0, values.data(), 4), GRASPKIT_OK);
  EXPECT_EQ(values[0], 0.3);
  EXPECT_EQ(values[2], 0.7);
  EXPECT_EQ(values[3], max[3]) << "clamped into the range";

  EXPECT_EQ(graspkit_robot_set_dofs(world, 0, wanted.data(), 3), GRASPKIT_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(lastError().find("3 values given, 4 expected"), std::string::npos) << lastError();
  EXPECT_EQ(graspkit_robot_get_dofs(world, 0, values.data(), 5), GRASPKIT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(graspkit_robot_dof_limits(world, 0, min.data(), nullptr, 4),
            GRASPKIT_ERROR_INVALID_ARGUMENT);
  const std::vector<double> nan = {0.1, NAN, 0.1, 0.1};
  EXPECT_EQ(graspkit_robot_set_dofs(world, 0, nan.data(), 4), GRASPKIT_ERROR_INPUT);
  EXPECT_EQ(graspkit_robot_set_dofs(world, 7, wanted.data(), 4), GRASPKIT_ERROR_OUT_OF_RANGE);
  ASSERT_EQ(graspkit_robot_get_dofs(world, 0, values.data(), 4), GRASPKIT_OK);
  EXPECT_EQ(values[1], 0.5) << "a refused call changed nothing";

  graspkit_pose pose{};
  ASSERT_EQ(graspkit_robot_get_pose(world, 0, &pose), GRASPKIT_OK);
  pose.translation[2] += 25;
  ASSERT_EQ(graspkit_robot_set_pose(world, 0, &pose), GRASPKIT_OK);
  graspkit_pose moved{};
  ASSERT_EQ(graspkit_robot_get_pose(world, 0, &moved), GRASPKIT_OK);
  EXPECT_NEAR(moved.translation[2], pose.translation[2], 1e-12);
  pose.rotation[0] = NAN;
  EXPECT_EQ(graspkit_robot_set_pose(world, 0, &pose), GRASPKIT_ERROR_INPUT);
}

TEST_F(CAbiPlannerMug, AutograspGivesGraspItsFigures) {
  const nlohmann::json truth = reference()["grasps"]["plannerMug_as_loaded"]["autograsp"];
  graspkit_autograsp_result closed{-1, -1};
  ASSERT_EQ(graspkit_robot_autograsp(world, 0, &closed), GRASPKIT_OK) << lastError();
  EXPECT_EQ(closed.end, GRASPKIT_MOTION_SETTLED);
  EXPECT_GT(closed.steps, 0);
  std::vector<double> dofs(4);
  ASSERT_EQ(graspkit_robot_get_dofs(world, 0, dofs.data(), 4), GRASPKIT_OK);
  for (int d = 0; d < 4; ++d) EXPECT_NEAR(dofs[d], truth["final_dofs"][d].get<double>(), 1e-3);

  int32_t mug = -1;
  ASSERT_EQ(graspkit_world_find_body(world, "mug", &mug), GRASPKIT_OK);
  graspkit_grasp* grasp = nullptr;
  ASSERT_EQ(graspkit_grasp_analyze(world, 0, mug, GRASPKIT_GWS_L1, &grasp), GRASPKIT_OK)
      << lastError();
  graspkit_quality quality{};
  ASSERT_EQ(graspkit_grasp_quality(grasp, &quality), GRASPKIT_OK);
  EXPECT_EQ(quality.epsilon, truth["epsilon_L1"].get<double>());
  EXPECT_NEAR(quality.volume, truth["volume_L1"].get<double>(),
              0.01 * truth["volume_L1"].get<double>());
  EXPECT_EQ(quality.force_closure, 0);
  size_t count = 0;
  ASSERT_EQ(graspkit_grasp_contact_count(grasp, &count), GRASPKIT_OK);
  EXPECT_EQ(count, truth["num_contacts"].get<size_t>());
  std::vector<graspkit_contact> contacts(count + 2);
  size_t copied = 0;
  ASSERT_EQ(graspkit_grasp_contacts(grasp, contacts.data(), contacts.size(), &copied), GRASPKIT_OK);
  EXPECT_EQ(copied, count);
  for (size_t i = 0; i < copied; ++i) {
    const graspkit_contact& c = contacts[i];
    EXPECT_EQ(c.link.kind, GRASPKIT_LINK);
    EXPECT_EQ(c.body.kind, GRASPKIT_BODY);
    EXPECT_EQ(c.body.index, mug);
    EXPECT_NEAR(std::hypot(c.normal[0], c.normal[1], c.normal[2]), 1.0, 1e-9);
    EXPECT_EQ(c.model, GRASPKIT_CONTACT_POINT);
    EXPECT_GT(c.mu, 0.0);
    char link[64];
    ASSERT_EQ(graspkit_body_ref_name(world, &c.link, link, sizeof link, nullptr), GRASPKIT_OK);
    EXPECT_EQ(std::string(link).rfind("Barrett_chain", 0), 0u) << link;
  }
  ASSERT_EQ(graspkit_grasp_contacts(grasp, contacts.data(), 2, &copied), GRASPKIT_OK);
  EXPECT_EQ(copied, 2u);
  char failure[64];
  ASSERT_EQ(graspkit_grasp_failure(grasp, failure, sizeof failure, nullptr), GRASPKIT_OK);
  EXPECT_STREQ(failure, "");
  graspkit_grasp_free(grasp);

  // The L-infinity space of 6 contacts of 8 edges is a Minkowski sum of 9^6 points: refused
  // with a message rather than built for minutes.
  grasp = nullptr;
  EXPECT_EQ(graspkit_grasp_analyze(world, 0, mug, GRASPKIT_GWS_LINF, &grasp), GRASPKIT_ERROR_INPUT);
  EXPECT_NE(lastError().find("L-infinity"), std::string::npos) << lastError();
  EXPECT_EQ(grasp, nullptr);

  EXPECT_EQ(graspkit_grasp_analyze(world, 0, mug, 5, &grasp), GRASPKIT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(graspkit_grasp_analyze(world, 0, 3, GRASPKIT_GWS_L1, &grasp),
            GRASPKIT_ERROR_OUT_OF_RANGE);
  EXPECT_EQ(graspkit_grasp_analyze(world, 2, mug, GRASPKIT_GWS_L1, &grasp),
            GRASPKIT_ERROR_OUT_OF_RANGE);
  EXPECT_EQ(graspkit_robot_autograsp(world, 1, nullptr), GRASPKIT_ERROR_OUT_OF_RANGE);
}

TEST_F(CAbiPlannerMug, ClonesAreIndependentAndSavedWorldsLoadBack) {
  WorldPtr clone;
  ASSERT_EQ(graspkit_world_clone(world, &clone.w), GRASPKIT_OK);
  ASSERT_EQ(graspkit_robot_autograsp(clone, 0, nullptr), GRASPKIT_OK);
  std::vector<double> original(4), closed(4), reloaded(4);
  graspkit_robot_get_dofs(world, 0, original.data(), 4);
  graspkit_robot_get_dofs(clone, 0, closed.data(), 4);
  EXPECT_EQ(original[1], 0.0);
  EXPECT_GT(closed[1], 0.5);

  const std::string path = (scratchDir() / "closed.xml").string();
  ASSERT_EQ(graspkit_world_save(clone, path.c_str()), GRASPKIT_OK) << lastError();
  // The saved world names its files as the loaded one did (relative to GraspIt!'s root).
  WorldPtr back;
  const std::string data = graspkit::test::graspitDataDir()->string();
  const char* roots[] = {data.c_str()};
  const graspkit_load_options options{roots, 1, 0};
  ASSERT_EQ(graspkit_world_load(path.c_str(), &options, &back.w), GRASPKIT_OK) << lastError();
  graspkit_robot_get_dofs(back, 0, reloaded.data(), 4);
  for (int d = 0; d < 4; ++d) EXPECT_NEAR(reloaded[d], closed[d], 1e-6);
  graspkit_grasp *a = nullptr, *b = nullptr;
  ASSERT_EQ(graspkit_grasp_analyze(clone, 0, 0, GRASPKIT_GWS_L1, &a), GRASPKIT_OK);
  ASSERT_EQ(graspkit_grasp_analyze(back, 0, 0, GRASPKIT_GWS_L1, &b), GRASPKIT_OK);
  size_t na = 0, nb = 0;
  graspkit_grasp_contact_count(a, &na);
  graspkit_grasp_contact_count(b, &nb);
  EXPECT_EQ(na, nb);
  graspkit_quality qa{}, qb{};
  graspkit_grasp_quality(a, &qa);
  graspkit_grasp_quality(b, &qb);
  EXPECT_NEAR(qa.volume, qb.volume, 1e-3 * qa.volume);
  graspkit_grasp_free(a);
  graspkit_grasp_free(b);

  EXPECT_EQ(graspkit_world_save(world, "/no/such/folder/w.xml"), GRASPKIT_ERROR_INPUT);
  EXPECT_NE(lastError().find("/no/such/folder"), std::string::npos) << lastError();
  EXPECT_EQ(graspkit_world_save(world, nullptr), GRASPKIT_ERROR_INVALID_ARGUMENT);
}

TEST(CAbi, RaysAndNearestPointsOnTheBox) {
  // models/objects/box.xml: 60 x 60 x 120 mm centred on its origin.
  WorldPtr world;
  loadOrFail((modelsDir() / "objects/box.xml").string(), world);
  graspkit_ray_scene* scene = nullptr;
  ASSERT_EQ(graspkit_ray_scene_new(world, 1, &scene), GRASPKIT_OK);
  const graspkit_ray rays[3] = {{{0, 0, 1000}, {0, 0, -2}, 0, kInf},
                                {{5, 5, 1000}, {0, 0, -1}, 0, 500},  // stops short
                                {{-1000, 10, 0}, {1, 0, 0}, 0, kInf}};
  graspkit_ray_hit hits[3];
  ASSERT_EQ(graspkit_ray_scene_intersect(scene, rays, hits, 3), GRASPKIT_OK) << lastError();
  ASSERT_EQ(hits[0].hit, 1);
  EXPECT_NEAR(hits[0].distance, 940.0, 1e-3);
  EXPECT_NEAR(hits[0].point[2], 60.0, 1e-3);
  EXPECT_NEAR(hits[0].normal[2], 1.0, 1e-6);
  EXPECT_EQ(hits[0].body.kind, GRASPKIT_BODY);
  EXPECT_EQ(hits[0].body.index, 0);
  EXPECT_EQ(hits[1].hit, 0);
  ASSERT_EQ(hits[2].hit, 1);
  EXPECT_NEAR(hits[2].distance, 970.0, 1e-3);

  const double points[6] = {100, 0, 0, 0, 0, 200};
  graspkit_ray_hit nearest[2];
  ASSERT_EQ(graspkit_ray_scene_nearest(scene, points, 2, kInf, nearest), GRASPKIT_OK);
  EXPECT_NEAR(nearest[0].distance, 70.0, 1e-9);
  EXPECT_NEAR(nearest[0].point[0], 30.0, 1e-9);
  EXPECT_NEAR(nearest[1].distance, 140.0, 1e-9);
  ASSERT_EQ(graspkit_ray_scene_nearest(scene, points, 2, 100.0, nearest), GRASPKIT_OK);
  EXPECT_EQ(nearest[0].hit, 1);
  EXPECT_EQ(nearest[1].hit, 0) << "140 mm is beyond max_distance";

  // Moving the box and updating the scene moves the hits.
  const graspkit_pose up{{0, 0, 10}, {1, 0, 0, 0}};
  ASSERT_EQ(graspkit_body_set_pose(world, 0, &up), GRASPKIT_OK);
  ASSERT_EQ(graspkit_ray_scene_update(scene, world), GRASPKIT_OK);
  ASSERT_EQ(graspkit_ray_scene_intersect(scene, rays, hits, 1), GRASPKIT_OK);
  EXPECT_NEAR(hits[0].distance, 930.0, 1e-3);

  // Bad input fails the whole call and names the ray.
  graspkit_ray bad[2] = {rays[0], {{0, 0, 0}, {0, 0, 0}, 0, kInf}};
  EXPECT_EQ(graspkit_ray_scene_intersect(scene, bad, hits, 2), GRASPKIT_ERROR_INPUT);
  EXPECT_NE(lastError().find("ray 1: the direction is zero"), std::string::npos) << lastError();
  bad[1] = rays[0];
  bad[1].tmin = -1;
  EXPECT_EQ(graspkit_ray_scene_intersect(scene, bad, hits, 2), GRASPKIT_ERROR_INPUT);
  bad[1].tmin = 0;
  bad[1].origin[0] = NAN;
  EXPECT_EQ(graspkit_ray_scene_intersect(scene, bad, hits, 2), GRASPKIT_ERROR_INPUT);
  EXPECT_EQ(graspkit_ray_scene_intersect(scene, rays, nullptr, 1), GRASPKIT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(graspkit_ray_scene_intersect(scene, nullptr, nullptr, 0), GRASPKIT_OK);
  const double nan_point[3] = {0, NAN, 0};
  EXPECT_EQ(graspkit_ray_scene_nearest(scene, nan_point, 1, kInf, nearest), GRASPKIT_ERROR_INPUT);
  EXPECT_EQ(graspkit_ray_scene_nearest(scene, points, 1, -1, nearest), GRASPKIT_ERROR_INPUT);
  graspkit_ray_scene_free(scene);
}

TEST_F(CAbiPlannerMug, RayScenesWithAndWithoutTheHandsLinks) {
  graspkit_pose palm{};
  ASSERT_EQ(graspkit_robot_get_pose(world, 0, &palm), GRASPKIT_OK);
  // Six rays converging on the palm's origin from 1 m away.
  std::vector<graspkit_ray> rays;
  for (int axis = 0; axis < 3; ++axis)
    for (double sign : {-1.0, 1.0}) {
      graspkit_ray r{};
      for (int i = 0; i < 3; ++i) r.origin[i] = palm.translation[i];
      r.origin[axis] += sign * 1000;
      r.direction[axis] = -sign;
      r.tmax = kInf;
      rays.push_back(r);
    }
  auto linksHit = [&](int include_links) {
    graspkit_ray_scene* scene = nullptr;
    EXPECT_EQ(graspkit_ray_scene_new(world, include_links, &scene), GRASPKIT_OK);
    std::vector<graspkit_ray_hit> hits(rays.size());
    EXPECT_EQ(graspkit_ray_scene_intersect(scene, rays.data(), hits.data(), rays.size()),
              GRASPKIT_OK);
    graspkit_ray_scene_free(scene);
    int links = 0;
    for (const auto& h : hits) links += h.hit && h.body.kind == GRASPKIT_LINK;
    return links;
  };
  EXPECT_GT(linksHit(1), 0);
  EXPECT_EQ(linksHit(0), 0);
}

namespace {

// The ranking the plan promises: force closure first, then the larger epsilon.
bool ranksBefore(const graspkit_planned_grasp& a, const graspkit_planned_grasp& b) {
  if (a.force_closure != b.force_closure) return a.force_closure > b.force_closure;
  return a.epsilon >= b.epsilon;
}

}  // namespace

TEST_F(CAbiPlannerMug, PlannedGraspsRankAndReproduce) {
  graspkit_plan_options options;
  ASSERT_EQ(graspkit_plan_options_default(&options), GRASPKIT_OK);
  EXPECT_STREQ(options.planner, "simann");
  EXPECT_EQ(options.steps, 40000);
  options.steps = 3000;
  options.threads = 1;
  options.top = 5;
  graspkit_plan* plan = nullptr;
  ASSERT_EQ(graspkit_plan_grasps(world, 0, 0, &options, &plan), GRASPKIT_OK) << lastError();
  size_t count = 0;
  ASSERT_EQ(graspkit_plan_count(plan, &count), GRASPKIT_OK);
  ASSERT_GT(count, 0u);
  EXPECT_LE(count, 5u);
  std::vector<graspkit_planned_grasp> grasps(count);
  for (size_t i = 0; i < count; ++i)
    ASSERT_EQ(graspkit_plan_grasp(plan, i, &grasps[i]), GRASPKIT_OK);
  for (size_t i = 1; i < count; ++i) EXPECT_TRUE(ranksBefore(grasps[i - 1], grasps[i])) << i;

  // The world of grasp 0, measured again, gives what the plan measured.
  WorldPtr closed;
  ASSERT_EQ(graspkit_plan_grasp_world(plan, 0, &closed.w), GRASPKIT_OK);
  std::vector<double> dofs(4), world_dofs(4);
  ASSERT_EQ(graspkit_plan_grasp_dofs(plan, 0, dofs.data(), 4), GRASPKIT_OK);
  graspkit_robot_get_dofs(closed, 0, world_dofs.data(), 4);
  EXPECT_EQ(dofs, world_dofs);
  graspkit_pose pose{};
  graspkit_robot_get_pose(closed, 0, &pose);
  for (int i = 0; i < 3; ++i)
    EXPECT_NEAR(pose.translation[i], grasps[0].closed.translation[i], 1e-9);
  graspkit_grasp* grasp = nullptr;
  ASSERT_EQ(graspkit_grasp_analyze(closed, 0, 0, GRASPKIT_GWS_L1, &grasp), GRASPKIT_OK);
  graspkit_quality quality{};
  graspkit_grasp_quality(grasp, &quality);
  size_t contacts = 0;
  graspkit_grasp_contact_count(grasp, &contacts);
  EXPECT_EQ(static_cast<int32_t>(contacts), grasps[0].contacts);
  EXPECT_NEAR(quality.epsilon, grasps[0].epsilon, 1e-9);
  EXPECT_NEAR(quality.volume, grasps[0].volume, 1e-9);
  graspkit_grasp_free(grasp);

  // The planner left the caller's world alone.
  std::vector<double> original(4);
  graspkit_robot_get_dofs(world, 0, original.data(), 4);
  EXPECT_EQ(original, std::vector<double>(4, 0.0));

  graspkit_planned_grasp g{};
  EXPECT_EQ(graspkit_plan_grasp(plan, count, &g), GRASPKIT_ERROR_OUT_OF_RANGE);
  EXPECT_EQ(graspkit_plan_grasp_dofs(plan, 0, dofs.data(), 3), GRASPKIT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(graspkit_plan_grasp_world(plan, count, &closed.w), GRASPKIT_ERROR_OUT_OF_RANGE);
  graspkit_plan_free(plan);

  graspkit_plan* none = nullptr;
  options.energy = "no-such-energy";
  EXPECT_EQ(graspkit_plan_grasps(world, 0, 0, &options, &none), GRASPKIT_ERROR_INPUT);
  EXPECT_NE(lastError().find("no-such-energy"), std::string::npos) << lastError();
  options.energy = "contact";
  options.planner = "no-such-planner";
  EXPECT_EQ(graspkit_plan_grasps(world, 0, 0, &options, &none), GRASPKIT_ERROR_INPUT);
  options.planner = "simann";
  options.top = 0;  // a bad setting: the caller's argument, not the input files
  EXPECT_EQ(graspkit_plan_grasps(world, 0, 0, &options, &none), GRASPKIT_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(graspkit_plan_grasps(world, 0, 4, nullptr, &none), GRASPKIT_ERROR_OUT_OF_RANGE);
  EXPECT_EQ(none, nullptr);
}

TEST(CAbi, LuaScenarios) {
  const fs::path dir = scratchDir();
  int status = -1;
  const std::string exits = writeFile(dir / "exits.lua", "os.exit(tonumber(arg[1]))\n");
  const char* args[] = {"3"};
  graspkit_script_options options{};
  options.args = args;
  options.arg_count = 1;
  ASSERT_EQ(graspkit_run_script(exits.c_str(), &options, &status), GRASPKIT_OK) << lastError();
  EXPECT_EQ(status, 3);

  // The module is there: a world built in the script, its body counted.
  const std::string box = (modelsDir() / "objects/box.xml").string();
  const std::string counts =
      writeFile(dir / "counts.lua",
                "local w = graspkit.new_world()\nw:add_object(arg[1])\nos.exit(#w:bodies() == 1 "
                "and 0 or 9)\n");
  const char* box_arg[] = {box.c_str()};
  const std::string models = modelsDir().string();
  const char* roots[] = {models.c_str()};
  graspkit_script_options with_box{roots, 1, box_arg, 1, 0, 0};
  ASSERT_EQ(graspkit_run_script(counts.c_str(), &with_box, &status), GRASPKIT_OK) << lastError();
  EXPECT_EQ(status, 0);

  const std::string fails = writeFile(dir / "fails.lua", "local x = 1\nerror('boom')\n");
  EXPECT_EQ(graspkit_run_script(fails.c_str(), nullptr, &status), GRASPKIT_ERROR_SCRIPT);
  EXPECT_EQ(status, 1);
  EXPECT_NE(lastError().find("boom"), std::string::npos) << lastError();
  EXPECT_NE(lastError().find("fails.lua:2"), std::string::npos) << lastError();

  // The sandbox holds: no programs from a script.
  const std::string popen = writeFile(dir / "popen.lua", "io.popen('true')\n");
  EXPECT_EQ(graspkit_run_script(popen.c_str(), nullptr, &status), GRASPKIT_ERROR_SCRIPT);

  const std::string spins = writeFile(dir / "spins.lua", "while true do end\n");
  graspkit_script_options limited{};
  limited.timeout_seconds = 0.2;
  EXPECT_EQ(graspkit_run_script(spins.c_str(), &limited, &status), GRASPKIT_ERROR_SCRIPT);
  EXPECT_EQ(status, 124);
  limited.timeout_seconds = NAN;
  EXPECT_EQ(graspkit_run_script(spins.c_str(), &limited, &status), GRASPKIT_ERROR_INPUT);

  EXPECT_EQ(graspkit_run_script((dir / "missing.lua").c_str(), nullptr, &status),
            GRASPKIT_ERROR_INPUT);
  EXPECT_EQ(graspkit_run_script(exits.c_str(), nullptr, nullptr), GRASPKIT_ERROR_INVALID_ARGUMENT);
}

TEST(CAbi, Plugins) {
  char path[4096];
  size_t length = 0;
  ASSERT_EQ(graspkit_plugin_search_path(path, sizeof path, &length), GRASPKIT_OK);
  EXPECT_NE(std::string(path).find("graspkit/plugins"), std::string::npos) << path;

  size_t count = 0;
  ASSERT_EQ(graspkit_plugins_scan(&count), GRASPKIT_OK) << lastError();
  bool barrett = false;
  for (size_t i = 0; i < count; ++i) {
    char name[64], error[512];
    int loaded = -1;
    const graspkit_status s =
        graspkit_plugin_info(i, name, sizeof name, &loaded, error, sizeof error);
    ASSERT_TRUE(s == GRASPKIT_OK || s == GRASPKIT_ERROR_BUFFER_TOO_SMALL) << lastError();
    if (std::string(name) == "barrett") barrett = loaded == 1;
  }
  EXPECT_TRUE(barrett) << "the build's barrett plugin is on the search path and loads";
  int loaded = 0;
  char name[64];
  EXPECT_EQ(graspkit_plugin_info(count, name, sizeof name, &loaded, nullptr, 0),
            GRASPKIT_ERROR_OUT_OF_RANGE);

  const std::string not_a_plugin = writeFile(scratchDir() / "fake.so", "not an ELF file\n");
  EXPECT_EQ(graspkit_plugin_load(not_a_plugin.c_str()), GRASPKIT_ERROR_INPUT);
  EXPECT_NE(lastError().find("fake.so"), std::string::npos) << lastError();
}

TEST_F(CAbiPlannerMug, WorldsOnTwoThreadsAtOnce) {
  // Each thread its own clone (the header's rule); both close the hand to the same DOFs.
  WorldPtr a, b;
  ASSERT_EQ(graspkit_world_clone(world, &a.w), GRASPKIT_OK);
  ASSERT_EQ(graspkit_world_clone(world, &b.w), GRASPKIT_OK);
  graspkit_status sa = GRASPKIT_ERROR_INTERNAL, sb = GRASPKIT_ERROR_INTERNAL;
  std::thread ta([&] { sa = graspkit_robot_autograsp(a, 0, nullptr); });
  std::thread tb([&] { sb = graspkit_robot_autograsp(b, 0, nullptr); });
  ta.join();
  tb.join();
  ASSERT_EQ(sa, GRASPKIT_OK);
  ASSERT_EQ(sb, GRASPKIT_OK);
  std::vector<double> da(4), db(4);
  graspkit_robot_get_dofs(a, 0, da.data(), 4);
  graspkit_robot_get_dofs(b, 0, db.data(), 4);
  EXPECT_EQ(da, db);
}

// ---- Dynamics, pictures, generated objects and datasets --------------------------------------

// drop.xml's box lands and rests at half its 120 mm height plus 0.1 mm (the file's closed form);
// the frame callback runs before the first step and every `every` steps.
TEST(CAbi, SimulateDropsTheBoxWhereTheClosedFormPutsIt) {
  WorldPtr world;
  const std::string root = modelsDir().string();
  const char* roots[] = {root.c_str()};
  graspkit_load_options load = {};
  load.roots = roots;
  load.root_count = 1;
  ASSERT_EQ(graspkit_world_load((modelsDir() / "worlds/drop.xml").c_str(), &load, &world.w),
            GRASPKIT_OK)
      << lastError();
  graspkit_simulation_options options;
  ASSERT_EQ(graspkit_simulation_options_default(&options), GRASPKIT_OK);
  EXPECT_EQ(options.seconds, 1.0);
  EXPECT_EQ(options.dt, 0.0025);
  int frames = 0;
  options.every = 100;
  options.user = &frames;
  options.frame = [](const graspkit_world*, void* user) { ++*static_cast<int*>(user); };
  graspkit_simulation_result result;
  ASSERT_EQ(graspkit_world_simulate(world, &options, &result), GRASPKIT_OK) << lastError();
  EXPECT_EQ(result.completed, 1);
  EXPECT_EQ(result.steps, 400);
  EXPECT_EQ(frames, 1 + 4);
  graspkit_pose pose;
  ASSERT_EQ(graspkit_body_get_pose(world, 1, &pose), GRASPKIT_OK);
  EXPECT_NEAR(pose.translation[2], 60.1, 0.2);
  graspkit_step_report step;
  ASSERT_EQ(graspkit_world_step(world, 0.0, &step), GRASPKIT_OK);
  EXPECT_NEAR(step.time, 1.0025, 1e-9);
  EXPECT_EQ(graspkit_world_step(world, 1.0, &step), GRASPKIT_ERROR_INPUT);  // dt > 0.05 s
  options.every = 0;
  EXPECT_EQ(graspkit_world_simulate(world, &options, &result), GRASPKIT_ERROR_INVALID_ARGUMENT);
  // No hand to validate with.
  graspkit_validation validation;
  EXPECT_EQ(graspkit_validate(world, 0.5, &validation), GRASPKIT_ERROR_INPUT);
  EXPECT_NE(lastError().find("hand"), std::string::npos) << lastError();
  // Removing the floor leaves the box as body 0.
  ASSERT_EQ(graspkit_world_remove_body(world, 0), GRASPKIT_OK);
  int32_t count = 0;
  graspkit_world_body_count(world, &count);
  EXPECT_EQ(count, 1);
  int graspable = 0;
  graspkit_body_is_graspable(world, 0, &graspable);
  EXPECT_EQ(graspable, 1);
  EXPECT_EQ(graspkit_world_remove_body(world, 3), GRASPKIT_ERROR_OUT_OF_RANGE);
}

TEST(CAbi, RenderFillsTheBufferOrSaysItIsTooSmall) {
  WorldPtr world;
  loadOrFail((modelsDir() / "objects/box.xml").string(), world);
  graspkit_render_options options;
  ASSERT_EQ(graspkit_render_options_default(&options), GRASPKIT_OK);
  EXPECT_EQ(options.width, 640);
  EXPECT_EQ(options.height, 480);
  options.width = 64;
  options.height = 48;
  std::vector<uint8_t> rgb(64 * 48 * 3, 7);
  EXPECT_EQ(graspkit_world_render(world, &options, rgb.data(), rgb.size() - 1, nullptr),
            GRASPKIT_ERROR_BUFFER_TOO_SMALL);
  EXPECT_EQ(rgb[0], 7);  // nothing written
  ASSERT_EQ(graspkit_world_render(world, &options, rgb.data(), rgb.size(), nullptr), GRASPKIT_OK)
      << lastError();
  // The background is white (the renderer's default) and the box, in the middle, is not.
  EXPECT_EQ(rgb[0], 255);
  const std::size_t centre = (24 * 64 + 32) * 3;
  EXPECT_LT(int(rgb[centre]) + rgb[centre + 1] + rgb[centre + 2], 3 * 255);
  options.camera = "sideways";
  EXPECT_EQ(graspkit_world_render(world, &options, rgb.data(), rgb.size(), nullptr),
            GRASPKIT_ERROR_INPUT);
}

TEST(CAbi, LoadOptionsRefuseABadClosingDirection) {
  const int32_t closing[] = {0, 2};
  graspkit_load_options load = {};
  load.closing = closing;
  load.close_count = 2;
  WorldPtr world;
  EXPECT_EQ(graspkit_world_load((modelsDir() / "robots/urdf_gripper/urdf_gripper.urdf").c_str(),
                                &load, &world.w),
            GRASPKIT_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(lastError().find("closing[1]"), std::string::npos) << lastError();
  load.close_count = 0;
  load.urdf_material = "unobtainium";
  EXPECT_EQ(graspkit_world_load((modelsDir() / "robots/urdf_gripper/urdf_gripper.urdf").c_str(),
                                &load, &world.w),
            GRASPKIT_ERROR_INPUT);
  EXPECT_NE(lastError().find("unobtainium"), std::string::npos) << lastError();
}

// A dataset saved and loaded back gives the grasps it was planned with; out-of-range indices
// and NULLs are refused.
TEST(CAbi, DatasetsRoundTrip) {
  const fs::path folder = graspkit::test::scratchDir();
  char object[4096];
  size_t length = 0;
  ASSERT_EQ(graspkit_generate_object(folder.c_str(), 1, 0, object, sizeof object, &length),
            GRASPKIT_OK)
      << lastError();
  EXPECT_TRUE(fs::exists(object));
  EXPECT_EQ(std::string(object).size(), length);
  graspkit_dataset_options options;
  ASSERT_EQ(graspkit_dataset_options_default(&options), GRASPKIT_OK);
  EXPECT_EQ(options.grasps, 20);
  EXPECT_EQ(options.steps, 40000);
  options.grasps = 2;
  options.steps = 600;
  graspkit_dataset* planned = nullptr;
  const std::string hand = (modelsDir() / "robots/parallel_jaw/parallel_jaw.xml").string();
  ASSERT_EQ(graspkit_dataset_plan(hand.c_str(), object, nullptr, &options, &planned), GRASPKIT_OK)
      << lastError();
  const std::string file = (folder / "d.h5").string();
  ASSERT_EQ(graspkit_dataset_save(planned, file.c_str()), GRASPKIT_OK) << lastError();
  graspkit_dataset* loaded = nullptr;
  ASSERT_EQ(graspkit_dataset_load(file.c_str(), &loaded), GRASPKIT_OK) << lastError();
  size_t a = 0, b = 0;
  graspkit_dataset_count(planned, &a);
  graspkit_dataset_count(loaded, &b);
  ASSERT_EQ(a, b);
  ASSERT_GT(a, 0u);
  for (size_t i = 0; i < a; ++i) {
    graspkit_dataset_grasp x, y;
    ASSERT_EQ(graspkit_dataset_get_grasp(planned, i, &x), GRASPKIT_OK);
    ASSERT_EQ(graspkit_dataset_get_grasp(loaded, i, &y), GRASPKIT_OK);
    EXPECT_EQ(x.epsilon, y.epsilon);
    EXPECT_EQ(x.volume, y.volume);
    EXPECT_EQ(x.contacts, y.contacts);
    EXPECT_EQ(x.held, -1);  // not validated
    for (int k = 0; k < 3; ++k) EXPECT_EQ(x.grasp.translation[k], y.grasp.translation[k]);
  }
  graspkit_dataset_grasp g;
  EXPECT_EQ(graspkit_dataset_get_grasp(loaded, a, &g), GRASPKIT_ERROR_OUT_OF_RANGE);
  EXPECT_EQ(graspkit_dataset_load((folder / "missing.h5").c_str(), &loaded), GRASPKIT_ERROR_INPUT);
  graspkit_dataset_free(planned);
  graspkit_dataset_free(loaded);
}
