// MuJoCo Menagerie's hands (../shared/hands/menagerie) read by graspkit, checked against
// MuJoCo itself (Debian libmujoco). For each DOF vector, the test takes every MJCF joint's value
// from graspkit's link poses (the rotation about, or slide along, the joint's own axis between
// its body and its parent), gives those values to MuJoCo's forward kinematics, and asks that
// MuJoCo put every body where graspkit does (1e-6 mm, 1e-9 in the axes): so each graspkit link
// moves relative to its parent exactly as the MJCF joint moves it. Then, with MuJoCo's numbers:
// - an actuated joint's value is its actuator's DOF value (one DOF per actuator);
// - joint equalities hold (q1 = c0 + c1 q2);
// - each connect loop stays closed within the 0.5 mm graspkit reports as its worst.
// Debian's MuJoCo (2.2.2) is older than Menagerie's files: the test hands it a copy without the
// parts it refuses and kinematics never reads (<option>, <extension>, <sensor>, plugin actuators,
// newer attributes), with the mesh folder made absolute.

#include <gtest/gtest.h>
#include <mujoco/mujoco.h>
#include <tinyxml2.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <memory>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "graspkit/collision/collision.hpp"
#include "graspkit/io/graspit/robot_export.hpp"
#include "graspkit/io/graspit/robot_file.hpp"
#include "graspkit/io/mjcf/mjcf_export.hpp"
#include "graspkit/io/mjcf/mjcf_file.hpp"
#include "graspkit/model/virtual_contact.hpp"
#include "graspkit/model/world.hpp"
#include "test_paths.hpp"

namespace graspkit {
namespace {

namespace fs = std::filesystem;
using tinyxml2::XMLElement;

struct MjModelDeleter {
  void operator()(mjModel* m) const { mj_deleteModel(m); }
};
struct MjDataDeleter {
  void operator()(mjData* d) const { mj_deleteData(d); }
};

void stripForOldMujoco(XMLElement* e) {
  for (const char* attr : {"dampratio", "gravcomp", "actdim", "texture", "texturedir"})
    e->DeleteAttribute(attr);
  for (XMLElement* c = e->FirstChildElement(); c;) {
    XMLElement* next = c->NextSiblingElement();
    const std::string tag = c->Name();
    if (tag == "option" || tag == "extension" || tag == "sensor" || tag == "plugin" ||
        tag == "texture")
      e->DeleteChild(c);
    else
      stripForOldMujoco(c);
    c = next;
  }
}

// A copy of `file` Debian's MuJoCo reads, in the scratch folder.
fs::path oldMujocoCopy(const fs::path& file) {
  tinyxml2::XMLDocument doc;
  EXPECT_EQ(doc.LoadFile(file.c_str()), tinyxml2::XML_SUCCESS);
  XMLElement* root = doc.RootElement();
  stripForOldMujoco(root);
  XMLElement* compiler = root->FirstChildElement("compiler");
  const char* meshdir = compiler ? compiler->Attribute("meshdir") : nullptr;
  // MuJoCo 2.3 made autolimits true by default; 2.2 needs it said.
  if (compiler && !compiler->Attribute("autolimits")) compiler->SetAttribute("autolimits", "true");
  if (compiler)
    compiler->SetAttribute("meshdir",
                           (file.parent_path() / (meshdir ? meshdir : "")).string().c_str());
  const fs::path copy = test::scratchDir() / ("mujoco_" + file.filename().string());
  doc.SaveFile(copy.c_str());
  return copy;
}

Transform mujocoPose(const mjData* d, int body) {
  Transform t = Transform::Identity();
  t.translation() =
      1000.0 * Vector3(d->xpos[3 * body], d->xpos[3 * body + 1], d->xpos[3 * body + 2]);
  t.linear() = Quaternion(d->xquat[4 * body], d->xquat[4 * body + 1], d->xquat[4 * body + 2],
                          d->xquat[4 * body + 3])
                   .toRotationMatrix();
  return t;
}

Transform localPose(const mjModel* m, int body) {
  Transform t = Transform::Identity();
  t.translation() =
      1000.0 * Vector3(m->body_pos[3 * body], m->body_pos[3 * body + 1], m->body_pos[3 * body + 2]);
  t.linear() = Quaternion(m->body_quat[4 * body], m->body_quat[4 * body + 1],
                          m->body_quat[4 * body + 2], m->body_quat[4 * body + 3])
                   .normalized()
                   .toRotationMatrix();
  return t;
}

class MenagerieHand {
 public:
  explicit MenagerieHand(const fs::path& file) : file_(file) {
    model_ = loadRobotFile(file);
    char error[1000] = "";
    m_.reset(mj_loadXML(oldMujocoCopy(file).c_str(), nullptr, error, sizeof(error)));
    if (!m_) {
      error_ = error;
      return;
    }
    d_.reset(mj_makeData(m_.get()));
    mj_kinematics(m_.get(), d_.get());  // qpos0: the frames the model is built in
    for (int b = 0; b < m_->nbody; ++b) rest_.push_back(mujocoPose(d_.get(), b));
    for (std::size_t c = 0; c < model_->chains.size(); ++c)
      for (std::size_t l = 0; l < model_->chains[c].links.size(); ++l)
        links_[model_->chains[c].links[l].name] = {static_cast<int>(c), static_cast<int>(l)};
  }

  const std::string& error() const { return error_; }
  const RobotModel& model() const { return *model_; }

  // graspkit's pose of MuJoCo body b: its link's pose times the body's fixed place on it.
  Transform graspkitPose(const Robot& robot, int b) const {
    auto link = [&](int body) {
      const char* name = mj_id2name(m_.get(), mjOBJ_BODY, body);
      return name ? links_.find(name) : links_.end();
    };
    int carrier = b;
    while (carrier > 0 && link(carrier) == links_.end()) carrier = m_->body_parentid[carrier];
    Transform link_pose = Transform::Identity();
    if (carrier > 0) {
      link_pose = robot.linkPose(link(carrier)->second);
    } else {
      carrier = 1;  // the palm: the first top-level body's frame
    }
    return link_pose * rest_[carrier].inverse() * rest_[b];
  }

  // Sets DOF values in graspkit, reads MuJoCo's joint values off graspkit's poses, runs
  // MuJoCo's kinematics and compares; returns MuJoCo's joint values.
  std::vector<double> check(const std::vector<double>& values) {
    Robot robot(model_);
    robot.setDofValues(values);
    std::vector<Transform> g(static_cast<std::size_t>(m_->nbody));
    for (int b = 1; b < m_->nbody; ++b) g[b] = graspkitPose(robot, b);
    for (int j = 0; j < m_->njnt; ++j) d_->qpos[m_->jnt_qposadr[j]] = m_->qpos0[m_->jnt_qposadr[j]];
    for (int b = 1; b < m_->nbody; ++b) {
      if (m_->body_jntnum[b] == 0 || m_->body_parentid[b] == 0) continue;
      EXPECT_EQ(m_->body_jntnum[b], 1) << "a body with several joints: not compared here";
      const int j = m_->body_jntadr[b];
      const Transform relative =
          (g[m_->body_parentid[b]] * localPose(m_.get(), b)).inverse() * g[b];
      const Vector3 axis(m_->jnt_axis[3 * j], m_->jnt_axis[3 * j + 1], m_->jnt_axis[3 * j + 2]);
      double motion = 0.0;
      if (m_->jnt_type[j] == mjJNT_HINGE) {
        const Matrix3 r = relative.linear();
        const Vector3 vee(r(2, 1) - r(1, 2), r(0, 2) - r(2, 0), r(1, 0) - r(0, 1));
        motion = std::atan2(0.5 * axis.dot(vee), 0.5 * (r.trace() - 1.0));
      } else {
        motion = axis.dot(relative.translation()) / 1000.0;
      }
      d_->qpos[m_->jnt_qposadr[j]] += motion;
    }
    mj_kinematics(m_.get(), d_.get());
    const Transform palm = rest_[1];
    for (int b = 1; b < m_->nbody; ++b) {
      const Transform mj = palm.inverse() * mujocoPose(d_.get(), b);
      EXPECT_LT((mj.translation() - g[b].translation()).norm(), 1e-6) << "body " << b;
      EXPECT_LT((mj.linear() - g[b].linear()).norm(), 1e-9) << "body " << b;
    }
    return {d_->qpos, d_->qpos + m_->nq};
  }

  double qpos(const char* joint) const {
    const int j = mj_name2id(m_.get(), mjOBJ_JOINT, joint);
    EXPECT_GE(j, 0) << joint;
    // graspkit's units: mm for a slide joint.
    return d_->qpos[m_->jnt_qposadr[j]] * (m_->jnt_type[j] == mjJNT_SLIDE ? 1000.0 : 1.0);
  }

  // The largest gap of a connect constraint and of a joint equality, in mm and rad.
  std::pair<double, double> equalityGaps() const {
    double connect = 0.0, joint = 0.0;
    for (int e = 0; e < m_->neq; ++e) {
      const double* data = m_->eq_data + mjNEQDATA * e;
      const int a = m_->eq_obj1id[e], b = m_->eq_obj2id[e];
      if (m_->eq_type[e] == mjEQ_CONNECT) {
        const Vector3 anchor = 1000.0 * Vector3(data[0], data[1], data[2]);
        const Vector3 world = rest_[a] * anchor;
        const Vector3 anchor2 = rest_[b].inverse() * world;
        const Vector3 p1 = mujocoPose(d_.get(), a) * anchor;
        const Vector3 p2 = mujocoPose(d_.get(), b) * anchor2;
        connect = std::max(connect, (p1 - p2).norm());
      } else if (m_->eq_type[e] == mjEQ_JOINT) {
        const double q1 = d_->qpos[m_->jnt_qposadr[a]] - m_->qpos0[m_->jnt_qposadr[a]];
        const double q2 = d_->qpos[m_->jnt_qposadr[b]] - m_->qpos0[m_->jnt_qposadr[b]];
        joint = std::max(joint, std::abs(q1 - (data[0] + data[1] * q2)));
      }
    }
    return {connect, joint};
  }

 private:
  fs::path file_;
  std::shared_ptr<const RobotModel> model_;
  std::unique_ptr<mjModel, MjModelDeleter> m_;
  std::unique_ptr<mjData, MjDataDeleter> d_;
  std::string error_;
  std::vector<Transform> rest_;
  std::map<std::string, LinkRef> links_;
};

// Each DOF at fractions of its range, then random vectors.
std::vector<std::vector<double>> dofSamples(const RobotModel& model) {
  std::vector<std::vector<double>> out;
  for (const double t : {0.0, 0.25, 0.5, 0.75, 1.0}) {
    std::vector<double> v;
    for (const Dof& dof : model.dofs) v.push_back(dof.min + t * (dof.max - dof.min));
    out.push_back(v);
  }
  std::mt19937 random(7);
  for (int k = 0; k < 4; ++k) {
    std::vector<double> v;
    for (const Dof& dof : model.dofs)
      v.push_back(std::uniform_real_distribution<double>(dof.min, dof.max)(random));
    out.push_back(v);
  }
  return out;
}

struct Expected {
  const char* file;
  int dofs;
  std::vector<std::pair<int, const char*>> actuated;  // DOF index, joint it drives directly
};

class MenagerieHands : public ::testing::TestWithParam<Expected> {};

TEST_P(MenagerieHands, LoadAsMujocoReadsThem) {
  GRASPKIT_REQUIRE_SHARED();
  const fs::path file = *test::sharedDir() / "hands" / "menagerie" / GetParam().file;
  if (!fs::exists(file)) GTEST_SKIP() << "SKIPPED: " << file << " not found";
  MenagerieHand hand(file);
  EXPECT_EQ(static_cast<int>(hand.model().dofs.size()), GetParam().dofs);
  ASSERT_TRUE(hand.error().empty()) << "Debian's MuJoCo refused the copy: " << hand.error();
  for (const std::vector<double>& values : dofSamples(hand.model())) {
    SCOPED_TRACE(::testing::PrintToString(values));
    hand.check(values);
    for (const auto& [dof, joint] : GetParam().actuated)
      EXPECT_NEAR(hand.qpos(joint), values[static_cast<std::size_t>(dof)], 1e-9) << joint;
    const auto [connect, joint] = hand.equalityGaps();
    EXPECT_LT(connect, 0.5) << "a four-bar loop opens (mm)";
    EXPECT_LT(joint, 1e-9) << "a joint equality breaks (rad)";
  }
}

INSTANTIATE_TEST_SUITE_P(
    Menagerie, MenagerieHands,
    ::testing::Values(Expected{"umi_gripper/umi_gripper.xml",
                               1,
                               {{0, "right_finger_joint"}, {0, "left_finger_joint"}}},
                      Expected{"robotiq_2f85_v4/2f85.xml",
                               1,
                               {{0, "right_driver_joint"}, {0, "left_driver_joint"}}},
                      Expected{"shadow_dexee/shadow_dexee.xml",
                               12,
                               {{0, "F0/J0"}, {3, "F0/J3"}, {5, "F1/J1"}, {11, "F2/J3"}}},
                      Expected{"ufactory_xarm7/hand.xml",
                               1,
                               {{0, "right_driver_joint"}, {0, "left_driver_joint"}}}),
    [](const auto& info) {
      return fs::path(info.param.file).stem().string() == "hand" ? std::string("xarm7_hand")
             : fs::path(info.param.file).stem().string() == "2f85"
                 ? std::string("robotiq_2f85")
                 : fs::path(info.param.file).stem().string();
    });

}  // namespace
}  // namespace graspkit

namespace graspkit {
namespace {

// Shadow DEX-EE's three fingers meet at the zero posture (their middle and distal links
// collide), yet they are free in most postures: the hand setup keeps those pairs checked, and
// switches off only what the file excludes.
TEST(MenagerieHandSetup, FingersThatMeetAtRestStayChecked) {
  GRASPKIT_REQUIRE_SHARED();
  const fs::path file = *test::sharedDir() / "hands/menagerie/shadow_dexee/shadow_dexee.xml";
  if (!fs::exists(file)) GTEST_SKIP() << "SKIPPED: " << file << " not found";
  const auto model = loadRobotFile(file);
  for (const CollisionPair& p : model->disabledCollisions)
    EXPECT_EQ(p.reason, "MJCF <contact><exclude>");
  World world;
  world.addRobot(Robot(model));
  world.setDofValues(0, std::vector<double>(model->dofs.size(), 0.0));
  int across_fingers = 0;
  for (const CollidingPair& p : collisionReport(world))
    if (p.first.link.chain >= 0 && p.second.link.chain >= 0 &&
        p.first.link.chain != p.second.link.chain)
      ++across_fingers;
  EXPECT_GT(across_fingers, 0) << "the fingers should meet at the zero posture";
}

}  // namespace
}  // namespace graspkit

namespace graspkit {
namespace {

// The names of the links a hand's setup puts virtual contacts on ("palm" for the palm).
std::set<std::string> contactLinks(const RobotModel& model) {
  std::set<std::string> out;
  for (const VirtualContact& v : model.virtualContacts)
    out.insert(v.finger < 0 ? "palm" : model.chains[v.finger].links[v.link].name);
  return out;
}

// The planner's energy pulls virtual contacts to the object. On the Robotiq 2F-85 the DOF that
// moves the fingertips (the followers, with the pads) also moves the inner bars (the drivers and
// spring links), which end nearer the palm: only the palm and the followers get contacts. Each
// of the Allegro's four fingers is a chain of its own: its fingertip gets one.
TEST(MenagerieHandSetup, VirtualContactsSitOnThePalmAndTheFingertips) {
  GRASPKIT_REQUIRE_SHARED();
  const fs::path robotiq = *test::sharedDir() / "hands/menagerie/robotiq_2f85_v4/2f85.xml";
  const fs::path allegro = *test::sharedDir() /
                           "hands/dex-urdf/robots/hands/allegro_hand/variation/"
                           "allegro_hand_right_fsr_simple.urdf";
  if (!fs::exists(robotiq) || !fs::exists(allegro)) GTEST_SKIP() << "SKIPPED: hands not found";
  EXPECT_EQ(contactLinks(*loadRobotFile(robotiq)),
            (std::set<std::string>{"palm", "left_follower", "right_follower"}));
  EXPECT_EQ(contactLinks(*loadRobotFile(allegro)),
            (std::set<std::string>{"palm", "link_3.0", "link_7.0", "link_11.0", "link_15.0"}));
}

}  // namespace
}  // namespace graspkit

namespace graspkit {
namespace {

// Menagerie's hands written back as MJCF by graspkit and read again: the same DOFs, every link
// where it was at the same DOF vectors (a DOF reads back as its first joint's value), and the
// excluded pairs still excluded.
TEST(MenagerieRoundTrip, MjcfWrittenByGraspkitReadsBackToTheSameHand) {
  GRASPKIT_REQUIRE_SHARED();
  for (const char* name :
       {"robotiq_2f85_v4/2f85.xml", "shadow_dexee/shadow_dexee.xml", "ufactory_xarm7/hand.xml"}) {
    SCOPED_TRACE(name);
    const fs::path file = *test::sharedDir() / "hands/menagerie" / name;
    if (!fs::exists(file)) GTEST_SKIP() << "SKIPPED: " << file << " not found";
    const auto original = loadRobotFile(file);
    const fs::path written = saveMjcf(*original, test::scratchDir() / "round_trip");
    const auto back = loadMjcfFile(written);
    ASSERT_EQ(back->dofs.size(), original->dofs.size());
    ASSERT_EQ(back->chains.size(), original->chains.size());
    for (std::size_t c = 0; c < original->chains.size(); ++c)
      ASSERT_EQ(back->chains[c].links.size(), original->chains[c].links.size());
    Robot a(original), b(back);
    for (const std::vector<double>& values : dofSamples(*original)) {
      a.setDofValues(values);
      std::vector<double> scaled;
      for (std::size_t d = 0; d < values.size(); ++d)
        scaled.push_back(values[d] * original->joint(original->dofs[d].joints.front()).ratio);
      b.setDofValues(scaled);
      for (std::size_t c = 0; c < original->chains.size(); ++c)
        for (std::size_t l = 0; l < original->chains[c].links.size(); ++l) {
          const Transform pa = a.linkPose(static_cast<int>(c), static_cast<int>(l));
          const Transform pb = b.linkPose(static_cast<int>(c), static_cast<int>(l));
          EXPECT_LT((pa.translation() - pb.translation()).norm(), 1e-6) << c << " " << l;
          EXPECT_LT((pa.linear() - pb.linear()).norm(), 1e-9) << c << " " << l;
        }
    }
    for (const CollisionPair& pair : original->disabledCollisions) {
      const bool kept = std::any_of(back->disabledCollisions.begin(),
                                    back->disabledCollisions.end(), [&](const CollisionPair& p) {
                                      return (p.first == pair.first && p.second == pair.second) ||
                                             (p.first == pair.second && p.second == pair.first);
                                    });
      EXPECT_TRUE(kept) << pair.reason;
    }
  }
}

}  // namespace
}  // namespace graspkit

namespace graspkit {
namespace {

// The hand setup travels into a GraspIt! robot file (convert --to graspit): the same closing
// directions, switched-off pairs and virtual contacts (each at the same place in the world and
// facing the same way at a DOF vector), so GraspIt! and graspkit plan with the same hand.
TEST(MenagerieRoundTrip, GraspitRobotFilesCarryTheHandSetup) {
  GRASPKIT_REQUIRE_SHARED();
  const fs::path file = *test::sharedDir() / "hands/menagerie/robotiq_2f85_v4/2f85.xml";
  if (!fs::exists(file)) GTEST_SKIP() << "SKIPPED: " << file << " not found";
  const auto original = loadRobotFile(file);
  const auto back = loadRobotFile(saveRobotFile(*original, test::scratchDir() / "graspit"));
  ASSERT_EQ(back->dofs.size(), original->dofs.size());
  for (std::size_t d = 0; d < back->dofs.size(); ++d)
    EXPECT_EQ(back->dofs[d].defaultVelocity > 0, original->dofs[d].defaultVelocity > 0);
  EXPECT_EQ(back->disabledCollisions.size(), original->disabledCollisions.size());
  ASSERT_EQ(back->virtualContacts.size(), original->virtualContacts.size());
  Robot a(original), b(back);
  const std::vector<double> values{0.5};
  a.setDofValues(values);
  b.setDofValues(values);
  for (std::size_t k = 0; k < original->virtualContacts.size(); ++k) {
    const VirtualContact& va = original->virtualContacts[k];
    const VirtualContact& vb = back->virtualContacts[k];
    const Transform pa = va.finger < 0 ? a.pose() : a.linkPose(va.finger, va.link);
    const Transform pb = vb.finger < 0 ? b.pose() : b.linkPose(vb.finger, vb.link);
    EXPECT_LT((pa * va.location - pb * vb.location).norm(), 1e-6);
    EXPECT_LT((pa.linear() * va.normal - pb.linear() * vb.normal).norm(), 1e-9);
  }
}

}  // namespace
}  // namespace graspkit
