#pragma once
// Pictures of a world, ray cast through the engine's own Embree scene (no GPU, no display):
// bodies shaded in their file colours (or their material's), and optionally a grasp's contacts
// as markers with their friction cones.
//
// Cameras follow Inventor's convention, as GraspIt!'s <camera> does: the camera looks along -z
// of its frame with +y up, and heightAngle is the full vertical field of view.

#include <array>
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

// How a picture draws robot links (the hand).
enum class HandStyle {
  Solid,        // opaque, in their colours: what lies behind a link is hidden
  Outline,      // dark silhouette and crease lines over a faint fill: contacts behind a finger
                // stay visible, and the hand's shape still reads
  Transparent,  // each link surface blends its colour with what lies behind it
};

// "solid", "outline" or "transparent"; nullopt for any other name.
std::optional<HandStyle> handStyleNamed(const std::string& name);
const char* handStyleName(HandStyle style);

// How far apart two colours look on a shaded picture: the Euclidean distance of their
// chromatic parts (each colour less its grey, the mean of its channels; 0..1 each) and half the
// difference of those greys. Lightness counts half because shading spreads one surface's
// lightness over a wide range: a grey palm and a lighter grey mug look alike once shaded.
double colourDistance(const Colour& a, const Colour& b);
// Two colours closer than this look alike on a picture (greys 0.55 and 0.85, or a glass light
// blue and a light grey, are alike; a grey and kHandPalette's colours, or black and light grey,
// are not).
inline constexpr double kAlikeColourDistance = 0.3;
// The hand colours a picture falls back on, in order of preference: blue, amber, green, violet.
// None is red or orange, the colours of contact markers.
inline constexpr std::array<Colour, 4> kHandPalette = {
    Colour{0.25f, 0.50f, 0.85f}, Colour{0.95f, 0.68f, 0.18f}, Colour{0.15f, 0.65f, 0.35f},
    Colour{0.60f, 0.30f, 0.85f}};
// The colour a hand link is drawn in beside an object of colour `object`: `hand` itself when the
// two are not alike (colourDistance >= kAlikeColourDistance), else the first colour of
// kHandPalette that is not alike `object`.
Colour separatedColour(const Colour& hand, const Colour& object);
// A body's colour as a whole: its triangles' file colours weighted by area, or its material's.
Colour surfaceColour(const World& world, const BodyRef& body);

struct RenderRequest {
  int width = 640;
  int height = 480;
  ViewCamera camera;
  Colour background{1.0f, 1.0f, 1.0f};
  // Contacts to mark: a small solid sphere at each contact's point on body2 (the object, for a
  // grasp's contacts) and its friction cone drawn as thin lines (about 1.5 pixels wide at any
  // distance): the rim circle and four generators from the apex at the point, opening along the
  // normal with half angle atan(mu). Markers hide behind any opaque surface in front of them (a
  // Solid hand's links too). Sizes are in mm; 0 picks 4 % and 25 % of the radius of the first
  // contact's body2 (the object).
  std::vector<Contact> contacts;
  double markerRadius = 0.0;
  double coneLength = 0.0;
  // Samples per pixel along each axis (1: one ray a pixel; 2: four, averaged).
  int samples = 1;

  // The look. The defaults draw the world as it stands: no floor, solid links, the files'
  // colours; graspkit render turns on the floor, the outline hand (for grasps) and separated
  // colours.
  //
  // A floor: a plane perpendicular to the world's up (+z, as frameBodies frames) just under the
  // lowest point of `focus` (every body when empty), in a light neutral grey that fades into the
  // background a few focus radii out, with the shadows of the bodies from a soft light above
  // (tilted a little towards the camera, so a shadow falls behind what casts it). Bodies outside
  // `focus` (a world's own floor or table) get the same shadows. Not drawn for a camera below it.
  bool floor = false;
  std::vector<BodyRef> focus;
  HandStyle hand = HandStyle::Solid;  // how every robot's links are drawn
  // When a hand link's colour is alike the object's (graspSubject's hand and object), the link
  // is drawn in separatedColour's palette colour instead (the object keeps its own).
  bool separateColours = false;
};

// Renders `world` as the request says. Throws graspkit::Error for a side outside 1..16384 or
// more than 4096 x 4096 pixels, a non-finite camera, or samples outside 1..4.
Image render(const World& world, const RenderRequest& request);

}  // namespace graspkit
