/// TriangleLocator answers as a scan over all triangles in index order would.
#include "tightfit/garment/triangle_locator.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <random>
#include <stdexcept>

#include "tightfit/garment/triangle_geometry.hpp"

namespace tightfit::triangle_locator_test {

/// A jittered n×n grid of squares, two triangles each, and one degenerate triangle.
struct TestMesh {
  Points2 points;
  Triangles triangles;
};

TestMesh jittered_grid(int n) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> jitter(-0.3, 0.3);
  TestMesh m;
  m.points.resize((n + 1) * (n + 1), 2);
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) {
      const bool inner = i > 0 && i < n && j > 0 && j < n;
      m.points.row(i * (n + 1) + j) << 0.01 * (i + (inner ? jitter(rng) : 0.0)),
          0.02 * (j + (inner ? jitter(rng) : 0.0));
    }
  m.triangles.resize(2 * n * n + 1, 3);
  int t = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const int a = i * (n + 1) + j, b = a + n + 1;
      m.triangles.row(t++) << a, b, b + 1;
      m.triangles.row(t++) << a, b + 1, a + 1;
    }
  m.triangles.row(t) << 0, 1, 2;  // collinear corners: degenerate
  return m;
}

int scan_containing(const TestMesh& m, const Vec2& q) {
  for (int t = 0; t < m.triangles.rows(); ++t) {
    const Vec2 a = m.points.row(m.triangles(t, 0)), b = m.points.row(m.triangles(t, 1)),
               c = m.points.row(m.triangles(t, 2));
    if ((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x() == 0.0) continue;
    if (barycentric_2d(q, a, b, c).minCoeff() >= -TriangleLocator::kContainsTolerance) return t;
  }
  return -1;
}

int scan_nearest(const TestMesh& m, const Vec2& q) {
  int best = -1;
  double best_d = std::numeric_limits<double>::infinity();
  for (int t = 0; t < m.triangles.rows(); ++t) {
    const Vec2 a = m.points.row(m.triangles(t, 0)), b = m.points.row(m.triangles(t, 1)),
               c = m.points.row(m.triangles(t, 2));
    const Vec3 w = closest_point_weights_2d(q, a, b, c);
    const double d = (w[0] * a + w[1] * b + w[2] * c - q).squaredNorm();
    if (d < best_d) {
      best_d = d;
      best = t;
    }
  }
  return best;
}

TEST(TriangleLocator, AnswersAsAScanOverAllTriangles) {
  const TestMesh m = jittered_grid(12);
  const TriangleLocator locator(m.triangles, m.points);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> x(-0.05, 0.17), y(-0.1, 0.34);
  int inside = 0;
  for (int k = 0; k < 2000; ++k) {
    const Vec2 q(x(rng), y(rng));
    const int expected = scan_containing(m, q);
    EXPECT_EQ(locator.containing(q), expected) << q.transpose();
    inside += expected >= 0 ? 1 : 0;
    EXPECT_EQ(locator.nearest(q), scan_nearest(m, q)) << q.transpose();
  }
  EXPECT_GT(inside, 300);  // about 30 % of the sampled box is meshed
  EXPECT_LT(inside, 1000);
  // On a shared vertex, the lowest-index triangle; `accept` skips others.
  const Vec2 vertex = m.points.row(m.triangles(40, 0));
  EXPECT_EQ(locator.containing(vertex), scan_containing(m, vertex));
  const int first = locator.containing(vertex);
  EXPECT_GT(locator.containing(vertex, [&](int t) { return t != first; }), first);
}

TEST(TriangleLocator, NoTrianglesHaveNoNearest) {
  const TriangleLocator locator(Triangles(0, 3), Points2(0, 2));
  EXPECT_EQ(locator.containing(Vec2(0, 0)), -1);
  EXPECT_THROW(locator.nearest(Vec2(0, 0)), std::invalid_argument);
}

}  // namespace tightfit::triangle_locator_test
