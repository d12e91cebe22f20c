#pragma once
// Pictures of a world, ray cast through the engine's own Embree scene (no GPU, no display):
// bodies shaded in their file colours (or their material's), and optionally a grasp's contacts
// as markers with their friction cones.
//
// Cameras follow Inventor's convention, as GraspIt!'s <camera> does: the camera looks along -z
// of its frame with +y up, and heightAngle is the full vertical field of view.

#include <optional>
#include <span>
#include <string>
#include <vector>

#include "graspkit/collision/contact.hpp"
#include "graspkit/geometry/mesh.hpp"
#include "graspkit/math/transform.hpp"
#include "graspkit/model/material.hpp"
#include "graspkit/render/image.hpp"

namespace graspkit {

class World;
struct Camera;

struct ViewCamera {
  Vector3 position = Vector3::Zero();               // world, mm
  Quaternion orientation = Quaternion::Identity();  // camera frame in the world
  double heightAngle = 0.785398163397448;           // radians: Inventor's default, pi/4
};

// The camera of a world file's <camera> (Inventor's default height angle).
ViewCamera viewCameraFrom(const Camera& camera);

struct BoundingSphere {
  Vector3 centre = Vector3::Zero();  // world, mm
  double radius = 0.0;               // mm
};

// A sphere around the vertices of `bodies` in the world (every body when empty), centred on
// their bounding box; radius 100 mm around the origin when there are none.
BoundingSphere boundingSphere(const World& world, std::span<const BodyRef> bodies);

// A camera on the side `direction` points to (world), looking back at the bounding sphere of
// `bodies` (every body of the world when empty) so that the sphere fills the view of an
// image `aspect` (width / height) wide. Up is the world's +z, or +y when looking along z.
ViewCamera frameBodies(const World& world, std::span<const BodyRef> bodies,
                       const Vector3& direction, double aspect);

// What a picture of a world shows as its grasp: the world's first hand (its first robot when no
// robot is a hand) and its first graspable body; either may be absent.
struct GraspSubject {
  std::optional<int> hand;
  std::optional<BodyRef> object;
};
GraspSubject graspSubject(const World& world);

// What a picture of a grasp frames: the subject's hand links and object (graspSubject).
std::vector<BodyRef> handAndObject(const World& world);

// The views render and view offer by name (kViewNames): "world" is the world file's <camera>,
// "auto" that camera when the world has one and "iso" otherwise; "iso" and the axes ("+x" puts
// the camera on the +x side) frame `focus` (every body when empty). Throws graspkit::Error for
// an unknown name, or "world" in a world without a camera.
inline constexpr const char* kViewNames = "auto, world, iso, +x, -x, +y, -y, +z, -z";
ViewCamera namedView(const World& world, const std::string& name, std::span<const BodyRef> focus,
                     double aspect);

// Where world point `point` lands in a width x height picture: x right, y down, in pixels, the
// centre of the top-left pixel at (0.5, 0.5). nullopt for a point behind the camera.
std::optional<Eigen::Vector2d> projectPoint(const ViewCamera& camera, int width, int height,
                                            const Vector3& point);

struct RenderRequest {
  int width = 640;
  int height = 480;
  ViewCamera camera;
  Colour background{1.0f, 1.0f, 1.0f};
  // Contacts to mark: a sphere at each contact's point on body2 (the object, for a grasp's
  // contacts) and its friction cone, apex at the point, opening along the normal with half
  // angle atan(mu). Markers show through robot links (they lie under the fingertips) but not
  // through other bodies. Sizes are in mm; 0 picks 5 % and 25 % of the radius of the first
  // contact's body2 (the object).
  std::vector<Contact> contacts;
  double markerRadius = 0.0;
  double coneLength = 0.0;
  // Samples per pixel along each axis (1: one ray a pixel; 2: four, averaged).
  int samples = 1;
};

// Renders `world` as the request says. Throws graspkit::Error for a side outside 1..16384 or
// more than 4096 x 4096 pixels, a non-finite camera, or samples outside 1..4.
Image render(const World& world, const RenderRequest& request);

}  // namespace graspkit
