#include "graspkit/grasp/friction_cone.hpp"

#include <cmath>

#include <fmt/format.h>

#include "graspkit/base/error.hpp"

namespace graspkit {

std::vector<FrictionLatitude> frictionLatitudes(ContactModel model) {
  switch (model) {
    case ContactModel::Frictionless:
      return {};
    case ContactModel::PointWithFriction:
      return {{0.0, 8}};
    case ContactModel::SoftFinger:
      return {{M_PI_2, 1}, {M_PI_4, 5}, {0.0, 8}, {-M_PI_4, 5}, {-M_PI_2, 1}};
  }
  return {};
}

std::vector<Vector6> frictionEdges(ContactModel model, double torsion) {
  if (model == ContactModel::Frictionless) {
    Vector6 normal_only = Vector6::Zero();
    normal_only[2] = 1.0;
    return {normal_only};
  }
  const bool soft = model == ContactModel::SoftFinger;
  if (soft && !(std::isfinite(torsion) && torsion >= 0.0))
    throw Error(
        fmt::format("soft-finger torsion (e_tau) must be finite and >= 0 mm, got {}", torsion));
  // Point contacts sample the equator only, where the torsion semi-axis plays no part.
  const double e_tau = soft ? torsion : 1.0;

  std::vector<Vector6> edges;
  for (const FrictionLatitude& latitude : frictionLatitudes(model)) {
    const double cos_phi = std::cos(latitude.phi);
    const double sin_phi = std::sin(latitude.phi);
    for (int j = 0; j < latitude.count; ++j) {
      const double theta = j * 2.0 * M_PI / latitude.count;
      const double cx = std::cos(theta) * cos_phi;
      const double cy = std::sin(theta) * cos_phi;
      // Scale the direction (cx, cy, sin phi) onto the ellipsoid with semi-axes (1, 1, e_tau).
      // A soft finger without torsion (e_tau = 0) has the limit: no friction off the equator.
      Vector6 edge = Vector6::Zero();
      edge[2] = 1.0;
      if (sin_phi == 0.0 || e_tau > 0.0) {
        const double tz = sin_phi == 0.0 ? 0.0 : sin_phi / e_tau;
        const double scale = 1.0 / std::sqrt(cx * cx + cy * cy + tz * tz);
        edge[0] = cx * scale;
        edge[1] = cy * scale;
        edge[5] = sin_phi * scale;
      }
      edges.push_back(edge);
    }
  }
  return edges;
}

std::vector<Vector6> contactWrenches(const Contact& c, const Vector3& cogWorld, double maxRadius) {
  if (!(maxRadius > 0.0) || !std::isfinite(maxRadius))
    throw Error(fmt::format("object maxRadius must be positive and finite, got {} mm", maxRadius));
  const bool frictionless = c.model == ContactModel::Frictionless || c.mu == 0.0;
  const std::vector<Vector6> edges =
      frictionEdges(frictionless ? ContactModel::Frictionless : c.model, c.torsion);

  const Vector3 n = c.normal;
  const Vector3 tx = c.frame.col(0);
  const Vector3 ty = c.frame.col(1);
  const Vector3 r = c.position1 - cogWorld;
  std::vector<Vector6> wrenches;
  wrenches.reserve(edges.size());
  for (const Vector6& e : edges) {
    const Vector3 f = n * e[2] + c.mu * (e[0] * tx + e[1] * ty);
    const Vector3 tau = (r.cross(f) + c.mu * e[5] * n) / maxRadius;
    Vector6 w;
    w << f, tau;
    wrenches.push_back(w);
  }
  return wrenches;
}

std::vector<std::vector<Vector6>> graspWrenches(const std::vector<Contact>& objectSideContacts,
                                                const Vector3& cogWorld, double maxRadius) {
  std::vector<std::vector<Vector6>> sets;
  sets.reserve(objectSideContacts.size());
  for (const Contact& c : objectSideContacts)
    sets.push_back(contactWrenches(c, cogWorld, maxRadius));
  return sets;
}

}  // namespace graspkit
