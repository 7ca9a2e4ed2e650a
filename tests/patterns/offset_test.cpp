#include "tightfit/patterns/offset.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "patterns/support/pattern_tools.hpp"

namespace tightfit::pattern_offset_test {

using test::inside_polygon;
using test::polygon_distance;
using test::self_intersects;

Polygon2 rectangle(double w, double h) { return {{0, 0}, {w, 0}, {w, h}, {0, h}}; }

/// Checks what every cut line must satisfy: simple, counter-clockwise, encloses the
/// sew line, and keeps at least the smallest allowance from it everywhere.
void expect_valid_cut(const Polygon2& sew, const Polygon2& cut, double min_allowance) {
  EXPECT_FALSE(self_intersects(cut));
  EXPECT_GT(signed_area(cut), signed_area(sew));
  for (const Vec2& q : sew) EXPECT_TRUE(inside_polygon(q, cut)) << q.transpose();
  for (const Vec2& q : cut)
    EXPECT_GE(polygon_distance(q, sew), min_allowance - 1e-9) << q.transpose();
}

TEST(PatternOffset, RectangleMitresToLargerRectangle) {
  const Polygon2 sew = rectangle(100, 50);
  const Polygon2 cut = offset_polygon(sew, {10, 10, 10, 10}, CornerStyle::kMitre, 2.0, 0.05);
  ASSERT_EQ(cut.size(), 4u);
  EXPECT_NEAR(signed_area(cut), 120.0 * 70.0, 1e-9);
  for (const Vec2& q : cut) {
    EXPECT_NEAR(std::abs(q.x() - 50.0), 60.0, 1e-12);
    EXPECT_NEAR(std::abs(q.y() - 25.0), 35.0, 1e-12);
  }
  expect_valid_cut(sew, cut, 10.0);
}

TEST(PatternOffset, PerEdgeAllowance) {
  const Polygon2 sew = rectangle(100, 50);
  const Polygon2 cut = offset_polygon(sew, {20, 10, 10, 10}, CornerStyle::kMitre, 2.0, 0.05);
  EXPECT_NEAR(signed_area(cut), 120.0 * 80.0, 1e-9);
  double ymin = 0.0;
  for (const Vec2& q : cut) ymin = std::min(ymin, q.y());
  EXPECT_NEAR(ymin, -20.0, 1e-12);
  expect_valid_cut(sew, cut, 10.0);
}

TEST(PatternOffset, StepWhereAllowanceChangesOnAStraightEdge) {
  // Bottom edge split at x = 50: the left half has 20 mm, the rest 10 mm.
  const Polygon2 sew = {{0, 0}, {50, 0}, {100, 0}, {100, 50}, {0, 50}};
  const Polygon2 cut = offset_polygon(sew, {20, 10, 10, 10, 10}, CornerStyle::kMitre, 2.0, 0.05);
  EXPECT_NEAR(signed_area(cut), 120.0 * 70.0 + 60.0 * 10.0, 1e-9);
  int on_step = 0;
  for (const Vec2& q : cut) on_step += std::abs(q.x() - 50.0) < 1e-12 ? 1 : 0;
  EXPECT_EQ(on_step, 2);
  expect_valid_cut(sew, cut, 10.0);
}

TEST(PatternOffset, RoundCornersKeepExactDistance) {
  const Polygon2 sew = rectangle(100, 50);
  const Polygon2 cut = offset_polygon(sew, {10, 10, 10, 10}, CornerStyle::kRound, 2.0, 0.01);
  for (const Vec2& q : cut) EXPECT_NEAR(polygon_distance(q, sew), 10.0, 1e-9);
  // Area of the rounded rectangle minus the chord error of the polygonal arcs.
  const double exact = 100.0 * 50.0 + 2.0 * (100.0 + 50.0) * 10.0 + std::numbers::pi * 100.0;
  EXPECT_NEAR(signed_area(cut), exact, 0.01 * 2.0 * std::numbers::pi * 10.0);
  EXPECT_LT(signed_area(cut), exact);
  expect_valid_cut(sew, cut, 10.0);
}

TEST(PatternOffset, SharpCornerIsRoundedBeyondMitreLimit) {
  // A 10° spike: its mitre would reach 10 / sin(5°) ≈ 115 mm.
  const double half = 5.0 * std::numbers::pi / 180.0;
  const Polygon2 sew = {{0, 0}, {200, -200 * std::tan(half)}, {200, 200 * std::tan(half)}};
  const Polygon2 cut = offset_polygon(sew, {10, 10, 10}, CornerStyle::kMitre, 2.0, 0.05);
  double farthest = 0.0;
  for (const Vec2& q : cut) farthest = std::max(farthest, polygon_distance(q, sew));
  EXPECT_LE(farthest, 2.0 * 10.0 + 1e-9);
  expect_valid_cut(sew, cut, 10.0);
}

TEST(PatternOffset, SlitNarrowerThanTwiceTheAllowanceIsBridged) {
  // A U shape: slit 4 mm wide and 40 mm deep from the top.
  const Polygon2 sew = {{0, 0},   {100, 0}, {100, 60}, {52, 60},
                        {52, 20}, {48, 20}, {48, 60},  {0, 60}};
  const Polygon2 cut =
      offset_polygon(sew, std::vector<double>(sew.size(), 10.0), CornerStyle::kMitre, 2.0, 0.05);
  expect_valid_cut(sew, cut, 10.0);
  // Nothing of the cut line dips into the slit: the top is flat at y = 70.
  for (const Vec2& q : cut) {
    if (q.x() > 0.0 && q.x() < 100.0) {
      EXPECT_TRUE(q.y() < 0.0 || std::abs(q.y() - 70.0) < 1e-9) << q.transpose();
    }
  }
}

TEST(PatternOffset, ConcaveCurveTighterThanTheAllowance) {
  // A bite of radius 5 mm out of the top of a 100 × 60 rectangle, 32 segments.
  Polygon2 sew = {{0, 0}, {100, 0}, {100, 60}};
  for (int k = 0; k <= 32; ++k) {
    const double theta = std::numbers::pi * k / 32.0;
    sew.emplace_back(50.0 + 5.0 * std::cos(theta), 60.0 - 5.0 * std::sin(theta));
  }
  sew.emplace_back(0, 60);
  const Polygon2 cut =
      offset_polygon(sew, std::vector<double>(sew.size(), 10.0), CornerStyle::kMitre, 2.0, 0.05);
  expect_valid_cut(sew, cut, 10.0);
  // The offset of a 5 mm hole by 10 mm closes it: the cut line's top is straight.
  double lowest_top = 1e9;
  for (const Vec2& q : cut) {
    if (q.y() > 30.0) lowest_top = std::min(lowest_top, q.y());
  }
  EXPECT_NEAR(lowest_top, 70.0, 1e-9);
}

TEST(PatternOffset, GentleConcaveCurveFollowsTheCurve) {
  // A scoop of radius 80 mm (an armhole-like curve): the cut line stays 10 mm away.
  Polygon2 sew = {{0, 0}, {200, 0}, {200, 100}};
  for (int k = 0; k <= 40; ++k) {
    const double theta = std::numbers::pi * k / 40.0;
    sew.emplace_back(100.0 + 80.0 * std::cos(theta), 100.0 - 40.0 * std::sin(theta));
  }
  sew.emplace_back(0, 100);
  const Polygon2 cut =
      offset_polygon(sew, std::vector<double>(sew.size(), 10.0), CornerStyle::kMitre, 2.0, 0.05);
  expect_valid_cut(sew, cut, 10.0);
  // Every sew-line edge midpoint is exactly one allowance from the cut line.
  for (size_t i = 0; i < sew.size(); ++i) {
    const Vec2 mid = 0.5 * (sew[i] + sew[(i + 1) % sew.size()]);
    EXPECT_NEAR(polygon_distance(mid, cut), 10.0, 1e-9) << i;
  }
}

TEST(PatternOffset, ZeroAllowanceReturnsTheSewLine) {
  const Polygon2 sew = {{0, 0}, {100, 0}, {60, 30}, {100, 60}, {0, 60}};
  const Polygon2 cut =
      offset_polygon(sew, std::vector<double>(sew.size(), 0.0), CornerStyle::kMitre, 2.0, 0.05);
  EXPECT_NEAR(signed_area(cut), signed_area(sew), 1e-9);
  EXPECT_EQ(cut.size(), sew.size());
}

TEST(PatternOffset, PolygonMeasures) {
  const Polygon2 square = rectangle(2, 2);
  EXPECT_DOUBLE_EQ(signed_area(square), 4.0);
  EXPECT_DOUBLE_EQ(test::perimeter(square), 8.0);
  EXPECT_TRUE(area_centroid(square).isApprox(Vec2(1, 1)));
  const Polygon2 reversed(square.rbegin(), square.rend());
  EXPECT_DOUBLE_EQ(signed_area(reversed), -4.0);
}

}  // namespace tightfit::pattern_offset_test
