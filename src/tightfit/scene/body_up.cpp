#include "tightfit/scene/body_up.hpp"

#include <cmath>

namespace tightfit {

Vec3 body_up_direction(const BodySpec& spec) {
  if (spec.source == BodySource::kCylinder) {
    const double length = spec.cylinder.axis.norm();
    if (length > 0.0 && std::isfinite(length)) return spec.cylinder.axis / length;
  }
  return Vec3::UnitY();
}

}  // namespace tightfit
