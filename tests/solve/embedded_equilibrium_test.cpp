#include "tightfit/solve/embedded_equilibrium.hpp"

#include <gtest/gtest.h>

#include <random>

#include "subdiv/test_meshes.hpp"
#include "support/finite_difference.hpp"
#include "tightfit/physics/assembly.hpp"

namespace tightfit::embedded_equilibrium_test {

/// Test-only energy: springs k/2 (|x_a − x_b| − l)² between given vertex pairs.
class SpringsForTest : public Energy {
 public:
  SpringsForTest(std::vector<std::array<int, 2>> pairs, std::vector<double> rest, double k)
      : pairs_(std::move(pairs)), rest_(std::move(rest)), k_(k) {}
  std::string name() const override { return "test springs"; }
  double value(const VecX& x) const override {
    double e = 0;
    for (size_t s = 0; s < pairs_.size(); ++s) {
      const double l = (x.segment<3>(3 * pairs_[s][0]) - x.segment<3>(3 * pairs_[s][1])).norm();
      e += 0.5 * k_ * (l - rest_[s]) * (l - rest_[s]);
    }
    return e;
  }
  void add_gradient(const VecX& x, VecX& g) const override {
    for (size_t s = 0; s < pairs_.size(); ++s) {
      const Vec3 d = x.segment<3>(3 * pairs_[s][0]) - x.segment<3>(3 * pairs_[s][1]);
      const double l = d.norm();
      const Vec3 f = k_ * (l - rest_[s]) * d / l;
      g.segment<3>(3 * pairs_[s][0]) += f;
      g.segment<3>(3 * pairs_[s][1]) -= f;
    }
  }
  void add_hessian(const VecX& x, std::vector<Triplet>& H, bool psd) const override {
    for (size_t s = 0; s < pairs_.size(); ++s) {
      const Vec3 d = x.segment<3>(3 * pairs_[s][0]) - x.segment<3>(3 * pairs_[s][1]);
      const double l = d.norm();
      const Vec3 n = d / l;
      const Mat3 K =
          k_ * (n * n.transpose() + (1 - rest_[s] / l) * (Mat3::Identity() - n * n.transpose()));
      Eigen::Matrix<double, 6, 6> local;
      local << K, -K, -K, K;
      if (psd) project_psd<6>(local);
      scatter_hessian<3, 2>(pairs_[s], local, H);
    }
  }

 private:
  std::vector<std::array<int, 2>> pairs_;
  std::vector<double> rest_;
  double k_;
};

struct Scene {
  TriMesh surface;
  std::unique_ptr<LimitSurface> limit;
  std::unique_ptr<SpringsForTest> garment_springs, body_springs;
  EmbeddedState state;
  std::vector<int> pinned_body, pinned_garment;
};

/// A sphere body perturbed off its rest shape, with random garment points well inside
/// faces (so finite-difference steps stay in their faces) joined by springs.
Scene make_scene(unsigned seed) {
  Scene s;
  s.surface = subdiv_test::midpoint_subdivide(subdiv_test::icosahedron());
  s.surface.vertices *= 0.1;
  s.limit = std::make_unique<LimitSurface>(s.surface);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u01(0.1, 0.4), any(-1, 1);
  std::uniform_int_distribution<int> face(0, s.surface.num_faces() - 1);
  const int ng = 30;
  for (int i = 0; i < ng; ++i) s.state.garment.push_back({face(rng), u01(rng), u01(rng)});
  s.state.body = s.surface.vertices;
  for (int k = 0; k < s.state.body.rows(); ++k)
    s.state.body.row(k) += 0.01 * Vec3(any(rng), any(rng), any(rng)).transpose();
  std::vector<std::array<int, 2>> gp;
  std::vector<double> gl;
  for (int i = 0; i < ng; ++i) {
    gp.push_back({i, (i + 1) % ng});
    gl.push_back(0.05);
    gp.push_back({i, (i + 7) % ng});
    gl.push_back(0.08);
  }
  s.garment_springs = std::make_unique<SpringsForTest>(gp, gl, 50.0);
  std::vector<std::array<int, 2>> bp;
  std::vector<double> bl;
  for (int f = 0; f < s.surface.num_faces(); ++f)
    for (int c = 0; c < 3; ++c) {
      const int a = s.surface.faces(f, c), b = s.surface.faces(f, (c + 1) % 3);
      if (a < b) {
        bp.push_back({a, b});
        bl.push_back((s.surface.vertices.row(a) - s.surface.vertices.row(b)).norm());
      }
    }
  s.body_springs = std::make_unique<SpringsForTest>(bp, bl, 20.0);
  s.pinned_body = {0, 1, 2, 3};
  s.pinned_garment = {5};
  return s;
}

EmbeddedEquilibrium make_problem(const Scene& s) {
  EmbeddedSystemSetup setup;
  setup.surface = s.limit.get();
  setup.garment_energies = {s.garment_springs.get()};
  setup.body_energies = {s.body_springs.get()};
  setup.pinned_body = s.pinned_body;
  setup.pinned_garment = s.pinned_garment;
  setup.project_garment_hessians = false;
  return EmbeddedEquilibrium(setup, s.state);
}

TEST(EmbeddedEquilibrium, ChainRuleGradientAndHessianMatchFiniteDifferences) {
  const Scene s = make_scene(3);
  EmbeddedEquilibrium problem = make_problem(s);
  const Eigen::Index n = problem.num_dofs();
  EXPECT_EQ(n, 2 * (30 - 1) + 3 * (s.surface.num_vertices() - 4));
  const VecX g = problem.gradient();
  const SparseMatrix H = problem.hessian();
  auto energy_at = [&](const VecX& dq) {
    problem.set_step(dq, 1.0);
    return problem.energy();
  };
  auto gradient_at = [&](const VecX& dq) -> VecX {
    problem.set_step(dq, 1.0);
    return problem.gradient();
  };
  const VecX zero = VecX::Zero(n);
  EXPECT_LT(test::check_gradient(energy_at, g, zero, 1e-6).relative_error, 1e-6);
  EXPECT_LT(test::check_hessian(gradient_at, MatX(H), zero, 1e-6).relative_error, 1e-6);
}

TEST(EmbeddedEquilibrium, RefusesAStepWhoseWalkCannotBeCompleted) {
  const Scene s = make_scene(5);
  EmbeddedEquilibrium problem = make_problem(s);
  // Millions of faces in one walk: the walk gives up (LimitSurface::Walk::complete) and
  // set_step must say so instead of taking the truncated step as asked.
  VecX dq = VecX::Zero(problem.num_dofs());
  dq[0] = 3e6;
  dq[1] = 1.1e6;
  EXPECT_FALSE(problem.set_step(dq, 1.0));
  EXPECT_TRUE(problem.set_step(dq, 1e-9));
  EXPECT_TRUE(problem.set_step(dq, 0.0));
}

TEST(EmbeddedEquilibrium, HessianOperatorIsTheProductWithTheNewtonHessian) {
  const Scene s = make_scene(3);
  EmbeddedEquilibrium problem = make_problem(s);
  problem.set_step(VecX::LinSpaced(problem.num_dofs(), -1e-3, 1e-3), 1.0);
  problem.commit();
  const SparseMatrix H = problem.hessian();
  const std::optional<LinearOperator> op = problem.hessian_operator();
  ASSERT_TRUE(op.has_value());
  const VecX v = VecX::LinSpaced(problem.num_dofs(), 1.0, -2.0);
  const VecX Hv = H * v;
  EXPECT_LT(((*op)(v)-Hv).norm(), 1e-12 * Hv.norm());
}

TEST(EmbeddedEquilibrium, PositionJacobianMatchesFiniteDifferences) {
  const Scene s = make_scene(4);
  EmbeddedEquilibrium problem = make_problem(s);
  const SparseMatrix J = problem.position_jacobian();
  auto positions_at = [&](const VecX& dq) -> VecX {
    problem.set_step(dq, 1.0);
    const Points3& x = problem.garment_positions();
    return Eigen::Map<const VecX>(x.data(), x.size());
  };
  EXPECT_LT(test::check_jacobian(positions_at, MatX(J), VecX::Zero(problem.num_dofs()), 1e-6)
                .relative_error,
            1e-7);
}

TEST(EmbeddedEquilibrium, ForceNormIsTheTangentialForceInNewtons) {
  const Scene s = make_scene(5);
  EmbeddedEquilibrium problem = make_problem(s);
  const VecX g = problem.gradient();
  // Garment part: project dU/dx of each free garment vertex onto its tangent plane.
  const VecX gx = problem.garment_energy_gradient();
  double expected = 0;
  for (int i = 0; i < problem.num_garment_vertices(); ++i) {
    if (problem.garment_dof(i) < 0) continue;
    const Vec3 n = problem.garment_normal(i);
    const Vec3 f = gx.segment<3>(3 * i);
    expected += (f - f.dot(n) * n).squaredNorm();
  }
  for (int k = 0; k < static_cast<int>(s.state.body.rows()); ++k)
    if (problem.body_dof(k) >= 0) expected += g.segment<3>(problem.body_dof(k)).squaredNorm();
  EXPECT_NEAR(problem.force_norm(g), std::sqrt(expected), 1e-10 * std::sqrt(expected));
}

}  // namespace tightfit::embedded_equilibrium_test
