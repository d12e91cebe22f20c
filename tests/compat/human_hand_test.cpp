// GraspIt!'s tendon-driven hands from the shared corpus: the two HumanFinger files (type
// HumanHand) and the three McGrip files load through the human_hand plugin with the classes
// GraspIt! reports for them; their tendons behave as their anatomy says when the finger flexes
// (flexors shorten, extensors lengthen; McGrip's tendons close its fingers, GraspIt!'s positive
// joint direction); and the joint torques of a tendon agree with a second method, virtual
// work: tau_j = -F dL/dq_j, with dL/dq_j by central differences of the length along the same
// route held fixed on its links.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <regex>
#include <string>
#include <vector>

#include "graspkit/base/error.hpp"
#include "graspkit/base/log.hpp"
#include "graspkit/io/graspit/robot_file.hpp"
#include "graspkit/model/robot.hpp"
#include "graspkit/model/tendon.hpp"
#include "quiet_warnings.hpp"
#include "reference.hpp"
#include "test_paths.hpp"
#include "xml_scan.hpp"

namespace graspkit {
namespace {

namespace fs = std::filesystem;

const std::vector<std::string> kTendonHandFiles = {
    "models/robots/HumanFinger/HumanFinger.xml", "models/robots/HumanFinger/ComplexHumanFinger.xml",
    "models/robots/McHand/McGrip.xml",           "models/robots/McHand/McGrip_optim.xml",
    "models/robots/McHand/McGrip_tall.xml",
};

using test::QuietWarnings;

std::shared_ptr<const RobotModel> load(const std::string& file) {
  QuietWarnings quiet;
  return loadRobotFile(*test::graspitDataDir() / file);
}

// GraspIt!'s class for a corpus file, from its survey in the reference figures.
std::string graspitClass(const std::string& file) {
  for (const auto& entry : test::referenceJson().at("robot_survey_shared"))
    if (entry.at("file") == file) return entry.at("class");
  return "";
}

std::size_t countElements(const fs::path& file, const std::string& tag) {
  const std::string text = test::readText(file);
  const std::regex open("<" + tag + R"([\s>])");
  return std::distance(std::sregex_iterator(text.begin(), text.end(), open),
                       std::sregex_iterator());
}

TEST(HumanHandCompat, FilesLoadWithTheirOwnTypes) {
  GRASPKIT_REQUIRE_SHARED();
  for (const std::string& file : kTendonHandFiles) {
    SCOPED_TRACE(file);
    const auto model = load(file);
    EXPECT_EQ(model->type, graspitClass(file));
    ASSERT_NE(model->robotType, nullptr);
    EXPECT_NE(model->typeProvider.find("human_hand"), std::string::npos) << model->typeProvider;
    const fs::path path = *test::graspitDataDir() / file;
    EXPECT_EQ(model->tendons.size(), countElements(path, "tendon"));
    EXPECT_EQ(model->tendonWrappers.size(), countElements(path, "tendonWrapper"));
    EXPECT_GT(model->tendons.size(), 0u);
    // McGrip's tendons are cables: no passive spring force. HumanHand's are muscles.
    for (const Tendon& tendon : model->tendons) {
      EXPECT_EQ(tendon.passiveForce, model->type == "HumanHand") << tendon.name;
      Tendon stiff = tendon;
      stiff.stiffness = 1.0e6;
      EXPECT_EQ(tendonForce(stiff, 11.0, 10.0, 5.0), stiff.passiveForce ? 1.0e6 + 5.0 : 5.0);
    }
  }
}

// Whether a tendon crosses joint `joint` of chain `chain`: it has points on both sides.
bool crosses(const Tendon& tendon, int chain, int joint, const KinematicChain& kc) {
  bool proximal = false, distal = false;
  for (const TendonInsertionPoint& p : tendon.insertionPoints) {
    const bool after = p.link.chain == chain && kc.links[p.link.link].lastJoint >= joint;
    (after ? distal : proximal) = true;
  }
  return proximal && distal;
}

// +1 when the tendon must lengthen as its finger flexes, -1 when it must shorten, 0 when its
// name does not say. Flexion is the positive joint direction on both hands (HumanFinger's
// ranges start at 0; GraspIt!'s McGrip notes a positive torque is a flexion).
int anatomy(const std::string& name) {
  if (name.rfind("Flexor", 0) == 0 || name.rfind("Finger", 0) == 0) return -1;
  if (name.find("Extensor") != std::string::npos) return +1;
  return 0;
}

TEST(HumanHandCompat, TendonLengthFollowsFlexion) {
  GRASPKIT_REQUIRE_SHARED();
  int swept = 0;
  for (const std::string& file : kTendonHandFiles) {
    const auto model = load(file);
    Robot robot(model);
    for (std::size_t t = 0; t < model->tendons.size(); ++t) {
      const Tendon& tendon = model->tendons[t];
      const int sign = anatomy(tendon.name);
      if (sign == 0) continue;
      for (std::size_t d = 0; d < model->dofs.size(); ++d) {
        const int joint = model->dofs[d].joints.at(0);
        int chain = 0;
        while (joint >= model->chains[chain].firstJoint +
                            static_cast<int>(model->chains[chain].joints.size()))
          ++chain;
        const KinematicChain& kc = model->chains[chain];
        SCOPED_TRACE(file + ": " + tendon.name + ", dof " + std::to_string(d));
        std::vector<double> q(model->dofs.size());
        for (std::size_t e = 0; e < q.size(); ++e) q[e] = model->dofs[e].clamp(0.0);
        const Dof& dof = model->dofs[d];
        std::vector<double> lengths;
        for (int k = 0; k <= 20; ++k) {
          q[d] = dof.min + (dof.max - dof.min) * k / 20.0;
          robot.setDofValues(q);
          lengths.push_back(tendonPath(robot, static_cast<int>(t)).length);
        }
        if (!crosses(tendon, chain, joint - kc.firstJoint, kc)) {
          for (double l : lengths) EXPECT_NEAR(l, lengths.front(), 1e-9);
          continue;
        }
        ++swept;
        // Strictly monotonic over the first three quarters of the range. Beyond, the file's
        // Flexor Sublimis line crosses the MCP axis near full flexion (its length rises by
        // 0.17 mm over the last 5% of the range): a property of its insertion points.
        for (std::size_t k = 1; k <= 15; ++k)
          EXPECT_GT(sign * (lengths[k] - lengths[k - 1]), 0.0) << "step " << k;
        EXPECT_GT(sign * (lengths.back() - lengths.front()), 1.0);  // mm over the range
      }
    }
  }
  EXPECT_GE(swept, 20);
}

TEST(HumanHandCompat, JointTorquesAreVirtualWork) {
  GRASPKIT_REQUIRE_SHARED();
  std::mt19937 random(7);
  constexpr double kForce = 1.0e6;  // 1 N
  constexpr double kStep = 1e-6;    // rad
  int wrapped = 0, checked = 0;
  for (const std::string& file : kTendonHandFiles) {
    const auto model = load(file);
    Robot robot(model);
    for (int trial = 0; trial < 5; ++trial) {
      std::vector<double> q(model->dofs.size());
      for (std::size_t d = 0; d < q.size(); ++d)
        q[d] =
            std::uniform_real_distribution<double>(model->dofs[d].min, model->dofs[d].max)(random);
      for (std::size_t t = 0; t < model->tendons.size(); ++t) {
        robot.setDofValues(q);
        const TendonPath path = tendonPath(robot, static_cast<int>(t));
        for (const TendonPathPoint& p : path.points) wrapped += p.isWrapPoint();
        const Eigen::VectorXd tau = tendonJointTorques(robot, path, kForce);
        for (std::size_t d = 0; d < q.size(); ++d) {
          SCOPED_TRACE(file + ": " + model->tendons[t].name + ", dof " + std::to_string(d));
          auto lengthAt = [&](double value) {
            std::vector<double> moved = q;
            moved[d] = value;
            robot.setDofValues(moved, LimitPolicy::Ignore);
            return tendonLength(robot, path);
          };
          const double dl = (lengthAt(q[d] + kStep) - lengthAt(q[d] - kStep)) / (2 * kStep);
          // The DOF's generalised force: its joints' torques through the coupling ratios.
          double generalised = 0.0;
          for (int j : model->dofs[d].joints) generalised += model->joint(j).ratio * tau[j];
          // Within 1e-6 mm of moment arm.
          EXPECT_NEAR(generalised, -kForce * dl, 1e-6 * kForce) << "tau " << generalised;
          ++checked;
        }
      }
    }
  }
  EXPECT_GT(wrapped, 0);  // the extensors wrap over the knuckles at random postures
  EXPECT_GT(checked, 100);
}

// A one-link HumanHand written at test time, with the given tendon and wrapper elements.
fs::path writeTendonHand(const std::string& extra) {
  const fs::path dir = test::scratchDir() / "TendonHand";
  fs::create_directories(dir / "iv");
  std::ofstream(dir / "iv" / "cube.off")
      << "OFF\n8 6 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n"
         "4 0 3 2 1\n4 4 5 6 7\n4 0 1 5 4\n4 2 3 7 6\n4 1 2 6 5\n4 0 4 7 3\n";
  std::ofstream(dir / "iv" / "link.xml")
      << "<root><material>plastic</material><mass>10</mass>"
         "<geometryFile type=\"off\">cube.off</geometryFile></root>\n";
  const fs::path file = dir / "TendonHand.xml";
  std::ofstream(file)
      << "<?xml version=\"1.0\" ?>\n<robot type=\"HumanHand\">\n  <palm>link.xml</palm>\n"
         "  <dof type=\"r\"><defaultVelocity>1</defaultVelocity><maxEffort>1</maxEffort>"
         "<Kp>1</Kp><Kd>1</Kd><draggerScale>1</draggerScale></dof>\n"
         "  <chain><joint type=\"Revolute\"><theta>d0</theta><d>0</d><a>10</a><alpha>0</alpha>"
         "<minValue>0</minValue><maxValue>90</maxValue></joint>"
         "<link dynamicJointType=\"Revolute\">link.xml</link></chain>\n"
      << extra << "</robot>\n";
  return file;
}

const std::string kGoodTendon =
    "<tendon name=\"t\"><insertionPoint><chain>-1</chain><link>-1</link>"
    "<position>0 -2 0</position></insertionPoint><insertionPoint><chain>0</chain><link>0</link>"
    "<position>-5 -2 0</position></insertionPoint></tendon>\n";

void expectErrorNamingFile(const std::string& extra, const std::string& words) {
  const fs::path file = writeTendonHand(extra);
  try {
    QuietWarnings quiet;
    loadRobotFile(file);
    ADD_FAILURE() << "loaded a robot with a bad tendon: " << extra;
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("TendonHand.xml"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
  }
}

TEST(HumanHandCompat, BadTendonsAreErrorsNamingTheFile) {
  // Needs only the plugin, not the corpus. A good file loads.
  const auto good = loadRobotFile(writeTendonHand(kGoodTendon));
  EXPECT_EQ(good->tendons.size(), 1u);
  EXPECT_FALSE(good->tendons[0].restLength.has_value());
  expectErrorNamingFile(
      "<tendon><insertionPoint><chain>-1</chain><link>-1</link><position>0 0 0</position>"
      "</insertionPoint><insertionPoint><chain>0</chain><link>0</link><position>0 0 0"
      "</position></insertionPoint></tendon>\n",
      "no name");
  expectErrorNamingFile(
      kGoodTendon +
          "<tendonWrapper><chain>0</chain><link>0</link><position>0 0 0</position>"
          "<orientation>0 0 1</orientation><radius>0</radius></tendonWrapper>\n",
      "radius");
  expectErrorNamingFile(
      kGoodTendon +
          "<tendonWrapper><chain>0</chain><link>0</link><position>0 0 0</position>"
          "<orientation>0 0 0</orientation><radius>2</radius></tendonWrapper>\n",
      "orientation");
  expectErrorNamingFile(
      "<tendon name=\"t\"><insertionPoint><chain>0</chain><link>3</link><position>0 0 0"
      "</position></insertionPoint><insertionPoint><chain>0</chain><link>0</link><position>0 "
      "0 0</position></insertionPoint></tendon>\n",
      "link");
}

}  // namespace
}  // namespace graspkit
