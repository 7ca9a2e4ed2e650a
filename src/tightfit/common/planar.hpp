#pragma once
/// Planar (2D) vector helpers shared by the pattern code of every layer: the cross
/// product, signed triangle and polygon areas, the angle between two directions and the
/// point-in-polygon test.
#include <cmath>
#include <cstddef>
#include <numbers>
#include <vector>

#include "tightfit/common/types.hpp"

namespace tightfit {

/// z of the cross product a × b: twice the signed area of the triangle (0, a, b).
inline double cross2(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

/// Signed area of the triangle (a, b, c) (units²), positive when counter-clockwise.
inline double signed_area(const Vec2& a, const Vec2& b, const Vec2& c) {
  return 0.5 * cross2(b - a, c - a);
}

/// Signed area of the closed polygon whose k-th corner is `corner(k)`, k = 0 … n−1
/// (units², the shoelace formula), positive when counter-clockwise.
template <class Corner>
double polygon_signed_area(std::size_t n, const Corner& corner) {
  double twice = 0.0;
  for (std::size_t i = 0; i < n; ++i) twice += cross2(corner(i), corner((i + 1) % n));
  return 0.5 * twice;
}

/// Signed area of the closed polygon with corners `polygon` in order (units², the last
/// corner not repeated), positive when counter-clockwise.
inline double signed_area(const std::vector<Vec2>& polygon) {
  return polygon_signed_area(polygon.size(), [&polygon](std::size_t i) { return polygon[i]; });
}

/// Angle between the directions a and b, in degrees in [0, 180] (0 when either is zero).
inline double angle_between_deg(const Vec2& a, const Vec2& b) {
  return std::atan2(std::abs(cross2(a, b)), a.dot(b)) * 180.0 / std::numbers::pi;
}

/// Whether `q` lies inside the closed polygon whose k-th corner is `corner(k)`,
/// k = 0 … n−1 (even-odd rule: a ray from q crosses its edges an odd number of times).
template <class Corner>
bool inside_polygon(std::size_t n, const Corner& corner, const Vec2& q) {
  bool in = false;
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
    const Vec2 pi = corner(i), pj = corner(j);
    if ((pi.y() > q.y()) != (pj.y() > q.y()) &&
        q.x() < (pj.x() - pi.x()) * (q.y() - pi.y()) / (pj.y() - pi.y()) + pi.x())
      in = !in;
  }
  return in;
}

}  // namespace tightfit
