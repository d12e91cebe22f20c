#pragma once
// Tendons and tendon wrappers of tendon-driven hands, and their geometry and statics.
//
// A tendon is a cable routed through insertion points fixed on links (the first and last are
// its anchors). Between two consecutive points it runs straight, unless the straight segment
// cuts into a tendon wrapper (a cylinder on a link), in which case the tendon is routed through
// an extra point on the cylinder's surface. The tendon's length is the length of that polyline.
// A tendon under tension F pulls every point of its route towards its neighbours; the resulting
// joint torques are the generalised forces of those point forces, so that by virtual work
// tau_j = -F * dL/dq_j with the route held fixed on its links.
//
// The rules reproduce GraspIt!'s tendon-driven hands (see tendonPath for the wrapping rule).

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "graspkit/model/link.hpp"

namespace graspkit {

class Robot;

struct TendonInsertionPoint {
  LinkRef link;
  Vector3 position = Vector3::Zero();  // mm, link frame
  double friction = 0.0;
};

struct Tendon {
  std::string name;
  double stiffness = 0.0;  // already multiplied by 1e6
  // The file's rest length and pre-tension (mm); absent when the file gives none, in which case
  // the rest length comes from the tendon's length at the robot's default posture.
  std::optional<double> restLength;
  std::optional<double> preTensionLength;
  // Whether the tendon acts as a spring when stretched past its rest length. Robot types whose
  // tendons are plain cables (not muscles) switch it off in configure().
  bool passiveForce = true;
  std::vector<TendonInsertionPoint> insertionPoints;
};

struct TendonWrapper {
  LinkRef link;
  double friction = 0.0;
  Vector3 position = Vector3::Zero();      // centre of the cylinder, link frame
  Vector3 orientation = Vector3::UnitZ();  // axis direction, link frame (used as written)
  double radius = 0.0;
  double length = 10.0;  // along the axis; GraspIt!'s default when the file gives none
  std::vector<std::string> exemptions;                         // tendon names
  std::vector<std::pair<std::string, Vector3>> wrappingSides;  // tendon name, side direction
  bool exempts(const std::string& tendon) const;
};

// A point of a tendon's route. It moves with `link`; `local` is its position in that link's
// frame and `world` its position at the posture the route was computed for.
struct TendonPathPoint {
  LinkRef link;
  Vector3 local = Vector3::Zero();
  Vector3 world = Vector3::Zero();
  int insertionPoint = -1;  // index in Tendon::insertionPoints, or -1 for a wrap point
  int wrapper = -1;         // for a wrap point, the index of its wrapper in tendonWrappers
  bool isWrapPoint() const { return insertionPoint < 0; }
};

struct TendonPath {
  std::vector<TendonPathPoint> points;
  double length = 0.0;  // mm, the sum of the segment lengths
};

// The route of tendon `tendon` of the robot at its current posture: its insertion points, with
// wrap points added where a segment cuts into a wrapper the tendon is not exempt from. A segment
// a-b cuts into a wrapper when the closest points of line a-b and of the wrapper's axis lie
// strictly inside a-b and within the axis segment (length long, centred on the wrapper's
// position), and are closer than 0.995 x radius. The wrap point is then put on the cylinder's
// surface, radially out from the axis through the segment's closest point, and the segments
// either side are checked again (at most 12 passes per segment). Afterwards a wrap point whose
// neighbours no longer need it is dropped. Wrapping sides are read but, as in GraspIt!, unused.
// Throws graspkit::Error for a tendon index out of range.
TendonPath tendonPath(const Robot& robot, int tendon);

// The length of `path` at the robot's current posture with the route held fixed on its links
// (the points keep their link-frame positions; no wrap point is added or removed).
double tendonLength(const Robot& robot, const TendonPath& path);

// The rest length: the file's restLength when given; otherwise the tendon's length at the
// robot model's default posture, less the pre-tension length when one is given.
double tendonRestLength(const Robot& robot, int tendon);

// The tension of a tendon of length `length`: the active force (negative values count as 0)
// plus, when the tendon acts as a spring, stiffness x (length - rest length) if that is
// positive. Units: g mm/s^2 (1e-6 N).
double tendonForce(const Tendon& tendon, double length, double rest_length,
                   double active_force = 0.0);

// The force the tendon applies at each point of its route under tension `force`: towards the
// next point at the first, towards the previous one at the last, and the sum of both unit
// directions times `force` at the points between. World frame.
std::vector<Vector3> insertionForces(const TendonPath& path, double force);

// The torque (force for a prismatic joint) on every joint of the robot, robot-wide joint order,
// from tension `force` along `path`: the sum over route points of the moment of the point force
// about each joint axis the point hangs from. A positive torque drives the joint value up.
// `path` must be the route at the robot's current posture (force directions come from it).
Eigen::VectorXd tendonJointTorques(const Robot& robot, const TendonPath& path, double force);
// The same along the tendon's current route.
Eigen::VectorXd tendonJointTorques(const Robot& robot, int tendon, double force);

}  // namespace graspkit
