#include "tightfit/objectives/shape_objective.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "objectives/objective_test_garments.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/objectives/imls_surface.hpp"

namespace tightfit::shape_objective_test {

/// Target points on the plane z = 0 over [−0.5, 0.5]², spacing 0.02, normals +z.
ImlsSurface plane_target(double radius) {
  const int n = 51;
  Points3 p(n * n, 3), nrm(n * n, 3);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      p.row(j * n + i) << -0.5 + 0.02 * i, -0.5 + 0.02 * j, 0.0;
      nrm.row(j * n + i) << 0.0, 0.0, 2.0;  // normalized by ImlsSurface
    }
  return ImlsSurface(p, nrm, radius);
}

/// Target points on a sphere of radius r (latitude-longitude), outward normals.
ImlsSurface sphere_target(double r, double radius) {
  const int nu = 60, nv = 30;
  Points3 p(nu * nv, 3), nrm(nu * nv, 3);
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      const double th = std::numbers::pi * (j + 0.5) / nv, ph = 2.0 * std::numbers::pi * i / nu;
      const Vec3 d(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th));
      p.row(j * nu + i) = r * d.transpose();
      nrm.row(j * nu + i) = d.transpose();
    }
  return ImlsSurface(p, nrm, radius);
}

/// FD check of ∇f at x.
double gradient_error(const ImlsSurface& s, const Vec3& x, double h) {
  auto f = [&](const VecX& y) { return s.evaluate(Vec3(y)).value; };
  return test::check_gradient(f, VecX(s.evaluate(x).gradient), VecX(x), h).relative_error;
}

TEST(ImlsSurface, PlaneTargetIsTheSignedDistanceWithinTheCutOff) {
  const ImlsSurface s = plane_target(0.05);
  for (const Vec3& x : {Vec3(0.013, -0.27, 0.01), Vec3(0.2, 0.2, -0.03), Vec3(-0.31, 0.05, 0.04),
                        Vec3(0.0, 0.0, 0.0)}) {
    const ImlsSurface::Evaluation e = s.evaluate(x);
    EXPECT_FALSE(e.fallback);
    EXPECT_NEAR(e.value, x.z(), 1e-14);
    EXPECT_LT((e.gradient - Vec3::UnitZ()).norm(), 1e-12);
  }
}

TEST(ImlsSurface, FallbackBeyondTheCutOffUsesTheNearestPointsPlane) {
  const ImlsSurface s = plane_target(0.05);
  const Vec3 x(0.011, 0.029, 0.2);  // nearest target point (0.02, 0.02, 0)
  const ImlsSurface::Evaluation e = s.evaluate(x);
  EXPECT_TRUE(e.fallback);
  EXPECT_NEAR(e.value, 0.2, 1e-15);
  EXPECT_EQ(e.gradient, Vec3::UnitZ());
  // Continuity where the last point leaves the h-ball (a single point in range gives the
  // same value as the fallback): beyond the plate's corner.
  const Vec3 corner(0.5, 0.5, 0.0);
  const Vec3 dir = Vec3(1.0, 1.0, 1.0).normalized();
  const ImlsSurface::Evaluation in = s.evaluate(corner + (0.05 - 1e-9) * dir);
  const ImlsSurface::Evaluation out = s.evaluate(corner + (0.05 + 1e-9) * dir);
  EXPECT_FALSE(in.fallback);
  EXPECT_TRUE(out.fallback);
  EXPECT_NEAR(in.value, out.value, 1e-8);
}

TEST(ImlsSurface, SphereTargetApproximatesTheDistance) {
  // On a curved target the point-normal IMLS is biased inwards by O(h²/R).
  const double r = 0.1, h = 0.02;
  const ImlsSurface s = sphere_target(r, h);
  for (const Vec3& d : {Vec3(1, 0, 0), Vec3(0.3, -0.5, 0.8), Vec3(-0.2, 0.9, -0.1)}) {
    for (double dist : {-0.004, 0.0, 0.005}) {
      const Vec3 x = (r + dist) * d.normalized();
      EXPECT_NEAR(s.evaluate(x).value, dist, 0.25 * h * h / (2.0 * r)) << dist;
    }
  }
}

TEST(ImlsSurface, GradientNearTheCutOffAndInTheFallback) {
  const ImlsSurface sphere = sphere_target(0.1, 0.03);
  EXPECT_LT(gradient_error(sphere, Vec3(0.03, -0.07, 0.065), 1e-7), 1e-6);
  EXPECT_LT(gradient_error(sphere, Vec3(0.02, 0.01, -0.112), 1e-7), 1e-6);
  // Two target points with different normals; x inside the first point's ball and at
  // r = h (1 − ε) from the second one.
  Points3 c(2, 3), n(2, 3);
  c << 0.0, 0.0, 0.0, 0.03, 0.0, 0.0;
  n << 0.0, 0.0, 1.0, 0.6, 0.0, 0.8;
  const double h = 0.05;
  const ImlsSurface pair(c, n, h);
  const Vec3 out_dir(-0.8, 0.0, 0.6);
  for (double eps : {1e-1, 1e-3, 1e-6}) {
    const Vec3 x =
        Vec3(0.03, 0.0, 0.0) + h * (1.0 - eps) * (out_dir + Vec3(0.0, 0.02, 0.0)).normalized();
    ASSERT_LT((x - Vec3(0.03, 0.0, 0.0)).norm(), h);
    ASSERT_LT(x.norm(), h);
    EXPECT_FALSE(pair.evaluate(x).fallback);
    EXPECT_LT(gradient_error(pair, x, 1e-3 * eps * h), 1e-6) << eps;
  }
  // One point just inside h at the plate's corner (the ratio of two tiny kernel sums).
  const ImlsSurface plane = plane_target(0.05);
  const Vec3 near_cut = Vec3(0.5, 0.5, 0.0) + (0.05 * (1.0 - 1e-6)) * Vec3(0.6, 0.0, 0.8);
  EXPECT_FALSE(plane.evaluate(near_cut).fallback);
  EXPECT_LT(gradient_error(plane, near_cut, 1e-10), 1e-6);
  // No target within h.
  const Vec3 far(0.3, -0.1, 0.4);
  EXPECT_TRUE(sphere.evaluate(far).fallback);
  EXPECT_LT(gradient_error(sphere, far, 1e-7), 1e-6);
}

TEST(ImlsSurface, RejectsBadTargets) {
  Points3 p(2, 3), n(2, 3);
  p.setZero();
  n.setZero();
  n(0, 2) = 1.0;
  EXPECT_THROW(ImlsSurface(p, n, 0.1), InputError);  // zero normal
  n(1, 0) = 1.0;
  EXPECT_THROW(ImlsSurface(p, n, 0.0), InputError);
  EXPECT_THROW(ImlsSurface(Points3(0, 3), Points3(0, 3), 0.1), InputError);
  EXPECT_THROW(ImlsSurface(p, Points3(1, 3), 0.1), InputError);
  EXPECT_NO_THROW(ImlsSurface(p, n, 0.1));
}

TEST(ShapeObjective, ValueAndGradientOnASleeve) {
  // Sleeve of radius 0.05 against a sphere of radius 0.06 centred at the sleeve's middle:
  // some vertices within the cut-off, some in the fallback.
  test::GarmentState s = test::sleeve(13, 6, 0.05, 0.3, 0.1, 0.2, 2);
  const test::OrientedPoints sphere =
      test::fibonacci_sphere(Vec3(0, 0, 0.05), 0.06, 2000);  // spacing about 5 mm
  const Points3& pts = sphere.points;
  const Points3& nrm = sphere.normals;
  const ShapeObjective t(ImlsSurface(pts, nrm, 0.008), s.garment.num_garment_vertices());
  const VecX x = test::perturb(s.x, 0.003, 1);
  const Points2 rest = s.garment.rest_positions();
  const VecX f = t.distances(x);
  EXPECT_NEAR(t.value({x, rest}), f.squaredNorm(), 1e-15);
  int fallback = 0;
  for (int v = 0; v < s.garment.num_garment_vertices(); ++v)
    fallback += t.target().evaluate(x.segment<3>(3 * v)).fallback ? 1 : 0;
  EXPECT_GT(fallback, 0);
  EXPECT_LT(fallback, s.garment.num_garment_vertices());
  const test::GradientErrors e = test::gradient_errors(t, x, rest, 1e-7, 1e-7);
  EXPECT_LT(e.x, 1e-6);
  EXPECT_EQ(e.norm_rest, 0.0);
  EXPECT_TRUE(t.depends_on_positions());
  // A vertex subset.
  const ShapeObjective sub(ImlsSurface(pts, nrm, 0.008), s.garment.num_garment_vertices(),
                           {0, 5, 7});
  EXPECT_NEAR(sub.value({x, rest}), f[0] * f[0] + f[5] * f[5] + f[7] * f[7], 1e-15);
  EXPECT_THROW(ShapeObjective(ImlsSurface(pts, nrm, 0.008), 3, {3}), std::invalid_argument);
  // Vertex weights (each vertex's share of the rest area over the mean share).
  const VecX w = shape_vertex_weights(s.garment, {});
  EXPECT_NEAR(w.mean(), 1.0, 1e-12);
  const ShapeObjective weighted(ImlsSurface(pts, nrm, 0.008), s.garment.num_garment_vertices(), {},
                                w);
  EXPECT_NEAR(weighted.value({x, rest}), (w.array() * f.array().square()).sum(), 1e-15);
  const test::GradientErrors ew = test::gradient_errors(weighted, x, rest, 1e-7, 1e-7);
  EXPECT_LT(ew.x, 1e-6);
  EXPECT_THROW(ShapeObjective(ImlsSurface(pts, nrm, 0.008), 3, {}, VecX::Ones(2)),
               std::invalid_argument);
}

TEST(ShapeObjective, UnpinnedVerticesLeaveThePinnedRingsOut) {
  test::GarmentState s = test::sleeve(7, 4, 0.05, 0.3, 0.1, 0.0, 1);
  // Pin the bottom ring (pattern row 0; the seam welds its two ends into one vertex).
  std::vector<int> ring;
  for (int i = 0; i < 7; ++i) ring.push_back(s.garment.topology->pattern_to_garment[i]);
  std::sort(ring.begin(), ring.end());
  ring.erase(std::unique(ring.begin(), ring.end()), ring.end());
  s.garment.set_pinned_vertices(ring);
  const std::vector<int> free = unpinned_vertices(s.garment);
  EXPECT_EQ(free.size() + ring.size(), static_cast<size_t>(s.garment.num_garment_vertices()));
  for (int v : ring) EXPECT_FALSE(std::binary_search(free.begin(), free.end(), v));
  EXPECT_TRUE(std::is_sorted(free.begin(), free.end()));
  // Moving a pinned vertex changes the full objective but not the unpinned one.
  const ImlsSurface plane = plane_target(0.05);
  const ShapeObjective all(plane, s.garment.num_garment_vertices());
  const ShapeObjective unpinned(plane, s.garment.num_garment_vertices(), free);
  const Points2 rest = s.garment.rest_positions();
  VecX moved = s.x;
  moved[3 * ring[0] + 2] += 0.01;
  EXPECT_NE(all.value({moved, rest}), all.value({s.x, rest}));
  EXPECT_EQ(unpinned.value({moved, rest}), unpinned.value({s.x, rest}));
}

}  // namespace tightfit::shape_objective_test
