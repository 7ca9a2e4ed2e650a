#include <gtest/gtest.h>

#include <numbers>
#include <random>

#include "subdiv/test_meshes.hpp"
#include "support/finite_difference.hpp"
#include "tightfit/subdiv/limit_surface.hpp"

namespace tightfit::walk_test {

using subdiv_test::irregular_meshes;
using subdiv_test::random_point;

Vec2 random_delta(std::mt19937& rng, double max_length) {
  std::uniform_real_distribution<double> angle(0.0, 2 * std::numbers::pi), length(0.0, max_length);
  const double a = angle(rng), l = length(rng);
  return {l * std::cos(a), l * std::sin(a)};
}

void expect_inside(const SurfacePoint& s) {
  EXPECT_GE(s.u, 0.0);
  EXPECT_GE(s.v, 0.0);
  EXPECT_LE(s.u + s.v, 1.0 + 1e-15);
}

TEST(LimitSurfaceWalk, ThereAndBackReturnsToTheStart) {
  for (const auto& [name, mesh] : irregular_meshes()) {
    const LimitSurface surface(mesh);
    std::mt19937 rng(11);
    int crossings = 0;
    for (int k = 0; k < 400; ++k) {
      const SurfacePoint s = random_point(rng, surface.num_faces());
      const Vec2 delta = random_delta(rng, 2.5);
      const LimitSurface::Walk there = surface.walk(s, delta);
      ASSERT_TRUE(there.complete);
      expect_inside(there.end);
      crossings += there.crossings;
      const LimitSurface::Walk back = surface.walk(there.end, -(there.jacobian * delta));
      ASSERT_TRUE(back.complete);
      EXPECT_EQ(back.end.face, s.face) << name;
      EXPECT_NEAR(back.end.u, s.u, 1e-12) << name;
      EXPECT_NEAR(back.end.v, s.v, 1e-12) << name;
      EXPECT_EQ(back.crossings, there.crossings);
      EXPECT_LT((back.jacobian * there.jacobian - Mat2::Identity()).norm(), 1e-12);
    }
    EXPECT_GT(crossings, 400) << name;
  }
}

TEST(LimitSurfaceWalk, WalksAlongOneLineCompose) {
  // Splitting a straight walk into two pieces changes nothing. (Broken lines need not
  // agree with the straight one: the domain has cone points at extraordinary vertices.)
  for (const auto& [name, mesh] : irregular_meshes()) {
    const LimitSurface surface(mesh);
    std::mt19937 rng(12);
    for (int k = 0; k < 300; ++k) {
      const SurfacePoint s = random_point(rng, surface.num_faces());
      const Vec2 d1 = random_delta(rng, 1.5);
      const Vec2 d2 = std::uniform_real_distribution<double>(0.0, 1.5)(rng) * d1;
      const LimitSurface::Walk whole = surface.walk(s, d1 + d2);
      const LimitSurface::Walk first = surface.walk(s, d1);
      const LimitSurface::Walk second = surface.walk(first.end, first.jacobian * d2);
      EXPECT_EQ(whole.end.face, second.end.face) << name;
      EXPECT_NEAR(whole.end.u, second.end.u, 1e-12) << name;
      EXPECT_NEAR(whole.end.v, second.end.v, 1e-12) << name;
      EXPECT_LT((whole.jacobian - second.jacobian * first.jacobian).norm(),
                1e-12 * whole.jacobian.norm());
    }
  }
}

TEST(LimitSurfaceWalk, JacobianCarriesTangentVectors) {
  // Eq. 20: d x(end(delta)) / d delta = [x_u x_v](end) · J, checked with finite
  // differences of the walked position, for ends outside the Gregory regions.
  for (const auto& [name, mesh] : irregular_meshes()) {
    const LimitSurface surface(mesh);
    std::mt19937 rng(13);
    int checked = 0;
    while (checked < 60) {
      const SurfacePoint s = random_point(rng, surface.num_faces());
      const Vec2 delta = random_delta(rng, 2.0);
      const LimitSurface::Walk w = surface.walk(s, delta);
      const double corner = 1.0 / 128;
      if (w.crossings == 0 || w.end.u + w.end.v < corner || w.end.u > 1 - corner ||
          w.end.v > 1 - corner)
        continue;
      ++checked;
      const LimitFrame fr = surface.evaluate(w.end, mesh.vertices);
      Mat32 T;
      T << fr.xu, fr.xv;
      const Eigen::MatrixXd analytic = T * w.jacobian;
      auto x_of = [&](const Eigen::VectorXd& d) -> Eigen::VectorXd {
        return surface.position(surface.walk(s, Vec2(d[0], d[1])).end, mesh.vertices);
      };
      const auto c = test::check_jacobian(x_of, analytic, Eigen::Vector2d(delta), 1e-6);
      EXPECT_LT(c.relative_error, 1e-6) << name << " crossings " << w.crossings;
    }
  }
}

TEST(LimitSurfaceWalk, ZeroStepAndSingleFaceSteps) {
  const LimitSurface surface(subdiv_test::icosahedron());
  const LimitSurface::Walk still = surface.walk({3, 0.2, 0.3}, Vec2::Zero());
  EXPECT_EQ(still.end.face, 3);
  EXPECT_EQ(still.end.u, 0.2);
  EXPECT_EQ(still.end.v, 0.3);
  EXPECT_EQ(still.crossings, 0);
  EXPECT_EQ(still.jacobian, Mat2::Identity());
  const LimitSurface::Walk inside = surface.walk({3, 0.2, 0.3}, Vec2(0.1, -0.05));
  EXPECT_EQ(inside.end.face, 3);
  EXPECT_NEAR(inside.end.u, 0.3, 1e-15);
  EXPECT_NEAR(inside.end.v, 0.25, 1e-15);
}

TEST(LimitSurfaceWalk, LinesThroughVerticesEndInsideAFace) {
  for (const auto& [name, mesh] : irregular_meshes()) {
    const LimitSurface surface(mesh);
    for (int f = 0; f < surface.num_faces(); ++f) {
      // Aimed exactly at corner 0, then past it; and exactly along an edge.
      for (const Vec2& d : {Vec2(-0.5, -0.5), Vec2(-0.3, -0.6), Vec2(0.9, 0.0)}) {
        const SurfacePoint start =
            d[1] == 0.0 ? SurfacePoint{f, 0.05, 0.0} : SurfacePoint{f, 0.25, 0.25 * d[1] / d[0]};
        const LimitSurface::Walk w = surface.walk(start, d);
        expect_inside(w.end);
        EXPECT_LE(w.crossings, 64) << name;
      }
    }
  }
}

}  // namespace tightfit::walk_test
