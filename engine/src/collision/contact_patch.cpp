#include "graspkit/collision/contact_patch.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace graspkit {
namespace {

// GraspIt!'s FIT_TINY: coefficients and curvatures below it count as zero (1/mm).
constexpr double kFitTiny = 1e-6;

double radiusOf(double curvature) {
  return std::abs(curvature) > kFitTiny ? 1.0 / curvature : -1.0;
}

// Curvature 1/r of a principal radius; flat and concave directions count as flat.
double curvatureOf(double radius) {
  return radius < 0.0 ? 0.0 : 1.0 / radius;
}

}  // namespace

Paraboloid fitParaboloid(std::span<const Vector3> points) {
  // Normal equations of z = a x^2 + b y^2 + c xy: rows x^2, y^2, xy against the same columns.
  Matrix3 normal = Matrix3::Zero();
  Vector3 rhs = Vector3::Zero();
  for (const Vector3& p : points) {
    const Vector3 basis(p.x() * p.x(), p.y() * p.y(), p.x() * p.y());
    normal += basis * basis.transpose();
    rhs += basis * p.z();
  }
  // Points on a line (or fewer than three) leave the fit undetermined: call it flat.
  const Eigen::FullPivLU<Matrix3> lu(normal);
  if (!normal.allFinite() || !rhs.allFinite() || lu.rank() < 3) return {};
  Vector3 x = lu.solve(rhs);
  for (int i = 0; i < 3; ++i)
    if (!(std::abs(x[i]) >= kFitTiny)) x[i] = 0.0;
  return {x[0], x[1], x[2]};
}

PrincipalRadii principalRadii(const Paraboloid& s) {
  PrincipalRadii out;
  if (std::abs(s.c) <= kFitTiny) {
    out.r1 = std::abs(s.a) > kFitTiny ? 1.0 / (2.0 * s.a) : -1.0;
    out.r2 = std::abs(s.b) > kFitTiny ? 1.0 / (2.0 * s.b) : -1.0;
    return out;
  }
  // The tangent at angle t from x sees z = k(t) s^2 / 2 with k(t) = 2 (a cos^2 t + b sin^2 t +
  // c sin t cos t); k is extreme where tan 2t = c / (a - b). (GraspIt! turns the other way and
  // then reports the mirrored direction; its radii are the same.)
  const double t = s.a != s.b ? 0.5 * std::atan(s.c / (s.a - s.b)) : 0.25 * std::numbers::pi;
  const double cos_t = std::cos(t), sin_t = std::sin(t);
  out.r1 = radiusOf(2.0 * (s.a * cos_t * cos_t + s.b * sin_t * sin_t + s.c * sin_t * cos_t));
  out.r2 = radiusOf(2.0 * (s.a * sin_t * sin_t + s.b * cos_t * cos_t - s.c * sin_t * cos_t));
  out.direction = Vector3(cos_t, sin_t, 0.0);
  return out;
}

RelativeRadii relativeRadii(const PrincipalRadii& s1, const PrincipalRadii& s2, double angle) {
  // Johnson, Contact Mechanics, 4.2: A + B and A - B from the four principal curvatures.
  const double w = curvatureOf(s1.r1), x = curvatureOf(s1.r2);
  const double y = curvatureOf(s2.r1), z = curvatureOf(s2.r2);
  const double sum = 0.5 * (w + x + y + z);
  const double squared =
      (w - x) * (w - x) + (y - z) * (y - z) + 2.0 * std::cos(2.0 * angle) * (w - x) * (y - z);
  // Rounding can make A - B exceed A + B by an ulp when one pair is flat; it cannot otherwise.
  const double difference = std::min(sum, 0.5 * std::sqrt(std::max(0.0, squared)));
  RelativeRadii out;
  if (sum + difference != 0.0) out.r1 = 1.0 / (sum + difference);
  if (sum != difference) out.r2 = 1.0 / (sum - difference);
  return out;
}

ContactEllipse mattressEllipse(RelativeRadii radii, double youngs, double normal_force) {
  if (!(youngs > 0.0) || !(normal_force > 0.0)) return {};
  if (!(radii.r1 > 0.0)) radii.r1 = kFlatRelativeRadius;
  if (!(radii.r2 > 0.0)) radii.r2 = kFlatRelativeRadius;
  // In SI units: radii and depth in m, the modulus in Pa, the force in N.
  const double r1 = radii.r1 * 1e-3, r2 = radii.r2 * 1e-3, depth = kMattressDepth * 1e-3;
  const double sink =
      std::sqrt(normal_force * depth / (youngs * std::numbers::pi * std::sqrt(r1 * r2)));
  const double major = std::sqrt(2.0 * sink * r1);
  const double minor = std::sqrt(2.0 * sink * r2);
  ContactEllipse out;
  out.semiMajor = major * 1e3;
  out.semiMinor = minor * 1e3;
  out.torsion = 8.0 * std::sqrt(major * minor) / 15.0 * 1e3;
  return out;
}

double patchNeighbourhoodRadius(double youngs) {
  // GraspIt!'s own exponent (0.333, not 1/3) and fudge factor 0.4; its clamp to 5 mm never
  // applies (its condition is rad <= 3 && rad >= 10), so none here either.
  return std::pow(1.0 / youngs, 0.333) * 1000.0 * 0.4;
}

}  // namespace graspkit
