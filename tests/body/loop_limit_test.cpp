#include "tightfit/body/loop_limit.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "tightfit/body/generators.hpp"

namespace tightfit::loop_limit_test {

TriMesh octahedron(double r) {
  TriMesh m;
  m.vertices.resize(6, 3);
  m.vertices << r, 0, 0, -r, 0, 0, 0, r, 0, 0, -r, 0, 0, 0, r, 0, 0, -r;
  m.faces.resize(8, 3);
  m.faces << 0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5;
  return m;
}

TEST(LoopLimit, ChiMatchesLoopsMasks) {
  EXPECT_NEAR(loop_limit_chi(6), 1.0 / 12.0, 1e-15);  // regular: 1/2 v + 1/12 Σ w
  EXPECT_NEAR(loop_limit_chi(3), 0.2, 1e-15);         // β3 = 3/16
  const double beta4 =
      (5.0 / 8.0 - std::pow(3.0 / 8.0 + 0.25 * std::cos(std::numbers::pi / 2), 2)) / 4.0;
  EXPECT_NEAR(loop_limit_chi(4), 1.0 / (4.0 + 3.0 / (8.0 * beta4)), 1e-15);
  EXPECT_THROW(loop_limit_chi(2), std::invalid_argument);
}

TEST(LoopLimit, OctahedronVerticesMoveInwardBySymmetry) {
  const TriMesh m = octahedron(1.0);
  const Points3 limit = loop_limit_positions(m);
  // Valence 4, neighbours sum to zero: v∞ = (1 − 4χ) v.
  const double scale = 1.0 - 4.0 * loop_limit_chi(4);
  for (int v = 0; v < 6; ++v)
    EXPECT_NEAR((limit.row(v) - scale * m.vertices.row(v)).norm(), 0.0, 1e-15);
}

TEST(LoopLimit, FitPutsLimitPointsOnSphere) {
  TriMesh m = octahedron(1.0);
  const auto onto_sphere = [](const Vec3& p) { return Vec3(p.normalized()); };
  const LimitFitResult r = fit_loop_limit(m, onto_sphere);
  // Tolerance: 1e-8 of the mean edge length (√2).
  EXPECT_LT(r.max_residual, 1.5e-8);
  const Points3 limit = loop_limit_positions(m);
  for (int v = 0; v < 6; ++v) EXPECT_NEAR(limit.row(v).norm(), 1.0, 1.5e-8);
  EXPECT_NEAR(m.vertices.row(0).norm(), 1.0 / (1.0 - 4.0 * loop_limit_chi(4)), 1e-7);
  EXPECT_GT(r.max_displacement, 0.1);
}

TEST(LoopLimit, FitOfAPlaneIsIdentity) {
  // A flat target: projecting the limit onto the plane of a planar mesh changes nothing.
  TriMesh m = octahedron(1.0);
  m.vertices.col(2).setZero();  // flattened (degenerate but valid topology)
  const Points3 before = m.vertices;
  const LimitFitResult r = fit_loop_limit(m, [](const Vec3& p) { return Vec3(p.x(), p.y(), 0.0); });
  EXPECT_EQ(r.iterations, 0);
  EXPECT_EQ((m.vertices - before).norm(), 0.0);
}

}  // namespace tightfit::loop_limit_test
