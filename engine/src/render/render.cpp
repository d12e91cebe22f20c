// Ray casting a world: one ray per pixel (or per sample), built in float straight into Embree
// packets of 8 and traced through a RayScene's scene (raycast::SceneAccess: a picture needs
// only a hit's body, triangle and facing, not RayScene's checked double-precision hits); each
// hit is shaded as it comes back. Contact markers are shapes of their own (a sphere and a cone
// per contact), intersected in closed form after the scene.
#include "graspkit/render/render.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

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

namespace {

// What a hit on one instance of the scene needs: its colours and its rotation (Embree reports
// normals in the instance's own frame).
struct InstanceLook {
  bool isLink = false;
  const std::vector<Colour>* triangles = nullptr;  // null or empty: the material's colour
  Colour material;
  Eigen::Matrix3f rotation;
};

// A hit as the tracer shades it.
struct SurfaceHit {
  double distance = kInfinity;  // mm; infinity for a miss
  bool onLink = false;
  Colour colour;
  Vector3 normal = Vector3::UnitZ();  // world, unit
};

struct MarkerHit {
  double t = kInfinity;
  Vector3 normal = Vector3::UnitZ();
};

// A contact's marker sphere and friction cone.
struct ContactMarker {
  Vector3 point;
  Vector3 axis;  // unit, the cone opens along it
  double cosAngle, tanAngle;
  double radius, length;
  Vector3 boundCentre;  // a sphere around both shapes, for a cheap miss
  double boundRadius;
};

std::vector<ContactMarker> contactMarkers(const RenderRequest& request, double objectRadius) {
  std::vector<ContactMarker> markers;
  const double radius = request.markerRadius > 0 ? request.markerRadius : 0.05 * objectRadius;
  const double length = request.coneLength > 0 ? request.coneLength : 0.25 * objectRadius;
  for (const Contact& c : request.contacts) {
    if (!c.position2.allFinite() || !c.normal.allFinite() || c.normal.norm() == 0.0) continue;
    ContactMarker m;
    m.point = c.position2;
    m.axis = c.normal.normalized();
    const double angle = std::atan(std::max(c.mu, 0.0));
    m.cosAngle = std::cos(angle);
    m.tanAngle = std::tan(angle);
    m.radius = radius;
    m.length = length;
    m.boundCentre = m.point + m.axis * (length / 2.0);
    m.boundRadius = std::hypot(length / 2.0, length * m.tanAngle) + radius;
    markers.push_back(m);
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

// The nearest point of the cone's surface or its cap along the ray: the roots of
// (q . axis)^2 = cos^2 |q|^2 with q = origin + t direction - apex and 0 <= q . axis <= length.
MarkerHit coneEntry(const Vector3& origin, const Vector3& direction, const ContactMarker& m) {
  MarkerHit hit;
  const Vector3 co = origin - m.point;
  const double cos2 = m.cosAngle * m.cosAngle;
  const double du = direction.dot(m.axis), cu = co.dot(m.axis);
  const double a = du * du - cos2;
  const double b = 2.0 * (du * cu - cos2 * direction.dot(co));
  const double c = cu * cu - cos2 * co.squaredNorm();
  const auto consider = [&](double t) {
    if (!(t > 1e-9) || t >= hit.t) return;
    const Vector3 q = co + t * direction;
    const double h = q.dot(m.axis);
    if (h < 0.0 || h > m.length) return;
    hit.t = t;
    hit.normal = (q - m.axis * (q.norm() / m.cosAngle)).normalized();
  };
  if (std::abs(a) > 1e-12) {
    const double disc = b * b - 4.0 * a * c;
    if (disc >= 0.0) {
      const double root = std::sqrt(disc);
      consider((-b - root) / (2.0 * a));
      consider((-b + root) / (2.0 * a));
    }
  }
  if (std::abs(du) > 1e-12) {  // the cap, a disc at h = length
    const double t = (m.length - cu) / du;
    const Vector3 q = co + t * direction;
    if (t > 1e-9 && t < hit.t && (q - m.axis * m.length).norm() <= m.length * m.tanAngle) {
      hit.t = t;
      hit.normal = m.axis;
    }
  }
  return hit;
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

const Colour kMarkerColour{0.85f, 0.1f, 0.1f};
const Colour kConeColour{1.0f, 0.35f, 0.2f};
constexpr float kConeOpacity = 0.45f;
constexpr float kBehindLinkFade = 0.8f;

struct Tracer {
  const RenderRequest& request;
  std::vector<InstanceLook> instances;  // by Embree instance id
  std::vector<ContactMarker> markers;
  Vector3 keyLight;

  SurfaceHit surfaceHit(unsigned instance, unsigned triangle, float t, float nx, float ny,
                        float nz) const {
    const InstanceLook& look = instances[instance];
    SurfaceHit hit;
    hit.distance = t;
    hit.onLink = look.isLink;
    hit.colour = look.triangles && triangle < look.triangles->size() ? (*look.triangles)[triangle]
                                                                     : look.material;
    const Eigen::Vector3f n = look.rotation * Eigen::Vector3f(nx, ny, nz);
    const float length = n.norm();
    hit.normal = length > 0.0f ? Vector3((n / length).cast<double>()) : Vector3::UnitZ();
    return hit;
  }

  // Markers show through the hand's links (a contact lies under a fingertip), not through
  // other bodies: there they are drawn over the link, a little faded.
  Eigen::Vector3f colourOf(const Vector3& origin, const Vector3& d, const SurfaceHit& hit) const {
    Eigen::Vector3f colour(request.background.r, request.background.g, request.background.b);
    const double surface = hit.distance;
    if (surface < kInfinity) colour = shade(hit.colour, hit.normal, d, keyLight);
    if (markers.empty()) return colour;
    const double occluder = hit.onLink ? kInfinity : surface;
    double sphereT = kInfinity, coneT = kInfinity;
    Vector3 sphereNormal = Vector3::UnitZ(), coneNormal = Vector3::UnitZ();
    for (const ContactMarker& m : markers) {
      if (sphereEntry(origin, d, m.boundCentre, m.boundRadius) >= occluder) continue;
      const double ts = sphereEntry(origin, d, m.point, m.radius);
      if (ts < sphereT) {
        sphereT = ts;
        sphereNormal = (origin + ts * d - m.point).normalized();
      }
      const MarkerHit cone = coneEntry(origin, d, m);
      if (cone.t < coneT) {
        coneT = cone.t;
        coneNormal = cone.normal;
      }
    }
    const auto blend = [&](double t, const Colour& c, const Vector3& normal, float opacity) {
      if (t >= occluder) return;
      const float alpha = t < surface ? opacity : opacity * kBehindLinkFade;
      colour = (1.0f - alpha) * colour + alpha * shade(c, normal, d, keyLight);
    };
    if (sphereT < coneT) {
      blend(coneT, kConeColour, coneNormal, kConeOpacity);
      blend(sphereT, kMarkerColour, sphereNormal, 1.0f);
    } else {
      blend(sphereT, kMarkerColour, sphereNormal, 1.0f);
      blend(coneT, kConeColour, coneNormal, kConeOpacity);
    }
    return colour;
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

}  // namespace

namespace {

// Rows top..bottom of samples, traced in Embree packets of 8 along each row.
void traceBand(RTCScene scene, const Tracer& tracer, const Matrix3& axes, int top, int bottom,
               int w, int h, std::vector<Eigen::Vector3f>& sum) {
  const RenderRequest& request = tracer.request;
  const int n = request.samples;
  const double scale = std::tan(request.camera.heightAngle / 2.0);
  const double aspect = static_cast<double>(request.width) / request.height;
  const Eigen::Matrix3f axesF = axes.cast<float>();
  const Eigen::Vector3f originF = request.camera.position.cast<float>();
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  alignas(32) RTCRayHit8 packet;
  alignas(32) int valid[8];
  // Each column's offset along the camera's x axis, the same for every row.
  std::vector<Eigen::Vector3f> across(static_cast<std::size_t>(w));
  for (int x = 0; x < w; ++x)
    across[static_cast<std::size_t>(x)] =
        axesF.col(0) * static_cast<float>((2.0 * (x + 0.5) / w - 1.0) * scale * aspect);
  const Eigen::Vector3f background(request.background.r, request.background.g,
                                   request.background.b);
  for (int y = top; y < bottom; ++y) {
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
      rtcIntersect8(valid, scene, &context, &packet);
      for (int k = 0; k < 8 && x0 + k < w; ++k) {
        const std::size_t pixel = static_cast<std::size_t>(y / n) * request.width +
                                  static_cast<std::size_t>((x0 + k) / n);
        const bool missed = packet.hit.instID[0][k] == RTC_INVALID_GEOMETRY_ID;
        if (missed && tracer.markers.empty()) {
          sum[pixel] += background;
          continue;
        }
        SurfaceHit hit;
        if (!missed)
          hit = tracer.surfaceHit(packet.hit.instID[0][k], packet.hit.primID[k], packet.ray.tfar[k],
                                  packet.hit.Ng_x[k], packet.hit.Ng_y[k], packet.hit.Ng_z[k]);
        const Vector3 d(packet.ray.dir_x[k], packet.ray.dir_y[k], packet.ray.dir_z[k]);
        sum[pixel] += tracer.colourOf(request.camera.position, d, hit);
      }
    }
  }
}

}  // namespace

Image render(const World& world, const RenderRequest& request) {
  checkRequest(request);
  const RayScene scene(world);
  Tracer tracer{request, {}, {}, {}};
  const std::vector<Transform> poses = raycast::SceneAccess::instancePoses(scene);
  for (std::size_t i = 0; i < scene.bodies().size(); ++i) {
    const BodyRef& body = scene.bodies()[i];
    const BodyModel& model = bodyModel(world, body);
    tracer.instances.push_back({body.isLink(), model.mesh ? &model.mesh->triangleColours : nullptr,
                                materialColour(model.material), poses[i].linear().cast<float>()});
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

  const int n = request.samples;
  const int w = request.width * n;
  const int h = request.height * n;
  std::vector<Eigen::Vector3f> sum(static_cast<std::size_t>(request.width) * request.height,
                                   Eigen::Vector3f::Zero());
  traceBand(raycast::SceneAccess::scene(scene), tracer, axes, 0, h, w, h, sum);
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
