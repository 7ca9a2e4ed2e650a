#include "tightfit/patterns/truing.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "patterns/support/pattern_tools.hpp"

namespace tightfit {
namespace truing_test {

/// A 200 × 100 mm rectangle with 5 mm vertex spacing, corners at the four corners,
/// the top side (y = 100) disturbed by ±`noise` mm of seeded noise.
struct NoisyRectangle {
  Polygon2 points;
  std::vector<bool> corner;
  std::vector<size_t> top;  ///< indices of the top side's points (corners excluded)
};

NoisyRectangle noisy_rectangle(double noise) {
  NoisyRectangle r;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> jitter(-1.0, 1.0);
  auto side = [&](const Vec2& a, const Vec2& b, int segments, bool disturbed) {
    for (int k = 0; k < segments; ++k) {
      Vec2 q = a + (b - a) * (static_cast<double>(k) / segments);
      const bool is_corner = k == 0;
      if (disturbed && !is_corner) {
        q.y() += noise * jitter(rng);
        r.top.push_back(r.points.size());
      }
      r.points.push_back(q);
      r.corner.push_back(is_corner);
    }
  };
  side({0.0, 0.0}, {200.0, 0.0}, 40, false);
  side({200.0, 0.0}, {200.0, 100.0}, 20, false);
  side({200.0, 100.0}, {0.0, 100.0}, 40, true);
  side({0.0, 100.0}, {0.0, 0.0}, 20, false);
  return r;
}

double max_turning(const Polygon2& polygon, const std::vector<bool>& skip_corner_at) {
  double worst = 0.0;
  for (size_t i = 0; i < polygon.size(); ++i)
    if (!skip_corner_at[i]) worst = std::max(worst, turning_angle(polygon, i));
  return worst;
}

/// Whether every point of `trued` is within `tolerance` of `original` and back.
double two_way_distance(const Polygon2& a, const Polygon2& b) {
  double worst = 0.0;
  for (const Vec2& q : a) worst = std::max(worst, test::polygon_distance(q, b));
  for (const Vec2& q : b) worst = std::max(worst, test::polygon_distance(q, a));
  return worst;
}

TEST(PatternTruing, ZeroToleranceReturnsTheInput) {
  const NoisyRectangle r = noisy_rectangle(0.2);
  const std::vector<bool> keep(r.points.size(), false);
  const TruedOutline t = true_outline(r.points, keep, r.corner, 0.0, 2.0);
  ASSERT_EQ(t.points.size(), r.points.size());
  for (size_t i = 0; i < t.points.size(); ++i) {
    EXPECT_EQ(t.points[i], r.points[i]);
    EXPECT_EQ(t.source[i], static_cast<int>(i));
  }
}

TEST(PatternTruing, ToleranceHeldAndCornersAndKeptPointsExact) {
  const NoisyRectangle r = noisy_rectangle(0.15);
  std::vector<bool> keep(r.points.size(), false);
  const size_t kept = r.top[17];
  keep[kept] = true;
  const double tolerance = 0.3;
  const TruedOutline t = true_outline(r.points, keep, r.corner, tolerance, 2.0);
  EXPECT_LE(two_way_distance(t.points, r.points), tolerance + 1e-9);
  ASSERT_EQ(t.source.size(), t.points.size());
  ASSERT_EQ(t.edge_source.size(), t.points.size());
  for (size_t i = 0; i < r.points.size(); ++i) {
    if (!r.corner[i] && !keep[i]) continue;
    const auto it = std::find(t.source.begin(), t.source.end(), static_cast<int>(i));
    ASSERT_NE(it, t.source.end()) << "kept point " << i << " missing";
    EXPECT_EQ(t.points[static_cast<size_t>(it - t.source.begin())], r.points[i]);
  }
  // Order kept: the sources that are input points increase around the loop.
  int last = -1;
  for (int s : t.source) {
    if (s < 0) continue;
    EXPECT_GT(s, last);
    last = s;
  }
}

TEST(PatternTruing, NoisyPolylineGetsSmallerTurningAngles) {
  const NoisyRectangle r = noisy_rectangle(0.1);
  const std::vector<bool> keep(r.points.size(), false);
  const TruedOutline t = true_outline(r.points, keep, r.corner, 0.3, 2.0);
  std::vector<bool> input_corner = r.corner;
  std::vector<bool> trued_corner(t.points.size(), false);
  for (size_t i = 0; i < t.points.size(); ++i)
    trued_corner[i] = t.source[i] >= 0 && r.corner[static_cast<size_t>(t.source[i])];
  const double before = max_turning(r.points, input_corner);
  const double after = max_turning(t.points, trued_corner);
  RecordProperty("turning_before_deg", std::to_string(before * 180.0 / std::numbers::pi));
  RecordProperty("turning_after_deg", std::to_string(after * 180.0 / std::numbers::pi));
  EXPECT_GT(before, 0.02);
  EXPECT_LT(after, 0.25 * before);
  // The noisy side became (nearly) straight: fewer points than before.
  EXPECT_LT(t.points.size(), r.points.size());
}

TEST(PatternTruing, StraightLinesStayStraight) {
  const NoisyRectangle r = noisy_rectangle(0.0);
  const std::vector<bool> keep(r.points.size(), false);
  const TruedOutline t = true_outline(r.points, keep, r.corner, 0.3, 2.0);
  for (const Vec2& q : t.points) {
    const bool on_side = std::abs(q.x()) < 1e-9 || std::abs(q.x() - 200.0) < 1e-9 ||
                         std::abs(q.y()) < 1e-9 || std::abs(q.y() - 100.0) < 1e-9;
    EXPECT_TRUE(on_side) << q.transpose();
  }
  EXPECT_EQ(t.points.size(), 4u);  // nothing but the corners is needed
}

TEST(PatternTruing, CircleIsSmoothWithinTolerance) {
  // A circle of radius 50 mm as a 72-gon, no corners: the trued curve passes through
  // kept point 0, stays within the tolerance of the polygon and turns less per point.
  Polygon2 circle;
  for (int k = 0; k < 72; ++k) {
    const double a = 2.0 * std::numbers::pi * k / 72.0;
    circle.emplace_back(50.0 * std::cos(a), 50.0 * std::sin(a));
  }
  std::vector<bool> keep(circle.size(), false);
  keep[0] = true;
  const std::vector<bool> corner(circle.size(), false);
  const double tolerance = 0.3;
  const TruedOutline t = true_outline(circle, keep, corner, tolerance, 2.0);
  EXPECT_LE(two_way_distance(t.points, circle), tolerance + 1e-9);
  EXPECT_EQ(t.points[0], circle[0]);
  EXPECT_LT(max_turning(t.points, std::vector<bool>(t.points.size(), false)),
            max_turning(circle, corner));
}

}  // namespace truing_test
}  // namespace tightfit
