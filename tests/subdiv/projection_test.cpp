#include <gtest/gtest.h>

#include <random>

#include "subdiv/test_meshes.hpp"
#include "tightfit/geometry/mesh_io.hpp"
#include "tightfit/subdiv/limit_projector.hpp"
#include "tightfit/subdiv/limit_surface.hpp"

namespace tightfit::projection_test {

using subdiv_test::irregular_meshes;
using subdiv_test::random_point;

/// A body-sized version of a test mesh: about 0.4 m across.
TriMesh body_sized(TriMesh m) {
  const double size = (m.vertices.colwise().maxCoeff() - m.vertices.colwise().minCoeff()).norm();
  m.vertices *= 0.4 / size;
  return m;
}

TEST(LimitSurfaceProjection, PointsOffsetAlongTheNormalProjectBack) {
  for (const auto& [name, raw] : irregular_meshes()) {
    const TriMesh mesh = body_sized(raw);
    const LimitSurface surface(mesh);
    const double edge =
        (mesh.vertices.row(mesh.faces(0, 0)) - mesh.vertices.row(mesh.faces(0, 1))).norm();
    std::mt19937 rng(21);
    std::uniform_real_distribution<double> offset(-0.05 * edge, 0.05 * edge);
    for (int k = 0; k < 200; ++k) {
      const SurfacePoint s = random_point(rng, surface.num_faces());
      const Vec3 x = surface.position(s, mesh.vertices);
      const Vec3 p = x + offset(rng) * surface.normal(s, mesh.vertices);
      const SurfacePoint q = surface.project(p, mesh.vertices);
      EXPECT_LT((surface.position(q, mesh.vertices) - x).norm(), 1e-9)
          << name << " face " << s.face << " (" << s.u << ", " << s.v << ") → face " << q.face
          << " (" << q.u << ", " << q.v << ")";
    }
  }
}

TEST(LimitSurfaceProjection, HintsAndPointsNearExtraordinaryVertices) {
  const TriMesh mesh = body_sized(irregular_meshes()[3].second);
  const LimitSurface surface(mesh);
  const LimitProjector projector(surface, mesh.vertices);
  std::mt19937 rng(22);
  std::uniform_real_distribution<double> small(1e-6, 0.02), offset(-2e-3, 2e-3), angle(0.0, 6.283);
  int near_ev = 0, closer = 0;
  for (int f = 0; f < surface.num_faces(); ++f) {
    for (int corner = 0; corner < 3; ++corner) {
      // Close to each corner, including inside the Gregory regions (2^-8).
      const double a = small(rng), b = small(rng) * 0.5;
      double bary[3];
      bary[corner] = 1 - a - b;
      bary[(corner + 1) % 3] = a;
      bary[(corner + 2) % 3] = b;
      const SurfacePoint s{f, bary[1], bary[2]};
      near_ev += surface.is_irregular(f);
      const Vec3 x = surface.position(s, mesh.vertices);
      const Vec3 n = surface.normal(s, mesh.vertices);
      // Within 10 µm of the surface, x is the closest point: it must be recovered.
      const Vec3 p = x + 1e-5 * offset(rng) / 2e-3 * n;
      EXPECT_LT((surface.position(projector.project(p), mesh.vertices) - x).norm(), 1e-9)
          << "face " << f << " corner " << corner;
      const double t = angle(rng);
      const SurfacePoint hint = surface.walk(s, 0.1 * Vec2(std::cos(t), std::sin(t))).end;
      EXPECT_LT(
          (surface.position(surface.project(p, mesh.vertices, hint), mesh.vertices) - x).norm(),
          1e-9)
          << "hinted, face " << f << " corner " << corner;
      // Up to 2 mm inside, the strongly curved limit near a cube corner can have a
      // closer point than x: the projection returns x or a point closer than x.
      const Vec3 p_far = x + offset(rng) * n;
      const Vec3 x_far = surface.position(projector.project(p_far), mesh.vertices);
      if ((x_far - x).norm() > 1e-9) {
        EXPECT_LT((x_far - p_far).norm(), (x - p_far).norm())
            << "face " << f << " corner " << corner;
        ++closer;
      }
    }
  }
  EXPECT_LT(closer, surface.num_faces() / 4);
  EXPECT_GT(near_ev, 0);
}

TEST(LimitSurfaceProjection, FollowsADeformedBody) {
  // The same surface object serves deformed positions: the projection cache is keyed
  // by the positions' contents.
  const TriMesh mesh = body_sized(irregular_meshes()[2].second);
  const LimitSurface surface(mesh);
  Points3 deformed = mesh.vertices;
  deformed.col(0) *= 1.3;
  deformed.col(2) *= 0.8;
  std::mt19937 rng(23);
  for (int k = 0; k < 50; ++k) {
    const SurfacePoint s = random_point(rng, surface.num_faces());
    const Points3& y = (k % 2) ? deformed : mesh.vertices;
    const Vec3 x = surface.position(s, y);
    const Vec3 p = x + 1e-3 * surface.normal(s, y);
    EXPECT_LT((surface.position(surface.project(p, y), y) - x).norm(), 1e-9);
  }
}

TEST(LimitSurfaceProjection, NeverMovesAwayFromTheStartPoint) {
  // Far from the surface Newton may stop at any local minimum, but never farther away
  // than where it started.
  const TriMesh mesh = body_sized(irregular_meshes()[0].second);
  const LimitSurface surface(mesh);
  std::mt19937 rng(24);
  std::uniform_real_distribution<double> coord(-0.5, 0.5);
  for (int k = 0; k < 50; ++k) {
    const Vec3 p(coord(rng), coord(rng), coord(rng));
    const SurfacePoint start = random_point(rng, surface.num_faces());
    const SurfacePoint q = refine_closest_point(surface, mesh.vertices, p, start);
    EXPECT_LE((surface.position(q, mesh.vertices) - p).norm(),
              (surface.position(start, mesh.vertices) - p).norm());
    // At an interior minimum the residual is normal to the surface.
    const LimitFrame fr = surface.evaluate(q, mesh.vertices);
    const Vec3 r = (fr.x - p).normalized();
    EXPECT_LT(std::abs(r.dot(fr.xu.normalized())), 1e-6);
    EXPECT_LT(std::abs(r.dot(fr.xv.normalized())), 1e-6);
  }
}

TEST(LimitSurfaceProjection, RealBodyMesh) {
  // MakeHuman legs (7672 triangles, valences 3..9): the self-test runs on a real mesh
  // and points within 1 mm of the limit surface project back.
  const TriMesh mesh = read_obj(std::string(TIGHTFIT_DATA_DIR) + "/bodies/mh_legs_male.obj");
  const LimitSurface surface(mesh);
  std::mt19937 rng(25);
  std::uniform_real_distribution<double> offset(-1e-3, 1e-3);
  int irregular = 0, not_recovered = 0;
  for (int k = 0; k < 200; ++k) {
    const SurfacePoint s = random_point(rng, surface.num_faces());
    irregular += surface.is_irregular(s.face);
    const Vec3 x = surface.position(s, mesh.vertices);
    const Vec3 p = x + offset(rng) * surface.normal(s, mesh.vertices);
    const Vec3 xq = surface.position(surface.project(p, mesh.vertices), mesh.vertices);
    const bool recovered = (xq - x).norm() < 1e-9;
    EXPECT_TRUE(recovered || (xq - p).norm() < (x - p).norm()) << "face " << s.face;
    not_recovered += !recovered;
  }
  EXPECT_GT(irregular, 0);
  EXPECT_LE(not_recovered, 4);
}

}  // namespace tightfit::projection_test
