#pragma once
/// Barycentric weights and closest points on single triangles (2D and 3D).
#include <Eigen/Core>
#include <Eigen/LU>  // determinant(), inverse()

#include "tightfit/common/types.hpp"

namespace tightfit {

/// Barycentric weights (w0, w1, w2) of q in the 2D triangle (a, b, c), Σw = 1;
/// negative weights outside. A degenerate triangle gives (1, 0, 0).
inline Vec3 barycentric_2d(const Vec2& q, const Vec2& a, const Vec2& b, const Vec2& c) {
  Mat2 E;
  E << b - a, c - a;
  const double det = E.determinant();
  if (det == 0.0) return Vec3(1, 0, 0);
  const Vec2 st = E.inverse() * (q - a);
  return Vec3(1.0 - st.x() - st.y(), st.x(), st.y());
}

/// Barycentric weights (all ≥ 0) of the point of triangle (a, b, c) closest to p, in
/// any dimension (Ericson, Real-Time Collision Detection, 5.1.5).
template <typename V>
Vec3 closest_point_weights_any(const V& p, const V& a, const V& b, const V& c) {
  const V ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return Vec3(1, 0, 0);
  const V bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return Vec3(0, 1, 0);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double v = d1 / (d1 - d3);
    return Vec3(1 - v, v, 0);
  }
  const V cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return Vec3(0, 0, 1);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double w = d2 / (d2 - d6);
    return Vec3(1 - w, 0, w);
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return Vec3(0, 1 - w, w);
  }
  const double denom = 1.0 / (va + vb + vc);
  const double v = vb * denom, w = vc * denom;
  return Vec3(1 - v - w, v, w);
}

inline Vec3 closest_point_weights_2d(const Vec2& p, const Vec2& a, const Vec2& b, const Vec2& c) {
  return closest_point_weights_any<Vec2>(p, a, b, c);
}
inline Vec3 closest_point_weights(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  return closest_point_weights_any<Vec3>(p, a, b, c);
}

}  // namespace tightfit
