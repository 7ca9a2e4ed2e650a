#include <gtest/gtest.h>

#include <random>

#include "subdiv/test_meshes.hpp"
#include "support/finite_difference.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/subdiv/limit_surface.hpp"
#include "tightfit/subdiv/patch_tree_rotation.hpp"

namespace tightfit::limit_stencil_test {

using subdiv_test::irregular_meshes;
using subdiv_test::random_smooth_point;

/// Dense stencil (one weight per control vertex) of one derivative.
Eigen::VectorXd dense(const LimitWeights& w, const std::vector<double>& a, int n) {
  Eigen::VectorXd d = Eigen::VectorXd::Zero(n);
  for (int k = 0; k < w.size(); ++k)
    d[w.index[static_cast<std::size_t>(k)]] += a[static_cast<std::size_t>(k)];
  return d;
}

TEST(LimitSurface, WeightsSumToOneAndDerivativesToZero) {
  for (const auto& [name, mesh] : irregular_meshes()) {
    const LimitSurface surface(mesh);
    std::mt19937 rng(1);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    LimitWeights w;
    for (int f = 0; f < surface.num_faces(); ++f) {
      double u = unit(rng), v = unit(rng);
      if (u + v > 1) u = 1 - u, v = 1 - v;
      surface.weights({f, u, v}, w);
      double sp = 0, sdu = 0, sdv = 0, suu = 0, suv = 0, svv = 0;
      for (int k = 0; k < w.size(); ++k) {
        sp += w.p[k], sdu += w.du[k], sdv += w.dv[k], suu += w.duu[k], suv += w.duv[k],
            svv += w.dvv[k];
      }
      EXPECT_NEAR(sp, 1.0, 1e-12) << name << " face " << f;
      for (double s : {sdu, sdv, suu, suv, svv}) EXPECT_NEAR(s, 0.0, 1e-9) << name << " face " << f;
      // Unique indices that include the face's own corners.
      std::vector<int> sorted = w.index;
      std::sort(sorted.begin(), sorted.end());
      EXPECT_TRUE(std::adjacent_find(sorted.begin(), sorted.end()) == sorted.end()) << name;
      for (int k = 0; k < 3; ++k) {
        EXPECT_TRUE(std::binary_search(sorted.begin(), sorted.end(), mesh.faces(f, k))) << name;
      }
    }
  }
}

TEST(LimitSurface, AccumulatedWeightsReproduceEvaluateOnTinyMeshes) {
  // On a tetrahedron and an octahedron a face's control points repeat base vertices.
  for (const TriMesh& mesh : {subdiv_test::tetrahedron(), subdiv_test::octahedron()}) {
    const LimitSurface surface(mesh);
    LimitWeights w;
    for (int f = 0; f < surface.num_faces(); ++f) {
      const SurfacePoint s{f, 0.3, 0.25};
      surface.weights(s, w);
      const LimitFrame fr = surface.evaluate(s, mesh.vertices);
      Vec3 x = Vec3::Zero(), xu = Vec3::Zero(), xvv = Vec3::Zero();
      double sum = 0;
      for (int k = 0; k < w.size(); ++k) {
        const Vec3 y = mesh.vertices.row(w.index[k]).transpose();
        x += w.p[k] * y;
        xu += w.du[k] * y;
        xvv += w.dvv[k] * y;
        sum += w.p[k];
      }
      EXPECT_NEAR(sum, 1.0, 1e-12);
      EXPECT_LT((x - fr.x).norm(), 1e-12);
      EXPECT_LT((xu - fr.xu).norm(), 1e-12);
      EXPECT_LT((xvv - fr.xvv).norm(), 1e-10);
      EXPECT_LE(w.size(), mesh.num_vertices());
    }
  }
}

TEST(LimitSurface, CornersOfRegularAndIrregularFacesAreDetected) {
  const auto meshes = irregular_meshes();
  const LimitSurface ico(meshes[0].second);
  for (int f = 0; f < ico.num_faces(); ++f) EXPECT_TRUE(ico.is_irregular(f));
  const LimitSurface cube(meshes[2].second);
  int regular = 0, irregular = 0;
  for (int f = 0; f < cube.num_faces(); ++f) (cube.is_irregular(f) ? irregular : regular)++;
  // The middle child of every split face has three new (valence-6) corners.
  EXPECT_GE(regular, cube.num_faces() / 4);
  EXPECT_GT(irregular, 0);
}

/// Weight stencils of first and second derivatives against fourth-order central
/// differences of the position and first-derivative stencils (exact for the quartic
/// box-spline pieces, so only round-off remains), on regular and irregular faces.
void check_derivative_stencils(const LimitSurface& surface, SurfacePoint s, const char* name) {
  const int n = surface.num_control_vertices();
  LimitWeights w;
  surface.weights(s, w);
  auto stencil = [&](const Eigen::VectorXd& uv, int which) {
    LimitWeights q;
    surface.weights({s.face, uv[0], uv[1]}, q);
    const std::vector<double>* arrays[3] = {&q.p, &q.du, &q.dv};
    return dense(q, *arrays[which], n);
  };
  const Eigen::VectorXd uv = Eigen::Vector2d(s.u, s.v);
  const double h = 1e-4;
  Eigen::MatrixXd first(n, 2);
  first << dense(w, w.du, n), dense(w, w.dv, n);
  const auto c1 =
      test::check_jacobian([&](const Eigen::VectorXd& x) { return stencil(x, 0); }, first, uv, h);
  EXPECT_LT(c1.relative_error, 1e-6)
      << name << " face " << s.face << " (" << s.u << ", " << s.v << ")";
  Eigen::MatrixXd second_u(n, 2), second_v(n, 2);
  second_u << dense(w, w.duu, n), dense(w, w.duv, n);
  second_v << dense(w, w.duv, n), dense(w, w.dvv, n);
  const auto cu = test::check_jacobian([&](const Eigen::VectorXd& x) { return stencil(x, 1); },
                                       second_u, uv, h);
  const auto cv = test::check_jacobian([&](const Eigen::VectorXd& x) { return stencil(x, 2); },
                                       second_v, uv, h);
  const bool rotated = surface.in_rotated_subpatch(s.face, s.u, s.v);
  EXPECT_LT(cu.relative_error, 1e-6)
      << name << " face " << s.face << " (" << s.u << ", " << s.v << ") rotated " << rotated;
  EXPECT_LT(cv.relative_error, 1e-6)
      << name << " face " << s.face << " (" << s.u << ", " << s.v << ") rotated " << rotated;
}

TEST(LimitSurface, DerivativeStencilsMatchFiniteDifferences) {
  for (const auto& [name, mesh] : irregular_meshes()) {
    const LimitSurface surface(mesh);
    std::mt19937 rng(2);
    int regular = 0, irregular = 0, rotated = 0;
    for (int k = 0; k < 150; ++k) {
      const SurfacePoint s = random_smooth_point(rng, surface.num_faces(), 8, 3e-4);
      check_derivative_stencils(surface, s, name);
      (surface.is_irregular(s.face) ? irregular : regular)++;
      rotated += surface.in_rotated_subpatch(s.face, s.u, s.v);
    }
    EXPECT_GT(irregular, 0) << name;
    EXPECT_GT(rotated, 0) << name;
  }
}

TEST(LimitSurface, SecondDerivativesNearExtraordinaryVerticesMatchFiniteDifferences) {
  // Rotated (middle) and non-rotated children of the sub-triangle at each corner, at
  // every depth down to the Gregory region, on every irregular face.
  const auto meshes = irregular_meshes();
  const LimitSurface surface(meshes[3].second);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> weight(0.2, 1.0);
  auto random_in = [&](const Eigen::Matrix3d& corners) {  // columns: barycentric corners
    const Eigen::Vector3d w = Eigen::Vector3d(weight(rng), weight(rng), weight(rng)).normalized();
    return Eigen::Vector3d(corners * (w / w.sum()));
  };
  int rotated = 0, total = 0;
  for (int f = 0; f < surface.num_faces(); ++f) {
    if (!surface.is_irregular(f)) continue;
    for (int corner = 0; corner < 3; ++corner) {
      for (int depth = 1; depth < 8; ++depth) {
        const double S = std::ldexp(1.0, 1 - depth);  // size of the parent corner triangle
        Eigen::Matrix3d middle, side;                 // barycentrics relative to `corner`
        middle << 1 - S / 2, 1 - S / 2, 1 - S, S / 2, 0, S / 2, 0, S / 2, S / 2;
        side << 1 - S / 2, 1 - S, 1 - S, S / 2, S, S / 2, 0, 0, S / 2;
        for (const Eigen::Matrix3d& tri : {middle, side}) {
          const Eigen::Vector3d local = random_in(tri);
          Eigen::Vector3d b;
          for (int k = 0; k < 3; ++k) b[(corner + k) % 3] = local[k];
          const SurfacePoint s{f, b[1], b[2]};
          rotated += surface.in_rotated_subpatch(f, s.u, s.v);
          ++total;
          check_derivative_stencils(surface, s, "perturbed_cube");
        }
      }
    }
  }
  EXPECT_GT(rotated, total / 6);
}

TEST(LimitSurface, PatchTreeRotationFollowsTheTreeSearch) {
  const unsigned all = 7u, none = 0u;
  EXPECT_TRUE(patch_tree_rotated(0.3, 0.3, none, 8));    // depth-1 middle triangle
  EXPECT_FALSE(patch_tree_rotated(0.1, 0.1, none, 8));   // regular corner-0 leaf at depth 1
  EXPECT_TRUE(patch_tree_rotated(0.1, 0.1, all, 8));     // depth-3 middle at an EV
  EXPECT_FALSE(patch_tree_rotated(0.3, 0.1, all, 8));    // depth-2 corner-1 child of corner 0
  EXPECT_TRUE(patch_tree_rotated(0.2, 0.2, all, 8));     // depth-2 middle
  EXPECT_FALSE(patch_tree_rotated(0.6, 0.1, all, 8));    // depth-2 child of corner 1
  EXPECT_FALSE(patch_tree_rotated(1e-4, 1e-4, all, 8));  // the Gregory leaf
  EXPECT_TRUE(patch_tree_rotated(0.5 * 0.75 * 0.01, 0.5 * 0.75 * 0.01, all, 8));
  // Ties go the way Bfr's search goes: u = 0.5 belongs to the corner-1 child.
  EXPECT_FALSE(patch_tree_rotated(0.5, 0.0, all, 8));
  EXPECT_TRUE(patch_tree_rotated(0.25, 0.25, all, 8));
}

TEST(LimitSurface, SignFixIsAppliedOnlyWhereTheSelfTestFoundTheBug) {
  const auto meshes = irregular_meshes();
  const LimitSurface fixed(meshes[1].second);
  LimitSurfaceOptions raw_options;
  raw_options.self_test = false;
  const LimitSurface raw(meshes[1].second, raw_options);
  EXPECT_FALSE(raw.second_derivative_fix_active());
  LimitWeights a, b;
  int rotated_checked = 0;
  for (int f = 0; f < fixed.num_faces(); ++f) {
    for (const Vec2& uv : {Vec2(0.3, 0.3), Vec2(0.1, 0.7), Vec2(0.15, 0.15), Vec2(0.35, 0.05)}) {
      fixed.weights({f, uv[0], uv[1]}, a);
      raw.weights({f, uv[0], uv[1]}, b);
      const bool flip =
          fixed.second_derivative_fix_active() && fixed.in_rotated_subpatch(f, uv[0], uv[1]);
      rotated_checked += flip;
      const double sign = flip ? -1.0 : 1.0;
      for (int k = 0; k < a.size(); ++k) {
        EXPECT_EQ(a.p[k], b.p[k]);
        EXPECT_EQ(a.du[k], b.du[k]);
        EXPECT_EQ(a.duu[k], sign * b.duu[k]);
        EXPECT_EQ(a.duv[k], sign * b.duv[k]);
        EXPECT_EQ(a.dvv[k], sign * b.dvv[k]);
      }
    }
  }
  if (fixed.second_derivative_fix_active()) {
    EXPECT_GT(rotated_checked, 0);
    // The raw second derivatives are then wrong on a rotated sub-triangle.
    const SurfacePoint s{0, 0.3, 0.3};
    ASSERT_TRUE(raw.is_irregular(0));
    raw.weights(s, b);
    LimitWeights p1, m1;
    const double h = 1e-6;
    raw.weights({0, s.u + h, s.v}, p1);
    raw.weights({0, s.u - h, s.v}, m1);
    double err = 0, norm = 0;
    for (int k = 0; k < b.size(); ++k) {
      const double fd = (p1.du[k] - m1.du[k]) / (2 * h);
      err += (fd - b.duu[k]) * (fd - b.duu[k]);
      norm += fd * fd;
    }
    EXPECT_GT(std::sqrt(err / norm), 1.0);
  }
}

TEST(LimitSurface, RejectsOpenMeshesAndBadOptions) {
  TriMesh open = subdiv_test::octahedron();
  open.faces.conservativeResize(open.num_faces() - 1, 3);
  EXPECT_THROW(LimitSurface{open}, InputError);
  TriMesh flipped = subdiv_test::octahedron();
  std::swap(flipped.faces(0, 1), flipped.faces(0, 2));
  EXPECT_THROW(LimitSurface{flipped}, InputError);
  LimitSurfaceOptions bad;
  bad.approx_level_sharp = 4;
  EXPECT_THROW(LimitSurface(subdiv_test::octahedron(), bad), std::invalid_argument);
  const LimitSurface ok(subdiv_test::octahedron());
  LimitWeights w;
  EXPECT_THROW(ok.weights({0, 0.7, 0.7}, w), std::invalid_argument);
  EXPECT_THROW(ok.weights({8, 0.1, 0.1}, w), std::invalid_argument);
}

}  // namespace tightfit::limit_stencil_test
