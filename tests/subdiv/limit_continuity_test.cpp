#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include "subdiv/loop_reference.hpp"
#include "subdiv/test_meshes.hpp"
#include "tightfit/subdiv/limit_surface.hpp"

namespace tightfit::limit_continuity_test {

using subdiv_test::irregular_meshes;

/// Surface point at parameter t along face edge i (from corner i to corner i+1).
SurfacePoint on_edge(int face, int i, double t) {
  const Vec2 corner[3] = {Vec2(0, 0), Vec2(1, 0), Vec2(0, 1)};
  const Vec2 uv = (1 - t) * corner[i] + t * corner[(i + 1) % 3];
  return {face, uv[0], uv[1]};
}

TEST(LimitSurface, PositionAndTangentPlaneAreContinuousAcrossEveryEdge) {
  for (const auto& [name, mesh] : irregular_meshes()) {
    const LimitSurface surface(mesh);
    const double size =
        (mesh.vertices.colwise().maxCoeff() - mesh.vertices.colwise().minCoeff()).norm();
    for (int f = 0; f < surface.num_faces(); ++f) {
      for (int i = 0; i < 3; ++i) {
        const LimitSurface::EdgeMap em = surface.edge_map(f, i);
        ASSERT_GE(em.neighbor, 0);
        for (double t : {0.0, 0.003, 0.1, 0.25, 0.5, 0.61, 0.9, 0.997, 1.0}) {
          const SurfacePoint a = on_edge(f, i, t);
          // The same point seen from the neighbour: its edge runs the other way.
          const SurfacePoint b = on_edge(em.neighbor, em.edge_in_neighbor, 1 - t);
          const Vec2 mapped = em.offset + em.jacobian * Vec2(a.u, a.v);
          EXPECT_NEAR(mapped[0], b.u, 1e-15);
          EXPECT_NEAR(mapped[1], b.v, 1e-15);
          const LimitFrame fa = surface.evaluate(a, mesh.vertices);
          const LimitFrame fb = surface.evaluate(b, mesh.vertices);
          EXPECT_LT((fa.x - fb.x).norm(), 1e-12 * size)
              << name << " face " << f << " edge " << i << " t " << t;
          const Vec3 na = surface.normal(a, mesh.vertices), nb = surface.normal(b, mesh.vertices);
          // Exact (box-spline) patches on both sides away from extraordinary corners;
          // the Gregory patches near them are tangent-plane continuous (G1) to round-off
          // but not C1 under the affine crossing map.
          const bool gregory = t < 1.0 / 256 || t > 1 - 1.0 / 256;
          EXPECT_LT((na - nb).norm(), gregory ? 1e-8 : 1e-10)
              << name << " face " << f << " edge " << i << " t " << t;
          if (!gregory) {
            // C1 with the crossing map (Eq. 20): [xu xv]_b J = [xu xv]_a.
            Mat32 Ta, Tb;
            Ta << fa.xu, fa.xv;
            Tb << fb.xu, fb.xv;
            EXPECT_LT((Tb * em.jacobian - Ta).norm(), 1e-10 * Ta.norm()) << name << " face " << f;
          }
        }
      }
    }
  }
}

TEST(LimitSurface, EveryVertexHasOneLimitPointAndNormal) {
  // At a control vertex (including extraordinary ones) all incident faces agree.
  for (const auto& [name, mesh] : irregular_meshes()) {
    const LimitSurface surface(mesh);
    const Vec2 corner_uv[3] = {Vec2(0, 0), Vec2(1, 0), Vec2(0, 1)};
    for (int v = 0; v < mesh.num_vertices(); ++v) {
      std::vector<Vec3> x, n;
      for (int f : surface.topology().vertex_faces(v)) {
        int c = 0;
        while (mesh.faces(f, c) != v) ++c;
        const SurfacePoint s{f, corner_uv[c][0], corner_uv[c][1]};
        x.push_back(surface.position(s, mesh.vertices));
        n.push_back(surface.normal(s, mesh.vertices));
        ASSERT_TRUE(n.back().allFinite()) << name << " vertex " << v;
      }
      for (std::size_t k = 1; k < x.size(); ++k) {
        EXPECT_LT((x[k] - x[0]).norm(), 1e-14) << name << " vertex " << v;
        EXPECT_LT((n[k] - n[0]).norm(), 1e-9) << name << " vertex " << v;
      }
    }
  }
}

TEST(LimitSurface, MatchesUniformLoopSubdivisionAtDyadicPoints) {
  for (const auto& [name, mesh] : irregular_meshes()) {
    const LimitSurface surface(mesh);
    subdiv_test::LoopLevel level = subdiv_test::loop_base(mesh);
    for (int k = 1; k <= 3; ++k) {
      level = subdiv_test::loop_subdivide(level);
      const Points3 limit = subdiv_test::loop_limit_positions(level.mesh);
      const std::vector<SurfacePoint> points = subdiv_test::vertex_surface_points(level);
      double worst = 0;
      for (int i = 0; i < level.mesh.num_vertices(); ++i) {
        const Vec3 x = surface.position(points[static_cast<std::size_t>(i)], mesh.vertices);
        worst = std::max(worst, (x - limit.row(i).transpose()).norm());
      }
      EXPECT_LT(worst, 1e-10) << name << " after " << k << " Loop steps";
    }
  }
}

TEST(LimitSurface, NormalsPointOutwardAndSphereCurvatureIsNegative) {
  // The limit of a refined octahedron is close to a sphere: outward normals and a
  // shape operator near -Id/R (S = -dn with outward n).
  TriMesh sphere = subdiv_test::octahedron();
  for (int k = 0; k < 3; ++k) sphere = subdiv_test::midpoint_subdivide(sphere);
  for (int i = 0; i < sphere.num_vertices(); ++i) sphere.vertices.row(i).normalize();
  const LimitSurface surface(sphere);
  for (int f = 0; f < surface.num_faces(); f += 7) {
    const SurfacePoint s{f, 0.3, 0.4};
    const Vec3 x = surface.position(s, sphere.vertices);
    const LimitCurvature c = surface.curvature(s, sphere.vertices);
    const double R = x.norm();
    EXPECT_GT(c.normal.dot(x) / R, 0.99);
    EXPECT_NEAR(c.e1.dot(c.e2), 0.0, 1e-14);
    EXPECT_NEAR(c.e1.dot(c.normal), 0.0, 1e-14);
    EXPECT_NEAR(c.shape_operator(0, 1), c.shape_operator(1, 0), 1e-12);
    // Loop's limit of a coarse sphere is not round: its curvature varies by ~20 %.
    const Eigen::Vector2d k = Eigen::SelfAdjointEigenSolver<Mat2>(c.shape_operator).eigenvalues();
    EXPECT_LT(k[1], 0.0);
    EXPECT_NEAR(0.5 * (k[0] + k[1]) * R, -1.0, 0.3);
    // Consistency: II in (u,v) equals Aᵀ S A with A the tangent coordinates in (e1, e2).
    const LimitFrame fr = surface.evaluate(s, sphere.vertices);
    Mat2 A;
    A << c.e1.dot(fr.xu), c.e1.dot(fr.xv), c.e2.dot(fr.xu), c.e2.dot(fr.xv);
    EXPECT_LT((A.transpose() * c.shape_operator * A - c.second_fundamental_form).norm(),
              1e-12 * c.second_fundamental_form.norm());
    EXPECT_LT(
        (surface.second_fundamental_form(s, sphere.vertices) - c.second_fundamental_form).norm(),
        1e-15);
  }
}

}  // namespace tightfit::limit_continuity_test
