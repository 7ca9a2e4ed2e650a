#pragma once
// Hand-built patterns for the pattern-export tests: a rectangle, a trapezoid and a
// piece with a curved side (sleeve cap), sewn together by three seams.
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "tightfit/garment/pattern.hpp"

namespace tightfit::test {

/// Appends `segments` points from `a` (included) towards `b` (excluded).
inline void add_straight(std::vector<Vec2>& points, const Vec2& a, const Vec2& b, int segments) {
  for (int k = 0; k < segments; ++k)
    points.push_back(a + (b - a) * (static_cast<double>(k) / segments));
}

/// A piece whose boundary loop is `boundary` (m, counter-clockwise, star-shaped about
/// its vertex mean), meshed as a fan around an extra centre vertex.
inline PatternPiece fan_piece(const std::string& name, const std::vector<Vec2>& boundary,
                              const std::vector<int>& corners) {
  PatternPiece piece;
  piece.name = name;
  const auto n = static_cast<int>(boundary.size());
  piece.rest.resize(n + 1, 2);
  Vec2 centre = Vec2::Zero();
  for (int i = 0; i < n; ++i) {
    piece.rest.row(i) = boundary[static_cast<size_t>(i)].transpose();
    centre += boundary[static_cast<size_t>(i)] / n;
  }
  piece.rest.row(n) = centre.transpose();
  piece.triangles.resize(n, 3);
  for (int i = 0; i < n; ++i) piece.triangles.row(i) << i, (i + 1) % n, n;
  for (int i = 0; i < n; ++i) piece.boundary.push_back(i);
  piece.corners = corners;
  return piece;
}

/// Rectangle 0.30 × 0.40 m: bottom 6 segments (vertices 0..6), right 8 (6..14),
/// top 6 (14..20), left 8 (20..27, 0).
inline PatternPiece front_piece() {
  std::vector<Vec2> b;
  add_straight(b, {0.0, 0.0}, {0.30, 0.0}, 6);
  add_straight(b, {0.30, 0.0}, {0.30, 0.40}, 8);
  add_straight(b, {0.30, 0.40}, {0.0, 0.40}, 6);
  add_straight(b, {0.0, 0.40}, {0.0, 0.0}, 8);
  return fan_piece("front", b, {0, 6, 14, 20});
}

/// Trapezoid: bottom 0.30 m, top 0.24 m, height 0.40 m, same vertex numbering as the front.
inline PatternPiece back_piece() {
  std::vector<Vec2> b;
  add_straight(b, {0.0, 0.0}, {0.30, 0.0}, 6);
  add_straight(b, {0.30, 0.0}, {0.27, 0.40}, 8);
  add_straight(b, {0.27, 0.40}, {0.03, 0.40}, 6);
  add_straight(b, {0.03, 0.40}, {0.0, 0.0}, 8);
  PatternPiece piece = fan_piece("back", b, {0, 6, 14, 20});
  piece.grain = Vec2(0.0, 1.0);
  return piece;
}

/// Sleeve 0.24 m wide with a curved cap: bottom 6 segments (0..6), right 4 (6..10),
/// elliptic cap 16 (10..26), left 4 (26..29, 0). Grain tilted a little.
inline PatternPiece sleeve_piece() {
  std::vector<Vec2> b;
  add_straight(b, {0.0, 0.0}, {0.24, 0.0}, 6);
  add_straight(b, {0.24, 0.0}, {0.24, 0.15}, 4);
  for (int k = 0; k < 16; ++k) {
    const double theta = std::numbers::pi * k / 16.0;
    b.emplace_back(0.12 + 0.12 * std::cos(theta), 0.15 + 0.08 * std::sin(theta));
  }
  add_straight(b, {0.0, 0.15}, {0.0, 0.0}, 4);
  PatternPiece piece = fan_piece("sleeve", b, {0, 6, 10, 26});
  piece.grain = Vec2(0.1, 1.0).normalized();
  return piece;
}

/// front ↔ back side seams, sleeve bottom ↔ back top, front bottom pinned.
inline Pattern test_pattern() {
  Pattern pattern;
  pattern.pieces = {front_piece(), back_piece(), sleeve_piece()};
  const std::vector<int> right_up = {6, 7, 8, 9, 10, 11, 12, 13, 14};
  const std::vector<int> left_up = {0, 27, 26, 25, 24, 23, 22, 21, 20};
  pattern.seams.push_back({"side_right", {0, right_up}, {1, left_up}});
  pattern.seams.push_back({"side_left", {1, right_up}, {0, left_up}});
  pattern.seams.push_back(
      {"sleeve_hem", {2, {0, 1, 2, 3, 4, 5, 6}}, {1, {20, 19, 18, 17, 16, 15, 14}}});
  pattern.pinned.push_back({"waist", 0, {0, 1, 2, 3, 4, 5, 6}});
  return pattern;
}

}  // namespace tightfit::test
