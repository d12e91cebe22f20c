#include "io/common/link_mass.hpp"

#include "graspkit/geometry/mass_properties.hpp"

namespace graspkit::io {

void setLinkMassProperties(BodyModel& body, double mass, const Vector3& moment,
                           const Matrix3& inertia_about_origin) {
  const MassProperties geometry = computeMassProperties(*body.mesh);
  if (mass > 0.0) {
    body.mass = mass;
    body.cog = moment / mass;
    const Vector3 c = body.cog;
    Matrix3 about_cog =
        inertia_about_origin - mass * (c.squaredNorm() * Matrix3::Identity() - c * c.transpose());
    if (about_cog.norm() < 1e-12 * mass)
      about_cog =
          geometry.valid ? Matrix3(geometry.inertia * mass) : Matrix3(mass * Matrix3::Identity());
    body.inertia = about_cog / mass;
    body.massFromFile = body.cogFromFile = body.inertiaFromFile = true;
  } else {
    body.mass = kDefaultMass;
    body.cog = geometry.valid ? geometry.centroid : surfaceCentroid(*body.mesh);
    body.inertia = geometry.valid ? geometry.inertia : Matrix3::Identity();
    body.inertiaFallback = !geometry.valid;
  }
  body.maxRadius = maxRadius(*body.mesh, body.cog);
}

}  // namespace graspkit::io
