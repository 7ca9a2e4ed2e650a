#include "tightfit/physics/neo_hookean_energy.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "physics_test_util.hpp"
#include "support/energy_assembly.hpp"
#include "support/finite_difference.hpp"
#include "tightfit/common/error.hpp"
#include "tightfit/physics/assembly.hpp"

namespace tightfit::test::neo_hookean_energy_test {

struct Cube {
  Points3 rest;
  Tetrahedra tets;
  Cube() { unit_cube_tets(rest, tets); }
};

TEST(NeoHookeanEnergy, MaterialConstantsFromYoungAndPoisson) {
  const NeoHookeanMaterial m;  // paper defaults
  EXPECT_DOUBLE_EQ(m.youngs_modulus, 24.78e3);
  EXPECT_DOUBLE_EQ(m.poisson_ratio, 0.49);
  EXPECT_NEAR(m.shear_modulus(), 24.78e3 / 2.98, 1e-9);
  EXPECT_NEAR(m.bulk_modulus(), 24.78e3 / 0.06, 1e-6);
}

TEST(NeoHookeanEnergy, ZeroEnergyAndForceAtRestAndUnderRigidMotion) {
  Cube c;
  const NeoHookeanEnergy energy(c.rest, c.tets);
  const VecX x0 = flatten(c.rest);
  EXPECT_NEAR(energy.value(x0), 0.0, 1e-10);
  EXPECT_LT(test::energy_gradient(energy, x0).norm(), 1e-9);

  Points3 moved =
      (c.rest * random_rotation(3).transpose()).rowwise() + Eigen::RowVector3d(1, -2, 3);
  const VecX x1 = flatten(moved);
  EXPECT_NEAR(energy.value(x1), 0.0, 1e-9);
  EXPECT_LT(test::energy_gradient(energy, x1).norm(), 1e-8);
}

TEST(NeoHookeanEnergy, RotationInvariantValueAndCovariantGradient) {
  Cube c;
  const NeoHookeanEnergy energy(c.rest, c.tets);
  const VecX x = flatten(c.rest) + 0.15 * random_vector(24, 5);
  const Mat3 R = random_rotation(7);
  Points3 p = Eigen::Map<const Points3>(x.data(), 8, 3);
  Points3 pr = p * R.transpose();
  const VecX xr = flatten(pr);
  EXPECT_NEAR(energy.value(xr), energy.value(x), 1e-10 * std::abs(energy.value(x)));
  const VecX g = test::energy_gradient(energy, x);
  const VecX gr = test::energy_gradient(energy, xr);
  for (int i = 0; i < 8; ++i)
    EXPECT_LT((gr.segment<3>(3 * i) - R * g.segment<3>(3 * i)).norm(), 1e-9 * g.norm());
}

TEST(NeoHookeanEnergy, SmallStrainMatchesLinearElasticity) {
  // Uniaxial stress state: F = diag(1+e, 1-nu e, 1-nu e) has energy density E e²/2.
  Cube c;
  const NeoHookeanEnergy energy(c.rest, c.tets);
  const double e = 1e-5;
  const double nu = energy.material().poisson_ratio;
  Points3 p = c.rest;
  p.col(0) *= 1 + e;
  p.col(1) *= 1 - nu * e;
  p.col(2) *= 1 - nu * e;
  EXPECT_NEAR(energy.value(flatten(p)) / (0.5 * energy.material().youngs_modulus * e * e), 1.0,
              1e-3);
}

TEST(NeoHookeanEnergy, DerivativesMatchFiniteDifferences) {
  Cube c;
  const NeoHookeanEnergy energy(c.rest, c.tets, NeoHookeanMaterial{1.0, 0.3});
  for (unsigned seed = 1; seed <= 5; ++seed) {
    const VecX x = flatten(c.rest) + 0.2 * random_vector(24, seed);
    ASSERT_TRUE(std::isfinite(energy.value(x)));
    const VecX g = test::energy_gradient(energy, x);
    EXPECT_LT(
        check_gradient([&](const VecX& y) { return energy.value(y); }, g, x, 1e-4).relative_error,
        1e-6);
    const MatX H = MatX(test::energy_hessian(energy, x));
    EXPECT_LT(
        check_hessian([&](const VecX& y) { return test::energy_gradient(energy, y); }, H, x, 1e-4)
            .relative_error,
        1e-6);
    EXPECT_LT((H - H.transpose()).norm(), 1e-12 * H.norm());
  }
}

TEST(NeoHookeanEnergy, ElementHessiansSumToTheHessian) {
  Cube c;
  const NeoHookeanEnergy energy(c.rest, c.tets);
  const VecX x = flatten(c.rest) + 0.3 * random_vector(24, 12);
  ASSERT_TRUE(std::isfinite(energy.value(x)));
  for (const bool project : {false, true}) {
    const MatX H = MatX(test::energy_hessian(energy, x, project));
    const MatX sum = test::element_hessian_sum(energy, x, project);
    ASSERT_EQ(sum.rows(), 24);
    EXPECT_LT((sum - H).norm(), 1e-13 * H.norm());
  }
}

TEST(NeoHookeanEnergy, ProjectedHessianIsPositiveSemiDefinite) {
  Cube c;
  const NeoHookeanEnergy energy(c.rest, c.tets);
  const VecX x = flatten(c.rest) + 0.3 * random_vector(24, 11);
  ASSERT_TRUE(std::isfinite(energy.value(x)));
  const MatX H = MatX(test::energy_hessian(energy, x, true));
  Eigen::SelfAdjointEigenSolver<MatX> eig(H);
  EXPECT_GT(eig.eigenvalues().minCoeff(), -1e-9 * eig.eigenvalues().maxCoeff());
}

TEST(NeoHookeanEnergy, InvertedElementHasInfiniteEnergy) {
  Cube c;
  const NeoHookeanEnergy energy(c.rest, c.tets);
  Points3 p = c.rest;
  p.col(2) *= -1.0;  // mirror: every tet inverted
  EXPECT_EQ(energy.value(flatten(p)), std::numeric_limits<double>::infinity());
  VecX g = VecX::Zero(24);
  EXPECT_THROW(energy.add_gradient(flatten(p), g), SolverError);
}

TEST(NeoHookeanEnergy, RejectsBadInput) {
  Cube c;
  Tetrahedra flipped = c.tets;
  flipped.col(0).swap(flipped.col(1));
  EXPECT_THROW(NeoHookeanEnergy(c.rest, flipped), InputError);
  Tetrahedra out_of_range = c.tets;
  out_of_range(2, 3) = 8;
  EXPECT_THROW(NeoHookeanEnergy(c.rest, out_of_range), InputError);
  EXPECT_THROW(NeoHookeanEnergy(c.rest, c.tets, NeoHookeanMaterial{1.0, 0.5}), InputError);
}

}  // namespace tightfit::test::neo_hookean_energy_test
