/// A sleeve on a soft cylinder with a pinned core (docs/design.md §7): the body's radial
/// compression against the plane-strain Lamé solution for a thick cylinder with zero
/// displacement at the core radius a and the sleeve's pressure p at the outer radius b:
///   u(r) = A (r − a²/r),  A = −p / (2(λ+μ) + 2μ a²/b²),
/// with the small-strain Lamé constants of the Neo-Hookean body (λ = κ − 2μ/3).
/// Also checks that Newton converges quadratically on the coupled system.
#include <gtest/gtest.h>

#include <cstdio>

#include "tightfit/body/body_builder.hpp"
#include "tightfit/body/generators.hpp"
#include "tightfit/body/tetrahedralize.hpp"
#include "tightfit/garment/primitive_garments.hpp"
#include "tightfit/solve/garment_simulation.hpp"

namespace tightfit::soft_cylinder_test {

struct SoftCylinder {
  double b = 0.05;     // outer radius
  double core = 0.02;  // core radius a: pinned below b − a of soft tissue
  Body body;
  std::unique_ptr<LimitSurface> surface;
};

SoftCylinder make_soft_cylinder(double edge) {
  SoftCylinder c;
  CylinderParams cyl;
  cyl.radius = c.b;
  cyl.length = 0.4;
  cyl.edge_length = edge;
  VolumeOptions volume = default_volume_options(edge);
  // An exact core: the cylinder r = a built into the tet mesh and pinned with all it holds.
  volume.core.soft_tissue.reset();
  volume.core.embedded_core = cylinder_surface(cylinder_core(cyl, c.core));
  volume.quality.max_volume = regular_tet_volume(edge);  // as fine inside as on the surface
  c.body = cylinder_body(cyl, volume);
  c.surface = std::make_unique<LimitSurface>(c.body.surface);
  return c;
}

SleeveParams covering_sleeve(const SoftCylinder& c) {
  SleeveParams s;
  s.radius = c.b;
  s.axial_begin = -0.19;
  s.axial_end = 0.19;
  s.hoop_scale = 0.97;
  s.axial_scale = 0.99;
  s.edge_length = 0.012;
  s.pin_first_ring = s.pin_last_ring = true;
  return s;
}

/// The covering sleeve as a garment on the cylinder.
Garment covering_garment(const SoftCylinder& c) {
  return make_sleeve(covering_sleeve(c), *c.surface, c.body.surface.vertices);
}

TEST(SoftCylinderSleeveSlow, RadialCompressionFollowsLame) {
  SoftCylinder c = make_soft_cylinder(0.008);
  SimulationMaterials m;
  m.body.poisson_ratio = 0.3;  // linear tets lock as ν → 0.5; the check is on elasticity
  GarmentSimulation sim(c.body, *c.surface, covering_garment(c), m);
  const NewtonReport report = sim.solve();
  ASSERT_TRUE(report.converged);
  const FitAnalysis fit = sim.analyze();
  // Mean pressure and radial displacement in the middle third (z in ±0.04 m).
  const Points3& x = sim.garment_positions();
  double p = 0, n = 0;
  for (Eigen::Index e = 0; e < sim.garment().topology->garment_triangles.rows(); ++e) {
    const double z = (x(sim.garment().topology->garment_triangles(e, 0), 2));
    if (std::abs(z) < 0.04) {
      p += fit.pressure_mid_edge[e];
      n += 1;
    }
  }
  p /= n;
  double u = 0, m_count = 0;
  const Points3& y = sim.body_positions();
  for (int k = 0; k < c.body.num_surface_vertices(); ++k) {
    const Vec3 rest = c.body.surface.vertices.row(k).transpose();
    if (std::abs(rest.z()) < 0.04 && std::hypot(rest.x(), rest.y()) > 0.9 * c.b) {
      const Vec3 dir = Vec3(rest.x(), rest.y(), 0).normalized();
      u += (y.row(k).transpose() - rest).dot(dir);
      m_count += 1;
    }
  }
  u /= m_count;
  // The pinned core's effective radius: the mean radius of the outermost pinned layer.
  double core_radius = 0;
  for (int k : c.body.pinned) {
    const Vec3 r = c.body.volume.vertices.row(k).transpose();
    if (std::abs(r.z()) < 0.1) core_radius = std::max(core_radius, std::hypot(r.x(), r.y()));
  }
  std::printf("soft cylinder: outermost pinned vertex at r = %.4f m (nominal core %.4f m)\n",
              core_radius, c.core);
  const double mu = m.body.shear_modulus();
  const double lambda = m.body.bulk_modulus() - 2.0 * mu / 3.0;
  const double a = c.core, b = c.b;
  const double A = -p / (2 * (lambda + mu) + 2 * mu * a * a / (b * b));
  const double u_lame = A * (b - a * a / b);
  std::printf(
      "soft cylinder: p = %.1f Pa, radial displacement %.4e m vs Lamé %.4e m (%.2f %%), "
      "%d Newton iterations\n",
      p, u, u_lame, 100 * (u / u_lame - 1), report.iterations);
  // Measured −1.40 % at 8 mm with the exact embedded core (3.95 % with a core pinned by
  // depth, whose jagged boundary lies anywhere within one element of r = a).
  EXPECT_NEAR(u / u_lame, 1.0, 0.03);
}

TEST(SoftCylinderSleeveSlow, NewtonConvergesQuadratically) {
  SoftCylinder c = make_soft_cylinder(0.012);
  SimulationMaterials m;
  GarmentSimulation sim(c.body, *c.surface, covering_garment(c), m);
  const NewtonReport r = sim.solve(ChordSteps{});  // plain Newton: every step factorizes
  ASSERT_TRUE(r.converged);
  // Once the residual is small, each step of the coupled solve squares it (up to a
  // constant); the steps before it relaxed the garment on the still body.
  int quadratic = 0;
  for (auto k = static_cast<size_t>(r.garment_first_iterations); k + 1 < r.history.size(); ++k) {
    const double rk = r.history[k].force_norm / sim.force_scale();
    const double rk1 = r.history[k + 1].force_norm / sim.force_scale();
    std::printf("iteration %zu: relative residual %.3e\n", k, rk);
    if (rk < 1e-2 && rk1 > 1e-13) {
      EXPECT_LT(rk1, 100 * rk * rk) << "iteration " << k;
      ++quadratic;
    }
  }
  EXPECT_GE(quadratic, 1);
}

TEST(SoftCylinderSleeveSlow, TheDefaultSolveReusesFactorizationsForTheSameEquilibrium) {
  SoftCylinder c = make_soft_cylinder(0.02);
  SimulationMaterials m;
  GarmentSimulation plain(c.body, *c.surface, covering_garment(c), m);
  GarmentSimulation reusing(c.body, *c.surface, covering_garment(c), m);
  const NewtonReport p = plain.solve(ChordSteps{});
  const NewtonReport r = reusing.solve();
  ASSERT_TRUE(p.converged);
  ASSERT_TRUE(r.converged);
  std::printf("plain Newton: %d steps, %d factorizations; default: %d steps (%d chord), %d\n",
              p.iterations, p.factorizations, r.iterations, r.chord_steps, r.factorizations);
  EXPECT_GT(r.chord_steps, 0);
  EXPECT_LT(r.factorizations, p.factorizations);
  const double garment =
      (plain.garment_positions() - reusing.garment_positions()).cwiseAbs().maxCoeff();
  const double body = (plain.body_positions() - reusing.body_positions()).cwiseAbs().maxCoeff();
  std::printf("largest difference: garment %.3e m, body %.3e m\n", garment, body);
  EXPECT_LT(garment, 1e-6);
  EXPECT_LT(body, 1e-6);
}

// A cold start relaxes the garment on the still body first (cheap: the garment's DOFs
// only), then solves the coupled system; it reaches the equilibrium of the solve without
// that stage. A warm start with a held factorization, and a rigid body, skip the stage.
TEST(SoftCylinderSleeveSlow, AColdStartRelaxesTheGarmentOnTheStillBodyFirst) {
  SoftCylinder c = make_soft_cylinder(0.02);
  SimulationMaterials m;
  GarmentSimulation staged(c.body, *c.surface, covering_garment(c), m);
  GarmentSimulation direct(c.body, *c.surface, covering_garment(c), m);
  ASSERT_TRUE(staged.garment_first());
  direct.set_garment_first(false);
  const NewtonReport s = staged.solve();
  const NewtonReport d = direct.solve();
  ASSERT_TRUE(s.converged);
  ASSERT_TRUE(d.converged);
  std::printf("staged: %d steps (%d body held), %d factorizations; direct: %d steps, %d\n",
              s.iterations, s.garment_first_iterations, s.factorizations, d.iterations,
              d.factorizations);
  EXPECT_GT(s.garment_first_iterations, 0);
  EXPECT_EQ(d.garment_first_iterations, 0);
  ASSERT_FALSE(s.history.empty());
  EXPECT_TRUE(s.history.front().body_held);
  EXPECT_FALSE(s.history.back().body_held);
  EXPECT_LE(s.final_force_norm, s.tolerance);
  const double garment =
      (staged.garment_positions() - direct.garment_positions()).cwiseAbs().maxCoeff();
  const double body = (staged.body_positions() - direct.body_positions()).cwiseAbs().maxCoeff();
  EXPECT_LT(garment, 1e-6);
  EXPECT_LT(body, 1e-6);

  // From the equilibrium with its factorization held: no first stage.
  SparseCholesky held;
  staged.newton().swap_factorization(held);
  const NewtonReport warm = staged.solve({&held, true});
  EXPECT_EQ(warm.garment_first_iterations, 0);

  SimulationMaterials rigid = m;
  rigid.rigid_body = true;
  GarmentSimulation on_rigid(c.body, *c.surface, covering_garment(c), rigid);
  EXPECT_EQ(on_rigid.solve().garment_first_iterations, 0);
}

// A warm start after a large change of the rest shape: the predictor step from the held
// factorization falls short, so the garment is relaxed on the still body before the
// coupled solve goes on; the same equilibrium as the coupled solve alone.
TEST(SoftCylinderSleeveSlow, AWarmStartWhosePredictorFallsShortRelaxesTheGarmentFirst) {
  SoftCylinder c = make_soft_cylinder(0.02);
  SimulationMaterials m;
  GarmentSimulation staged(c.body, *c.surface, covering_garment(c), m);
  GarmentSimulation direct(c.body, *c.surface, covering_garment(c), m);
  direct.set_garment_first(false);
  ASSERT_TRUE(staged.solve().converged);
  direct.set_state(staged.problem().state());
  SparseCholesky staged_held, direct_held;
  ASSERT_TRUE(staged_held.factorize(staged.problem().hessian()));
  ASSERT_TRUE(direct_held.factorize(direct.problem().hessian()));

  const Points2 tighter = 0.85 * staged.rest_positions();
  staged.set_rest_positions(tighter);
  direct.set_rest_positions(tighter);
  const NewtonReport s = staged.solve({&staged_held, true});
  const NewtonReport d = direct.solve({&direct_held, true});
  ASSERT_TRUE(s.converged);
  ASSERT_TRUE(d.converged);
  std::printf("staged: %d steps (%d body held), %d factorizations; direct: %d steps, %d\n",
              s.iterations, s.garment_first_iterations, s.factorizations, d.iterations,
              d.factorizations);
  EXPECT_FALSE(s.stopped_after_predictor);
  ASSERT_GT(s.garment_first_iterations, 0);
  EXPECT_EQ(d.garment_first_iterations, 0);
  // The predictor (coupled, with the held factorization), the garment alone, the rest.
  ASSERT_GE(s.history.size(), 3u);
  EXPECT_TRUE(s.history.front().chord);
  EXPECT_FALSE(s.history.front().body_held);
  EXPECT_TRUE(s.history[1].body_held);
  EXPECT_FALSE(s.history.back().body_held);
  int held_steps = 0;
  for (const NewtonIteration& it : s.history) held_steps += it.body_held ? 1 : 0;
  EXPECT_EQ(held_steps, s.garment_first_iterations);
  const double garment =
      (staged.garment_positions() - direct.garment_positions()).cwiseAbs().maxCoeff();
  const double body = (staged.body_positions() - direct.body_positions()).cwiseAbs().maxCoeff();
  std::printf("largest difference: garment %.3e m, body %.3e m\n", garment, body);
  EXPECT_LT(garment, 1e-6);
  EXPECT_LT(body, 1e-6);
}

}  // namespace tightfit::soft_cylinder_test
