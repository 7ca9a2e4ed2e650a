#pragma once
/// Analytic volumes of the generated primitive bodies (body/generators.hpp), the
/// references the body and generator tests compare the meshes with.
#include <numbers>

#include "tightfit/body/generators.hpp"

namespace tightfit::test {

/// Volume (m³) of the capped cylinder: the tube plus a ball for round caps.
inline double cylinder_volume(const CylinderParams& p) {
  const double r2 = p.radius * p.radius;
  return std::numbers::pi * r2 * p.length +
         (p.caps == CapStyle::kRound ? 4.0 / 3.0 * std::numbers::pi * r2 * p.radius : 0.0);
}

/// Volume (m³) of the sphere.
inline double sphere_volume(const SphereParams& p) {
  return 4.0 / 3.0 * std::numbers::pi * p.radius * p.radius * p.radius;
}

}  // namespace tightfit::test
