// Ray casting a world: one ray per pixel (or per sample), built in float straight into Embree
// packets of 8 and traced through a RayScene's scene (raycast::SceneAccess: a picture needs
// only a hit's body, triangle and facing, not RayScene's checked double-precision hits); each
// hit is shaded as it comes back. A see-through hand's links are looked through with more rays
// (one per link surface), and what lies in front of the first opaque surface (those links,
// contact spheres, the lines of friction cones) is blended over it back to front. The floor is
// a plane met in closed form, its shadows found with Embree occlusion rays towards a disc
// light. Outline edges are found between neighbouring samples, a few rows behind the tracing.
#include "graspkit/render/render.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <span>

#include <fmt/format.h>

#include "graspkit/base/error.hpp"
#include "graspkit/model/body_ref.hpp"
#include "graspkit/model/world.hpp"
#include "graspkit/raycast/ray_scene.hpp"
#include "raycast/scene_access.hpp"

namespace graspkit {

ViewCamera viewCameraFrom(const Camera& camera) {
  ViewCamera view;
  view.position = camera.position;
  view.orientation = camera.orientation.normalized();
  return view;
}

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

}  // namespace

BoundingSphere boundingSphere(const World& world, std::span<const BodyRef> bodies) {
  const std::vector<BodyRef> all = bodies.empty() ? worldBodies(world) : std::vector<BodyRef>{};
  if (bodies.empty()) bodies = all;
  Eigen::AlignedBox3d box;
  for (const BodyRef& body : bodies) {
    const Transform pose = bodyPose(world, body);
    const auto& mesh = bodyModel(world, body).mesh;
    if (!mesh) continue;
    for (const Vector3& v : mesh->vertices) box.extend(pose * v);
  }
  if (box.isEmpty()) return {Vector3::Zero(), 100.0};
  const Vector3 centre = box.center();
  double radius = 0.0;
  for (const BodyRef& body : bodies) {
    const Transform pose = bodyPose(world, body);
    const auto& mesh = bodyModel(world, body).mesh;
    if (!mesh) continue;
    for (const Vector3& v : mesh->vertices) radius = std::max(radius, (pose * v - centre).norm());
  }
  return {centre, std::max(radius, 1.0)};
}

ViewCamera frameBodies(const World& world, std::span<const BodyRef> bodies,
                       const Vector3& direction, double aspect) {
  const auto [centre, radius] = boundingSphere(world, bodies);
  if (!centre.allFinite() || !(radius < 1e9))
    throw Error(
        fmt::format("cannot frame the bodies: they span {} mm about ({}, {}, {}); is a "
                    "pose far out or not finite?",
                    radius, centre.x(), centre.y(), centre.z()));
  if (!direction.allFinite() || direction.norm() == 0.0)
    throw Error("frameBodies: the view direction must be finite and non-zero");
  const Vector3 back = direction.normalized();  // camera +z: from the scene towards the camera
  const Vector3 worldUp = std::abs(back.z()) > 0.99 ? Vector3::UnitY() : Vector3::UnitZ();
  const Vector3 right = worldUp.cross(back).normalized();
  const Vector3 up = back.cross(right);
  Matrix3 axes;
  axes << right, up, back;
  ViewCamera camera;
  camera.orientation = Quaternion(axes).normalized();
  const double halfHeight = camera.heightAngle / 2.0;
  const double halfWidth = std::atan(std::tan(halfHeight) * std::max(aspect, 1e-3));
  const double distance = radius / std::sin(std::min(halfHeight, halfWidth));
  camera.position = centre + back * distance;
  return camera;
}

GraspSubject graspSubject(const World& world) {
  GraspSubject subject;
  subject.hand = world.firstHand();
  if (!subject.hand && world.robotCount() > 0) subject.hand = 0;
  for (int i = 0; i < static_cast<int>(world.bodies().size()); ++i) {
    if (world.bodies()[static_cast<std::size_t>(i)].isDynamic()) {
      subject.object = BodyRef::body(i);
      break;
    }
  }
  return subject;
}

std::vector<BodyRef> handAndObject(const World& world) {
  const GraspSubject subject = graspSubject(world);
  std::vector<BodyRef> focus;
  for (const BodyRef& body : worldBodies(world)) {
    const bool ofHand = body.isLink() && subject.hand && body.index == *subject.hand;
    if (ofHand || (subject.object && body == *subject.object)) focus.push_back(body);
  }
  return focus;
}

ViewCamera namedView(const World& world, const std::string& name, std::span<const BodyRef> focus,
                     double aspect) {
  if (name == "world" || (name == "auto" && world.camera())) {
    if (!world.camera())
      throw Error("camera 'world': the world file has no <camera>; use auto, iso or an axis");
    return viewCameraFrom(*world.camera());
  }
  static const std::vector<std::pair<std::string, Vector3>> kSides = {
      {"auto", Vector3(1.0, -1.3, 0.9)}, {"iso", Vector3(1.0, -1.3, 0.9)},
      {"+x", Vector3::UnitX()},          {"-x", -Vector3::UnitX()},
      {"+y", Vector3::UnitY()},          {"-y", -Vector3::UnitY()},
      {"+z", Vector3::UnitZ()},          {"-z", -Vector3::UnitZ()}};
  for (const auto& [side, direction] : kSides)
    if (side == name) return frameBodies(world, focus, direction, aspect);
  throw Error(fmt::format("camera '{}': not one of {}", name, kViewNames));
}

std::optional<Eigen::Vector2d> projectPoint(const ViewCamera& camera, int width, int height,
                                            const Vector3& point) {
  const Vector3 local = camera.orientation.conjugate() * (point - camera.position);
  if (local.z() >= 0.0) return std::nullopt;
  const double scale = std::tan(camera.heightAngle / 2.0);
  const double aspect = static_cast<double>(width) / height;
  const double x = local.x() / -local.z() / (scale * aspect);
  const double y = local.y() / -local.z() / scale;
  return Eigen::Vector2d((x + 1.0) * 0.5 * width, (1.0 - y) * 0.5 * height);
}

std::optional<HandStyle> handStyleNamed(const std::string& name) {
  if (name == "solid") return HandStyle::Solid;
  if (name == "outline") return HandStyle::Outline;
  if (name == "transparent") return HandStyle::Transparent;
  return std::nullopt;
}

const char* handStyleName(HandStyle style) {
  switch (style) {
    case HandStyle::Solid:
      return "solid";
    case HandStyle::Outline:
      return "outline";
    case HandStyle::Transparent:
      return "transparent";
  }
  return "solid";
}

double colourDistance(const Colour& a, const Colour& b) {
  const Eigen::Vector3d d(a.r - b.r, a.g - b.g, a.b - b.b);
  const double lightness = d.mean();
  return std::hypot((d - Eigen::Vector3d::Constant(lightness)).norm(), 0.5 * lightness);
}

Colour separatedColour(const Colour& hand, const Colour& object) {
  if (colourDistance(hand, object) >= kAlikeColourDistance) return hand;
  // Blue and amber are over 2 * kAlikeColourDistance apart: no colour is alike both.
  for (const Colour& c : kHandPalette)
    if (colourDistance(c, object) >= kAlikeColourDistance) return c;
  return kHandPalette.front();
}

Colour surfaceColour(const World& world, const BodyRef& body) {
  const BodyModel& model = bodyModel(world, body);
  const Colour material = materialColour(model.material);
  const auto& mesh = model.mesh;
  if (!mesh || mesh->triangleColours.size() != mesh->triangles.size()) return material;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  double area = 0.0;
  for (std::size_t i = 0; i < mesh->triangles.size(); ++i) {
    const auto& t = mesh->triangles[i];
    const double a = 0.5 * (mesh->vertices[t[1]] - mesh->vertices[t[0]])
                               .cross(mesh->vertices[t[2]] - mesh->vertices[t[0]])
                               .norm();
    const Colour& c = mesh->triangleColours[i];
    sum += a * Eigen::Vector3d(c.r, c.g, c.b);
    area += a;
  }
  if (!(area > 0.0)) return material;
  sum /= area;
  return {static_cast<float>(sum.x()), static_cast<float>(sum.y()), static_cast<float>(sum.z())};
}

namespace {

// What a hit on one instance of the scene needs: its colours and its rotation (Embree reports
// normals in the instance's own frame).
struct InstanceLook {
  bool isLink = false;
  bool receivesShadow = false;  // outside the focus, with a floor: a world's own floor or table
  const std::vector<Colour>* triangles = nullptr;  // null or empty: the material's colour
  Colour material;
  std::optional<Colour> separated;  // the colour that replaces the file's (separateColours)
  Eigen::Matrix3f rotation;
};

// A surface hit as the tracer shades it.
struct SurfaceHit {
  double distance = kInfinity;  // mm; infinity for a miss
  int instance = -1;
  Colour colour;
  Vector3 normal = Vector3::UnitZ();  // world, unit
};

// A contact's marker sphere and the lines of its friction cone.
struct ContactMarker {
  Vector3 point;
  double radius;
  std::vector<std::pair<Vector3, Vector3>> lines;  // the rim's chords, then the generators
  Vector3 axis;                                    // unit, the cone opens along it
  Vector3 rimCentre;
  double rim = 0.0;     // the rim's radius; 0: no rim among the lines
  Vector3 boundCentre;  // a sphere around sphere and cone, for a cheap miss
  double boundRadius;
  double cullRadius = kInfinity;  // boundRadius and the lines' width there, seen from the camera
};

constexpr int kRimSegments = 32;
constexpr int kGenerators = 4;
constexpr double kLineWidth = 1.5;  // pixels, the cones' lines at any distance

std::vector<ContactMarker> contactMarkers(const RenderRequest& request, double objectRadius) {
  std::vector<ContactMarker> markers;
  const double radius = request.markerRadius > 0 ? request.markerRadius : 0.04 * objectRadius;
  const double length = request.coneLength > 0 ? request.coneLength : 0.25 * objectRadius;
  for (const Contact& c : request.contacts) {
    if (!c.position2.allFinite() || !c.normal.allFinite() || c.normal.norm() == 0.0) continue;
    ContactMarker m;
    m.point = c.position2;
    m.radius = radius;
    const Vector3 axis = c.normal.normalized();
    m.axis = axis;
    const Vector3 u = axis.unitOrthogonal();
    const Vector3 v = axis.cross(u);
    const double rim = length * std::tan(std::atan(std::max(c.mu, 0.0)));
    const Vector3 centre = m.point + axis * length;
    m.rimCentre = centre;
    m.rim = rim;
    const auto rimPoint = [&](double angle) {
      return centre + rim * (std::cos(angle) * u + std::sin(angle) * v);
    };
    if (rim > 0.0) {
      for (int i = 0; i < kRimSegments; ++i)
        m.lines.emplace_back(rimPoint(2.0 * std::numbers::pi * i / kRimSegments),
                             rimPoint(2.0 * std::numbers::pi * (i + 1) / kRimSegments));
      for (int i = 0; i < kGenerators; ++i)
        m.lines.emplace_back(m.point, rimPoint(2.0 * std::numbers::pi * (i + 0.5) / kGenerators));
    } else {
      m.lines.emplace_back(m.point, centre);  // no friction: the normal alone
    }
    m.boundCentre = m.point + axis * (length / 2.0);
    m.boundRadius = std::hypot(length / 2.0, rim) + radius;
    markers.push_back(std::move(m));
  }
  return markers;
}

double sphereEntry(const Vector3& origin, const Vector3& direction, const Vector3& centre,
                   double radius) {
  const Vector3 oc = origin - centre;
  const double b = oc.dot(direction);
  const double c = oc.squaredNorm() - radius * radius;
  const double disc = b * b - c;
  if (disc < 0.0) return kInfinity;
  const double root = std::sqrt(disc);
  if (-b - root > 0.0) return -b - root;
  return -b + root > 0.0 ? 0.0 : kInfinity;  // inside: the entry is the origin
}

// Where the ray (unit direction) passes closest to segment a-b: the ray's distance there and
// how far apart the two are.
std::pair<double, double> closestApproach(const Vector3& origin, const Vector3& direction,
                                          const Vector3& a, const Vector3& b) {
  const Vector3 e = b - a;
  const Vector3 w0 = origin - a;
  const double de = direction.dot(e), ee = e.dot(e);
  const double dw = direction.dot(w0), ew = e.dot(w0);
  const double denom = ee - de * de;
  double s = denom > 1e-12 * ee ? (ew - dw * de) / denom : 0.0;
  s = std::clamp(s, 0.0, 1.0);
  const double t = std::max(0.0, s * de - dw);
  return {t, (w0 + t * direction - s * e).norm()};
}

// Headlight shading with a key light above and left of the camera, so shapes read in depth.
Eigen::Vector3f shade(const Colour& base, Vector3 normal, const Vector3& direction,
                      const Vector3& keyLight) {
  if (normal.dot(direction) > 0.0) normal = -normal;  // the side facing the camera
  const double facing = -normal.dot(direction);
  const double key = std::max(0.0, normal.dot(keyLight));
  const float light = static_cast<float>(0.3 + 0.5 * facing + 0.35 * key);
  return Eigen::Vector3f(base.r, base.g, base.b) * light;
}

Eigen::Vector3f rgb(const Colour& c) {
  return {c.r, c.g, c.b};
}

const Colour kMarkerColour{0.85f, 0.1f, 0.1f};
const Colour kConeColour{0.8f, 0.2f, 0.05f};
const Colour kFloorColour{0.9f, 0.9f, 0.88f};
const Eigen::Vector3f kEdgeColour(0.1f, 0.1f, 0.12f);
constexpr float kEdgeOpacity = 0.9f;
constexpr float kOutlineFill = 0.15f;      // each link surface's opacity, outline hands
constexpr float kTransparentFill = 0.35f;  // and transparent ones
constexpr int kMaxLinkLayers = 8;          // link surfaces a ray sees through; then opaque
constexpr double kCreaseCos = 0.8;         // normals further apart than ~37 degrees: a crease
// Rays per sample in a penumbra, towards a disc light: 16 with one sample a pixel, 4 with more
// (a pixel of 4 samples then averages 16, in 4 turns of the pattern).
constexpr int kShadowRays = 16;
constexpr double kLightRadius = 0.12;  // the light's angular radius, radians
constexpr float kShadowDepth = 0.4f;   // how much a full shadow takes from the light

// What a sample leaves for the outline pass: its colour, and the nearest link it sees.
struct Sample {
  Eigen::Vector3f colour;
  int link = -1;  // the instance of the nearest link; -1 none
  float depth = 0.0f;
  Eigen::Vector3f normal = Eigen::Vector3f::UnitZ();
};

// Something drawn over the first opaque surface a ray meets: a see-through link, a marker.
struct Fragment {
  double t;
  Eigen::Vector3f colour;
  float alpha;
};

struct Floor {
  double height = 0.0;                 // z of the plane, mm
  Vector3 centre;                      // the focus's centre
  double inner = 0.0;                  // opaque within this distance of the centre (horizontal)
  double outer = 0.0;                  // faded into the background beyond
  Vector3 light;                       // unit, towards the light
  Vector3 lightU, lightV;              // unit, across the light's direction
  BoundingSphere casters;              // the focus, whose shadows are looked for
  std::vector<BoundingSphere> pieces;  // each body of the focus
  // Points of the light's disc (offsets across its direction, radians): a sunflower spiral.
  std::array<Eigen::Vector2d, kShadowRays> disc;
  int rays = kShadowRays;  // how many of them a sample in a penumbra traces
};

struct Tracer {
  const RenderRequest& request;
  RTCScene scene = nullptr;
  std::vector<InstanceLook> instances;  // by Embree instance id
  std::vector<ContactMarker> markers;
  Vector3 keyLight;
  std::optional<Floor> floor;
  double sampleAngle = 0.0;  // a sample's width over its distance (small angles)
  double pixelAngle = 0.0;

  SurfaceHit surfaceHit(unsigned instance, unsigned triangle, float t, float nx, float ny,
                        float nz) const {
    const InstanceLook& look = instances[instance];
    SurfaceHit hit;
    hit.distance = t;
    hit.instance = static_cast<int>(instance);
    hit.colour = look.separated                                        ? *look.separated
                 : look.triangles && triangle < look.triangles->size() ? (*look.triangles)[triangle]
                                                                       : look.material;
    const Eigen::Vector3f n = look.rotation * Eigen::Vector3f(nx, ny, nz);
    const float length = n.norm();
    hit.normal = length > 0.0f ? Vector3((n / length).cast<double>()) : Vector3::UnitZ();
    return hit;
  }

  bool isLink(const SurfaceHit& hit) const {
    return hit.instance >= 0 && instances[static_cast<std::size_t>(hit.instance)].isLink;
  }

  // The share of the light a point sees (0: in full shadow): up to kShadowRays rays towards points
  // of the light's disc, turned by `spin` so that neighbouring samples sample it differently.
  double lightSeen(const Vector3& point, double spin) const {
    const Floor& f = *floor;
    // A ray that passes nowhere near a caster's sphere cannot be stopped by it: trace only
    // when some sphere lies within the cone about the light of half angle asin(radius /
    // distance) + kLightRadius.
    const auto within = [&](const BoundingSphere& sphere) {
      const Vector3 toCentre = sphere.centre - point;
      const double distance = toCentre.norm();
      if (distance <= sphere.radius) return true;
      const double sine = sphere.radius / distance;
      const double limit =
          std::sqrt(1.0 - sine * sine) * std::cos(kLightRadius) - sine * std::sin(kLightRadius);
      return toCentre.dot(f.light) >= limit * distance;
    };
    if (!within(f.casters) || std::none_of(f.pieces.begin(), f.pieces.end(), within)) return 1.0;
    const double spinCos = std::cos(spin), spinSin = std::sin(spin);
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    // How many of the rays towards the disc's points ids[0..count) (count <= 4) reach the light,
    // traced as one Embree packet.
    const auto seenOf = [&](const std::array<int, 4>& ids, int count) {
      alignas(16) RTCRay4 rays;
      alignas(16) int valid[4];
      for (int k = 0; k < 4; ++k) {
        valid[k] = k < count ? -1 : 0;
        const Eigen::Vector2d& o = f.disc[static_cast<std::size_t>(ids[std::min(k, count - 1)])];
        const double u = spinCos * o.x() - spinSin * o.y(), v = spinSin * o.x() + spinCos * o.y();
        const Vector3 d = (f.light + u * f.lightU + v * f.lightV).normalized();
        rays.org_x[k] = static_cast<float>(point.x());
        rays.org_y[k] = static_cast<float>(point.y());
        rays.org_z[k] = static_cast<float>(point.z());
        rays.dir_x[k] = static_cast<float>(d.x());
        rays.dir_y[k] = static_cast<float>(d.y());
        rays.dir_z[k] = static_cast<float>(d.z());
        rays.tnear[k] = 0.0f;
        rays.tfar[k] = std::numeric_limits<float>::infinity();
        rays.time[k] = 0.0f;
        rays.mask[k] = ~0u;
        rays.id[k] = static_cast<unsigned>(k);
        rays.flags[k] = 0;
      }
      rtcOccluded4(valid, scene, &context, &rays);
      int seen = 0;
      for (int k = 0; k < count; ++k)
        seen += rays.tfar[k] >= 0.0f ? 1 : 0;  // Embree sets tfar to -inf when blocked
      return seen;
    };
    // Four rays spread over the disc first: when they agree, the point is taken as wholly lit
    // or wholly shadowed; in a penumbra all f.rays are traced.
    const int stride = f.rays / 4;
    if (stride == 1) return seenOf({0, 1, 2, 3}, 4) / 4.0;
    int seen = seenOf({1, 1 + stride, 1 + 2 * stride, 1 + 3 * stride}, 4);
    if (seen == 0 || seen == 4) return seen / 4.0;
    std::array<int, 4> ids{};
    int count = 0;
    for (int i = 0; i < f.rays; ++i) {
      if (i % stride == 1) continue;
      ids[static_cast<std::size_t>(count++)] = i;
      if (count == 4) {
        seen += seenOf(ids, 4);
        count = 0;
      }
    }
    if (count > 0) seen += seenOf(ids, count);
    return static_cast<double>(seen) / f.rays;
  }

  // The colour of the first opaque thing along the ray (`hit`, or the floor before it, or the
  // background), shadowed where the request has a floor.
  Eigen::Vector3f baseColour(const Vector3& origin, const Vector3& d, const SurfaceHit& hit,
                             double floorT, double spin) const {
    const Eigen::Vector3f background = rgb(request.background);
    if (floorT < hit.distance) {
      const Floor& f = *floor;
      const Vector3 p = origin + floorT * d;
      const double r = (p - f.centre).head<2>().norm();
      if (r >= f.outer) return background;
      const double x = std::clamp((r - f.inner) / (f.outer - f.inner), 0.0, 1.0);
      const float fade = static_cast<float>(1.0 - x * x * (3.0 - 2.0 * x));
      const Vector3 lifted(p.x(), p.y(), f.height + 1e-3 * f.casters.radius);
      const float lit = 1.0f - kShadowDepth * (1.0f - static_cast<float>(lightSeen(lifted, spin)));
      return (1.0f - fade) * background + fade * lit * rgb(kFloorColour);
    }
    if (hit.distance == kInfinity) return background;
    Eigen::Vector3f colour = shade(hit.colour, hit.normal, d, keyLight);
    if (floor && instances[static_cast<std::size_t>(hit.instance)].receivesShadow) {
      Vector3 n = hit.normal.dot(d) > 0.0 ? -hit.normal : hit.normal;
      if (n.dot(floor->light) > 0.0) {
        const Vector3 p = origin + hit.distance * d + n * (1e-3 * floor->casters.radius);
        colour *= 1.0f - kShadowDepth * (1.0f - static_cast<float>(lightSeen(p, spin)));
      }
    }
    return colour;
  }

  // One sample: `links`, the see-through links the camera ray passed, nearest first, and
  // `hit`, the first opaque surface behind them (or a miss).
  Sample sample(const Vector3& origin, const Vector3& d, std::span<const SurfaceHit> links,
                const SurfaceHit& hit, double spin) const {
    Sample out;
    std::array<Fragment, 24> fragments;
    std::size_t count = 0;
    const auto add = [&](const Fragment& f) {
      if (count < fragments.size()) fragments[count++] = f;
    };
    const float fill = request.hand == HandStyle::Outline ? kOutlineFill : kTransparentFill;
    for (const SurfaceHit& link : links) {
      if (out.link < 0) {
        out.link = link.instance;
        out.depth = static_cast<float>(link.distance);
        const Vector3 n = link.normal.dot(d) > 0.0 ? -link.normal : link.normal;
        out.normal = n.cast<float>();
      }
      add({link.distance, shade(link.colour, link.normal, d, keyLight), fill});
    }
    double floorT = kInfinity;
    if (floor && d.z() < 0.0 && origin.z() > floor->height)
      floorT = (floor->height - origin.z()) / d.z();
    const double opaque = std::min(hit.distance, floorT);
    if (out.link >= 0 && out.depth >= opaque) out.link = -1;  // below the floor
    for (const ContactMarker& m : markers) {
      if (sphereEntry(origin, d, m.boundCentre, m.cullRadius) >= opaque) continue;
      const double ts = sphereEntry(origin, d, m.point, m.radius);
      if (ts < opaque) {
        const Vector3 normal = (origin + ts * d - m.point).normalized();
        add({ts, shade(kMarkerColour, normal, d, keyLight), 1.0f});
      }
      // The line nearest the ray, drawn kLineWidth pixels wide with a soft edge a sample wide.
      double lineT = kInfinity;
      float coverage = 0.0f;
      // A ray that crosses the rim's plane far from the circle passes no chord: its distance to
      // a point of the circle is at least the in-plane distance times |d . axis|.
      std::size_t first = 0;
      const double across = d.dot(m.axis);
      if (m.rim > 0.0 && std::abs(across) > 0.2) {
        const double tq = (m.rimCentre - origin).dot(m.axis) / across;
        const double radial = (origin + tq * d - m.rimCentre).norm();
        const double reach = (pixelAngle + sampleAngle) * (std::abs(tq) + m.rim + m.radius);
        if (std::abs(radial - m.rim) * std::abs(across) > reach) first = kRimSegments;
      }
      for (std::size_t i = first; i < m.lines.size(); ++i) {
        const auto& [a, b] = m.lines[i];
        const auto [t, apart] = closestApproach(origin, d, a, b);
        if (!(t > 0.0) || t >= opaque) continue;
        const double half = 0.5 * kLineWidth * pixelAngle * t;
        const float c =
            static_cast<float>(std::clamp((half - apart) / (sampleAngle * t) + 0.5, 0.0, 1.0));
        if (c > coverage) {
          coverage = c;
          lineT = t;
        }
      }
      if (coverage > 0.0f) add({lineT, rgb(kConeColour), coverage});
    }
    Eigen::Vector3f colour = baseColour(origin, d, hit, floorT, spin);
    std::sort(fragments.begin(), fragments.begin() + static_cast<std::ptrdiff_t>(count),
              [](const Fragment& a, const Fragment& b) { return a.t > b.t; });
    for (std::size_t i = 0; i < count; ++i) {
      if (fragments[i].t >= opaque) continue;
      colour = (1.0f - fragments[i].alpha) * colour + fragments[i].alpha * fragments[i].colour;
    }
    out.colour = colour;
    return out;
  }
};

// A picture's memory grows with its pixels (16 bytes each while it is traced): 16.7 million
// (4096 x 4096) keeps that near 270 MB.
constexpr std::int64_t kMaxPixels = 4096 * 4096;

void checkRequest(const RenderRequest& request) {
  if (request.width < 1 || request.height < 1 || request.width > 16384 || request.height > 16384 ||
      static_cast<std::int64_t>(request.width) * request.height > kMaxPixels)
    throw Error(
        fmt::format("render: a {}x{} picture; width and height must be 1 to 16384, and "
                    "the picture at most {} pixels",
                    request.width, request.height, kMaxPixels));
  if (request.samples < 1 || request.samples > 4)
    throw Error(fmt::format("render: {} samples a side; 1 to 4", request.samples));
  const ViewCamera& c = request.camera;
  if (!c.position.allFinite() || !c.orientation.coeffs().allFinite() ||
      c.orientation.norm() < 1e-9 || !(c.heightAngle > 0.0 && c.heightAngle < 3.1))
    throw Error(
        "render: the camera needs a finite position, a rotation and a height angle "
        "between 0 and 3.1 radians");
}

// How far a sample turns the light's disc: 16 angles in a 4 x 4 ordered-dither tile, so that
// each tile of samples looks at the light through 16 turned copies of the pattern, a fine
// regular texture rather than grain.
double spinOf(int x, int y) {
  static constexpr std::array<int, 16> kBayer = {0, 8,  2, 10, 12, 4, 14, 6,
                                                 3, 11, 1, 9,  15, 7, 13, 5};
  return kBayer[static_cast<std::size_t>((y & 3) * 4 + (x & 3))] * (2.0 * std::numbers::pi / 16.0);
}

// Row y of samples, traced in Embree packets of 8.
void traceRow(const Tracer& tracer, const Matrix3& axes, int y, int w, int h,
              const std::vector<Eigen::Vector3f>& across, std::vector<Sample>& row) {
  const RenderRequest& request = tracer.request;
  const double scale = std::tan(request.camera.heightAngle / 2.0);
  const Eigen::Matrix3f axesF = axes.cast<float>();
  const Eigen::Vector3f originF = request.camera.position.cast<float>();
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  alignas(32) RTCRayHit8 packet;
  alignas(32) int valid[8];
  const Eigen::Vector3f background = rgb(request.background);
  const bool plain = tracer.markers.empty() && !tracer.floor;
  // A packet's hits, and the links each lane has seen through (constructed once a row).
  std::array<SurfaceHit, 8> hits;
  std::array<std::array<SurfaceHit, kMaxLinkLayers>, 8> links;
  std::array<std::size_t, 8> linkCount{};
  const float cy = static_cast<float>((1.0 - 2.0 * (y + 0.5) / h) * scale);
  const Eigen::Vector3f ahead = axesF.col(1) * cy - axesF.col(2);
  for (int x0 = 0; x0 < w; x0 += 8) {
    for (int k = 0; k < 8; ++k) {
      const int x = std::min(x0 + k, w - 1);
      valid[k] = x0 + k < w ? -1 : 0;
      const Eigen::Vector3f d = (ahead + across[static_cast<std::size_t>(x)]).normalized();
      packet.ray.org_x[k] = originF.x();
      packet.ray.org_y[k] = originF.y();
      packet.ray.org_z[k] = originF.z();
      packet.ray.dir_x[k] = d.x();
      packet.ray.dir_y[k] = d.y();
      packet.ray.dir_z[k] = d.z();
      packet.ray.tnear[k] = 0.0f;
      packet.ray.tfar[k] = std::numeric_limits<float>::infinity();
      packet.ray.time[k] = 0.0f;
      packet.ray.mask[k] = ~0u;
      packet.ray.id[k] = static_cast<unsigned>(k);
      packet.ray.flags[k] = 0;
      packet.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
      packet.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
    }
    rtcIntersect8(valid, tracer.scene, &context, &packet);
    const auto takeHits = [&](const int* lanes) {
      for (int k = 0; k < 8; ++k)
        if (lanes[k])
          hits[k] = packet.hit.instID[0][k] == RTC_INVALID_GEOMETRY_ID
                        ? SurfaceHit{}
                        : tracer.surfaceHit(packet.hit.instID[0][k], packet.hit.primID[k],
                                            packet.ray.tfar[k], packet.hit.Ng_x[k],
                                            packet.hit.Ng_y[k], packet.hit.Ng_z[k]);
    };
    takeHits(valid);
    // See-through links: the lanes that met one go on past it, as a packet, until each meets
    // an opaque surface or nothing (or kMaxLinkLayers links, the last then taken as opaque).
    linkCount.fill(0);
    for (int layer = 0; layer < kMaxLinkLayers && request.hand != HandStyle::Solid; ++layer) {
      alignas(32) int on[8];
      bool any = false;
      for (int k = 0; k < 8; ++k) {
        on[k] = valid[k] && tracer.isLink(hits[k]) ? -1 : 0;
        if (!on[k]) continue;
        any = true;
        links[k][linkCount[k]++] = hits[k];
        const double t = hits[k].distance;
        packet.ray.tnear[k] = static_cast<float>(t + std::max(1e-3, 1e-5 * t));
        packet.ray.tfar[k] = std::numeric_limits<float>::infinity();
        packet.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
        packet.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
      }
      if (!any) break;
      rtcIntersect8(on, tracer.scene, &context, &packet);
      takeHits(on);
    }
    for (int k = 0; k < 8 && x0 + k < w; ++k) {
      Sample& out = row[static_cast<std::size_t>(x0 + k)];
      if (hits[k].instance < 0 && linkCount[k] == 0 && plain) {
        out = Sample{background};
        continue;
      }
      const Vector3 d(packet.ray.dir_x[k], packet.ray.dir_y[k], packet.ray.dir_z[k]);
      out = tracer.sample(request.camera.position, d,
                          std::span<const SurfaceHit>(links[k].data(), linkCount[k]), hits[k],
                          spinOf(x0 + k, y));
    }
  }
}

// Whether samples a (on a link) and b show an edge of a's link between them: b sees another
// link or none, or the same link across a crease or a fold.
bool edgeBetween(const Sample& a, const Sample& b, int steps) {
  if (b.link != a.link) return true;
  if (a.normal.dot(b.normal) < kCreaseCos) return true;
  return std::abs(a.depth - b.depth) > 0.03f * static_cast<float>(steps) * a.depth;
}

}  // namespace

Image render(const World& world, const RenderRequest& request) {
  checkRequest(request);
  const RayScene scene(world);
  Tracer tracer{request};
  tracer.scene = raycast::SceneAccess::scene(scene);
  const std::vector<Transform> poses = raycast::SceneAccess::instancePoses(scene);
  const GraspSubject subject = graspSubject(world);
  const std::optional<Colour> objectColour =
      request.separateColours && subject.hand && subject.object
          ? std::optional<Colour>(surfaceColour(world, *subject.object))
          : std::nullopt;
  for (std::size_t i = 0; i < scene.bodies().size(); ++i) {
    const BodyRef& body = scene.bodies()[i];
    const BodyModel& model = bodyModel(world, body);
    InstanceLook look{body.isLink(),
                      false,
                      model.mesh ? &model.mesh->triangleColours : nullptr,
                      materialColour(model.material),
                      std::nullopt,
                      poses[i].linear().cast<float>()};
    look.receivesShadow =
        request.floor && !request.focus.empty() &&
        std::find(request.focus.begin(), request.focus.end(), body) == request.focus.end();
    if (objectColour && body.isLink() && body.index == *subject.hand) {
      const Colour own = surfaceColour(world, body);
      if (colourDistance(own, *objectColour) < kAlikeColourDistance)
        look.separated = separatedColour(own, *objectColour);
    }
    tracer.instances.push_back(look);
  }
  const Matrix3 axes = request.camera.orientation.normalized().toRotationMatrix();
  tracer.keyLight = (axes * Vector3(-0.4, 0.6, 1.0)).normalized();
  if (!request.contacts.empty()) {
    // Sized by what the contacts lie on (body2: the object of a grasp), not by the scene,
    // which may hold a floor or a table many times the object's size.
    const BodyRef object = request.contacts.front().body2;
    const double radius = isValid(world, object)
                              ? boundingSphere(world, std::vector<BodyRef>{object}).radius
                              : boundingSphere(world, scene.bodies()).radius;
    tracer.markers = contactMarkers(request, radius);
  }
  if (request.floor) {
    Floor f;
    f.casters = boundingSphere(world, request.focus);
    double lowest = kInfinity;
    const std::vector<BodyRef> all =
        request.focus.empty() ? worldBodies(world) : std::vector<BodyRef>{};
    for (const BodyRef& body : request.focus.empty() ? std::span<const BodyRef>(all)
                                                     : std::span<const BodyRef>(request.focus)) {
      const auto& mesh = bodyModel(world, body).mesh;
      if (!mesh) continue;
      const Transform pose = bodyPose(world, body);
      for (const Vector3& v : mesh->vertices) lowest = std::min(lowest, (pose * v).z());
      f.pieces.push_back(boundingSphere(world, std::span<const BodyRef>(&body, 1)));
    }
    if (lowest < kInfinity && std::isfinite(f.casters.radius)) {
      f.height = lowest - 0.005 * f.casters.radius;
      f.centre = f.casters.centre;
      f.inner = 2.0 * f.casters.radius;
      f.outer = 5.0 * f.casters.radius;
      // From above, tilted towards the camera's side (behind it and to its left, where the key
      // light is), so a shadow falls behind what casts it and shows.
      Vector3 side = axes.col(2) - 0.6 * axes.col(0);
      side.z() = 0.0;
      f.light = side.norm() > 1e-6 ? (Vector3::UnitZ() + 0.35 * side.normalized()).normalized()
                                   : Vector3::UnitZ();
      f.lightU = f.light.unitOrthogonal();
      f.lightV = f.light.cross(f.lightU);
      f.rays = request.samples > 1 ? 4 : kShadowRays;
      for (int i = 0; i < f.rays; ++i) {
        const double r = kLightRadius * std::sqrt((i + 0.5) / f.rays);
        const double a = i * 2.399963229728653;  // the golden angle
        f.disc[static_cast<std::size_t>(i)] = Eigen::Vector2d(r * std::cos(a), r * std::sin(a));
      }
      tracer.floor = f;
    }
  }

  const int n = request.samples;
  const int w = request.width * n;
  const int h = request.height * n;
  const double scale = std::tan(request.camera.heightAngle / 2.0);
  const double aspect = static_cast<double>(request.width) / request.height;
  tracer.pixelAngle = 2.0 * scale / request.height;
  tracer.sampleAngle = tracer.pixelAngle / n;
  // A marker's bound grows by its lines' width (and soft edge) at its far side.
  for (ContactMarker& m : tracer.markers)
    m.cullRadius =
        m.boundRadius + 1.5 * tracer.pixelAngle *
                            ((m.boundCentre - request.camera.position).norm() + m.boundRadius);
  // Each column's offset along the camera's x axis, the same for every row.
  std::vector<Eigen::Vector3f> across(static_cast<std::size_t>(w));
  const Eigen::Vector3f right = axes.col(0).cast<float>();
  for (int x = 0; x < w; ++x)
    across[static_cast<std::size_t>(x)] =
        right * static_cast<float>((2.0 * (x + 0.5) / w - 1.0) * scale * aspect);

  // Outline hands look `reach` samples (~kLineWidth pixels) each way for a link's edges: rows
  // are kept in a ring of 2 reach + 1 and finished once the rows below them are traced.
  const int reach = request.hand == HandStyle::Outline ? std::max(1, (3 * n) / 2) : 0;
  const int ringSize = 2 * reach + 1;
  std::vector<std::vector<Sample>> ring(static_cast<std::size_t>(ringSize),
                                        std::vector<Sample>(static_cast<std::size_t>(w)));
  const auto rowOf = [&](int y) -> const std::vector<Sample>& {
    return ring[static_cast<std::size_t>(y % ringSize)];
  };
  std::vector<Eigen::Vector3f> sum(static_cast<std::size_t>(request.width) * request.height,
                                   Eigen::Vector3f::Zero());
  for (int y = 0; y < h + reach; ++y) {
    if (y < h)
      traceRow(tracer, axes, y, w, h, across, ring[static_cast<std::size_t>(y % ringSize)]);
    const int done = y - reach;
    if (done < 0) continue;
    const std::vector<Sample>& row = rowOf(done);
    for (int x = 0; x < w; ++x) {
      const Sample& s = row[static_cast<std::size_t>(x)];
      Eigen::Vector3f colour = s.colour;
      if (reach > 0 && s.link >= 0) {
        bool edge = false;
        for (int j = 1; j <= reach && !edge; ++j) {
          if (x - j >= 0) edge = edgeBetween(s, row[static_cast<std::size_t>(x - j)], j);
          if (!edge && x + j < w) edge = edgeBetween(s, row[static_cast<std::size_t>(x + j)], j);
          if (!edge && done - j >= 0)
            edge = edgeBetween(s, rowOf(done - j)[static_cast<std::size_t>(x)], j);
          if (!edge && done + j < h)
            edge = edgeBetween(s, rowOf(done + j)[static_cast<std::size_t>(x)], j);
        }
        if (edge) colour = (1.0f - kEdgeOpacity) * colour + kEdgeOpacity * kEdgeColour;
      }
      sum[static_cast<std::size_t>(done / n) * request.width + static_cast<std::size_t>(x / n)] +=
          colour;
    }
  }
  Image image(request.width, request.height);
  const float weight = 255.0f / static_cast<float>(n * n);
  for (std::size_t i = 0; i < sum.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      const float v = std::clamp(sum[i][k] * weight, 0.0f, 255.0f);
      image.rgb[i * 3 + static_cast<std::size_t>(k)] = static_cast<std::uint8_t>(v + 0.5f);
    }
  }
  return image;
}

}  // namespace graspkit
