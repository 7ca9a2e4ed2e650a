#pragma once
/// Planar (2D) vector helpers shared by the pattern code of every layer: the cross
/// product, signed triangle areas and the angle between two directions.
#include <cmath>
#include <numbers>

#include "tightfit/common/types.hpp"

namespace tightfit {

/// z of the cross product a × b: twice the signed area of the triangle (0, a, b).
inline double cross2(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

/// Signed area of the triangle (a, b, c) (units²), positive when counter-clockwise.
inline double signed_area(const Vec2& a, const Vec2& b, const Vec2& c) {
  return 0.5 * cross2(b - a, c - a);
}

/// Angle between the directions a and b, in degrees in [0, 180] (0 when either is zero).
inline double angle_between_deg(const Vec2& a, const Vec2& b) {
  return std::atan2(std::abs(cross2(a, b)), a.dot(b)) * 180.0 / std::numbers::pi;
}

}  // namespace tightfit
