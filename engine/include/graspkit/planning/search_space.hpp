#pragma once
// The variables a grasp planner searches over: where the hand is (a position space) and how it is
// shaped (a posture space), each variable with its range, its largest jump and its flags, as in
// GraspIt!'s eigengrasp planner. A SearchSpace maps a vector of variable values to a hand pose
// and DOF values; SearchState (search_state.hpp) is one such vector with its energy.
//
// Variables come posture first, then position, as GraspIt! orders them.

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "graspkit/base/enum_names.hpp"
#include "graspkit/math/transform.hpp"
#include "graspkit/planning/eigengrasp_map.hpp"

namespace graspkit {

struct RobotModel;

enum class PositionSpace {
  Complete,   // Tx Ty Tz (+-250 mm, jump 100) and a quaternion Qw..Qz (+-5, jump 1), unnormalised
  AxisAngle,  // Tx Ty (+-250) Tz (-250..350) jump 150; theta [0,pi], phi (circular), alpha [0,pi]
  Ellipsoid,  // the hand on an ellipsoid around the object: beta, gamma, tau, dist
  Approach,   // along the hand's approach direction from its start: dist and two wrist angles
};
enum class PostureSpace {
  Eigen,  // eigengrasp amplitudes (range from the file, +-4, or the DOF range for identity sets;
          // jump = range / 4)
  Dof,    // DOF values (the DOF's range, jump = range / 2)
};

// "complete", "axis-angle", "ellipsoid", "approach"; "eigen", "dof". GraspIt!'s names
// (SPACE_AXIS_ANGLE, POSE_EIGEN, ...) are accepted too (base/enum_names.hpp: nameOf, valueNamed,
// parseNamed).
std::span<const EnumName<PositionSpace>> enumNames(std::type_identity<PositionSpace>);
std::span<const EnumName<PostureSpace>> enumNames(std::type_identity<PostureSpace>);

struct SearchVariable {
  std::string name;
  double min = 0.0;
  double max = 0.0;
  double jump = 0.0;      // the neighbour generator's largest step
  bool circular = false;  // wraps around instead of being redrawn
  bool fixed = false;     // never changed by the search
  double range() const { return max - min; }
};

class SearchSpace {
 public:
  // `reference` is what the position is relative to: the object's pose for the complete,
  // axis-angle and ellipsoid spaces, the hand's starting pose for the approach space.
  SearchSpace(const RobotModel& hand, PositionSpace position, PostureSpace posture,
              const Transform& reference);

  PositionSpace positionSpace() const { return position_; }
  PostureSpace postureSpace() const { return posture_; }
  const Transform& reference() const { return reference_; }
  const Transform& approachFrame() const { return approach_; }  // in the palm frame

  int size() const { return static_cast<int>(variables_.size()); }
  int postureSize() const { return posture_count_; }
  std::span<const SearchVariable> variables() const { return variables_; }
  // Index of the variable called `name`, or nullopt.
  std::optional<int> find(std::string_view name) const;
  // Lets a caller narrow a variable or fix it. Throws graspkit::Error for an index out of
  // range or a range that is empty or not finite.
  void setVariable(int index, const SearchVariable& variable);

  // The hand's world pose (its palm frame) for `values`.
  Transform handPose(std::span<const double> values) const;
  // The DOF values for `values`, within the DOFs' ranges.
  std::vector<double> dofs(std::span<const double> values) const;
  // The values that put the hand at `handPose` with DOFs `dofs` (eigen postures are projected).
  // Throws graspkit::Error for the ellipsoid space, which has no inverse (as in GraspIt!).
  std::vector<double> encode(const Transform& handPose, std::span<const double> dofs) const;

  // GraspIt!'s distance between two states: the larger of the approach frames' distance over
  // `lengthScale` (the object's max radius) and half their angle over pi.
  double distance(std::span<const double> a, std::span<const double> b, double lengthScale) const;

 private:
  Transform corePose(std::span<const double> position) const;

  PositionSpace position_;
  PostureSpace posture_;
  Transform reference_;
  Transform approach_;
  EigengraspMap eigengrasps_;
  std::vector<double> dofMin_;
  std::vector<double> dofMax_;
  std::vector<SearchVariable> variables_;
  int posture_count_ = 0;
};

}  // namespace graspkit
