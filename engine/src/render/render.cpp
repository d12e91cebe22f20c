// Ray casting a world: one ray per pixel (or per sample) through a RayScene, traced in batches
// that Embree takes as packets; each hit is shaded as it comes back. Contact markers are shapes
// of their own (a sphere and a cone per contact), intersected in closed form after the scene.
#include "graspkit/render.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "graspkit/body_ref.hpp"
#include "graspkit/error.hpp"
#include "graspkit/ray_scene.hpp"
#include "graspkit/world.hpp"

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

std::vector<BodyRef> handAndObject(const World& world) {
  std::optional<int> hand = world.firstHand();
  if (!hand && world.robotCount() > 0) hand = 0;
  std::optional<BodyRef> object;
  for (int i = 0; i < static_cast<int>(world.bodies().size()); ++i) {
    if (world.bodies()[static_cast<std::size_t>(i)].isDynamic()) {
      object = BodyRef::body(i);
      break;
    }
  }
  std::vector<BodyRef> focus;
  for (const BodyRef& body : worldBodies(world)) {
    const bool ofHand = body.kind == BodyRef::Kind::Link && hand && body.index == *hand;
    if (ofHand || (object && body == *object)) focus.push_back(body);
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

Colour materialColour(Material material) {
  switch (material) {
    case Material::Frictionless: return {0.85f, 0.85f, 0.9f};
    case Material::Glass: return {0.6f, 0.8f, 0.9f};
    case Material::Metal: return {0.62f, 0.64f, 0.68f};
    case Material::Plastic: return {0.9f, 0.7f, 0.35f};
    case Material::Wood: return {0.7f, 0.5f, 0.3f};
    case Material::Rubber: return {0.25f, 0.25f, 0.28f};
    case Material::Stone: return {0.55f, 0.55f, 0.5f};
  }
  return {};
}

namespace {

// A body's colours, looked up by the BodyRef a hit carries.
struct BodyColours {
  BodyRef body;
  const std::vector<Colour>* triangles = nullptr;  // null or empty: the material's colour
  Colour material;
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

std::vector<ContactMarker> contactMarkers(const RenderRequest& request, double sceneRadius) {
  std::vector<ContactMarker> markers;
  const double radius = request.markerRadius > 0 ? request.markerRadius : 0.03 * sceneRadius;
  const double length = request.coneLength > 0 ? request.coneLength : 0.15 * sceneRadius;
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
  std::vector<BodyColours> colours;  // sorted by body
  std::vector<ContactMarker> markers;
  Vector3 keyLight;

  Colour surfaceColour(const RayHit& hit) const {
    const auto it = std::lower_bound(
        colours.begin(), colours.end(), hit.body,
        [](const BodyColours& c, const BodyRef& body) { return c.body < body; });
    if (it == colours.end() || !(it->body == hit.body)) return Colour{};
    if (it->triangles && static_cast<std::size_t>(hit.triangle) < it->triangles->size())
      return (*it->triangles)[static_cast<std::size_t>(hit.triangle)];
    return it->material;
  }

  // Markers show through the hand's links (a contact lies under a fingertip), not through
  // other bodies: there they are drawn over the link, a little faded.
  Eigen::Vector3f colourOf(const Ray& ray, const RayHit* hit) const {
    const Vector3 d = ray.direction;  // unit: made so by the caller
    Eigen::Vector3f colour(request.background.r, request.background.g, request.background.b);
    const double surface = hit ? hit->distance : kInfinity;
    if (hit) colour = shade(surfaceColour(*hit), hit->normal, d, keyLight);
    if (markers.empty()) return colour;
    const double occluder = hit && hit->body.isLink() ? kInfinity : surface;
    double sphereT = kInfinity, coneT = kInfinity;
    Vector3 sphereNormal = Vector3::UnitZ(), coneNormal = Vector3::UnitZ();
    for (const ContactMarker& m : markers) {
      if (sphereEntry(ray.origin, d, m.boundCentre, m.boundRadius) >= occluder) continue;
      const double ts = sphereEntry(ray.origin, d, m.point, m.radius);
      if (ts < sphereT) {
        sphereT = ts;
        sphereNormal = (ray.origin + ts * d - m.point).normalized();
      }
      const MarkerHit cone = coneEntry(ray.origin, d, m);
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

void checkRequest(const RenderRequest& request) {
  if (request.width < 1 || request.height < 1 || request.width > 16384 || request.height > 16384)
    throw Error(fmt::format("render: a {}x{} picture; width and height must be 1 to 16384",
                            request.width, request.height));
  if (request.samples < 1 || request.samples > 4)
    throw Error(fmt::format("render: {} samples a side; 1 to 4", request.samples));
  const ViewCamera& c = request.camera;
  if (!c.position.allFinite() || !c.orientation.coeffs().allFinite() ||
      c.orientation.norm() < 1e-9 || !(c.heightAngle > 0.0 && c.heightAngle < 3.1))
    throw Error("render: the camera needs a finite position, a rotation and a height angle "
                "between 0 and 3.1 radians");
}

}  // namespace

Image render(const World& world, const RenderRequest& request) {
  checkRequest(request);
  const RayScene scene(world);
  Tracer tracer{request, {}, {}, {}};
  for (const BodyRef& body : scene.bodies()) {
    const BodyModel& model = bodyModel(world, body);
    tracer.colours.push_back(
        {body, model.mesh ? &model.mesh->triangleColours : nullptr, materialColour(model.material)});
  }
  std::sort(tracer.colours.begin(), tracer.colours.end(),
            [](const BodyColours& a, const BodyColours& b) { return a.body < b.body; });
  const Matrix3 axes = request.camera.orientation.normalized().toRotationMatrix();
  tracer.keyLight = (axes * Vector3(-0.4, 0.6, 1.0)).normalized();
  if (!request.contacts.empty())
    tracer.markers = contactMarkers(request, boundingSphere(world, scene.bodies()).radius);

  const int n = request.samples;
  const double scale = std::tan(request.camera.heightAngle / 2.0);
  const double aspect = static_cast<double>(request.width) / request.height;
  const int w = request.width * n;
  const int h = request.height * n;
  std::vector<Eigen::Vector3f> sum(static_cast<std::size_t>(request.width) * request.height,
                                   Eigen::Vector3f::Zero());
  // Rows of samples are traced a band at a time: enough rays for Embree's packets, few enough
  // to stay in cache.
  constexpr int kBandRays = 8192;
  const int bandRows = std::max(1, kBandRays / w);
  std::vector<Ray> rays;
  for (int top = 0; top < h; top += bandRows) {
    const int bottom = std::min(h, top + bandRows);
    rays.clear();
    for (int y = top; y < bottom; ++y) {
      const double cy = (1.0 - 2.0 * (y + 0.5) / h) * scale;
      for (int x = 0; x < w; ++x) {
        const double cx = (2.0 * (x + 0.5) / w - 1.0) * scale * aspect;
        Ray ray;
        ray.origin = request.camera.position;
        ray.direction = (axes * Vector3(cx, cy, -1.0)).normalized();
        rays.push_back(ray);
      }
    }
    struct Band {
      const Tracer* tracer;
      const std::vector<Ray>* rays;
      std::vector<Eigen::Vector3f>* sum;
      int top, w, n, width;
    } band{&tracer, &rays, &sum, top, w, n, request.width};
    scene.intersect(
        rays,
        [](void* context, std::size_t i, const RayHit* hit) {
          const auto& b = *static_cast<const Band*>(context);
          const int x = static_cast<int>(i) % b.w;
          const int y = b.top + static_cast<int>(i) / b.w;
          (*b.sum)[static_cast<std::size_t>(y / b.n) * b.width + x / b.n] +=
              b.tracer->colourOf((*b.rays)[i], hit);
        },
        &band);
  }
  Image image(request.width, request.height);
  const float weight = 1.0f / static_cast<float>(n * n);
  for (std::size_t i = 0; i < sum.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      const float v = std::clamp(sum[i][k] * weight, 0.0f, 1.0f);
      image.rgb[i * 3 + static_cast<std::size_t>(k)] = static_cast<std::uint8_t>(std::lround(v * 255.0f));
    }
  }
  return image;
}

}  // namespace graspkit
