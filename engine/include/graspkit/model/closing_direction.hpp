#pragma once
// Which way each DOF of a published hand closes it. GraspIt!'s robot files say so themselves
// (the sign of <defaultVelocity>); URDF and MJCF say nothing, and "towards the upper limit" is
// wrong for many hands (a gripper whose 0 mm is closed, a Barrett whose fingers close towards
// their lower limits). Autograsp, the planners, derived virtual contacts and the dynamic close
// all follow the sign of Dof::defaultVelocity, so the choice is made once, here.
//
// The rule: the fingertips are the last links of the chains (each at the centre of its
// geometry's box); their centroid is the grasp centre. A DOF closes towards its lower limit when
// raising it carries the tips it moves steadily away from the grasp centre (at 10, 30, 50, 70
// and 90 % of its range, each farther than the last, by 10 % of their reach in all), with the
// other DOFs at their defaults and again at mid-range. Otherwise it closes towards its upper
// limit, as before: a finger's spread, a finger that passes the centre, and a DOF whose range is
// even about zero (within 10 % of its span: it bends both ways) keep that default.

#include <map>
#include <string>

#include "graspkit/model/robot.hpp"

namespace graspkit {

// +1 (towards the upper limit) or -1 per DOF, by the rule above.
std::vector<int> inferClosingDirections(const RobotModel& robot);

// Sets the sign of every DOF's defaultVelocity to `directions` (+1 or -1 each).
void setClosingDirections(RobotModel& robot, const std::vector<int>& directions);

}  // namespace graspkit
