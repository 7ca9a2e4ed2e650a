#include "tightfit/common/preconditioned_gmres.hpp"

#include <gtest/gtest.h>

#include <random>

#include "support/laplacian_1d.hpp"
#include "tightfit/common/sparse_cholesky.hpp"

namespace tightfit::preconditioned_gmres_test {

using test::laplacian_1d;

TEST(PreconditionedGmres, ExactPreconditionerConvergesInOneIteration) {
  const SparseMatrix A = laplacian_1d(80, 0.1);
  SparseCholesky chol;
  ASSERT_TRUE(chol.factorize(A));
  const VecX b = VecX::LinSpaced(80, -1.0, 3.0);
  VecX x;
  const GmresReport r = preconditioned_gmres([&](const VecX& v) { return VecX(A * v); },
                                             [&](const VecX& v) { return chol.solve(v); }, b, x);
  EXPECT_TRUE(r.converged);
  EXPECT_LE(r.iterations, 1);
  EXPECT_LT((A * x - b).norm(), 1e-12 * b.norm());
}

TEST(PreconditionedGmres, SolvesAPerturbedIndefiniteSystemWithANearbyFactorization) {
  // A = M + E with M SPD (factorized) and E a sparse symmetric perturbation on a few
  // rows that makes A indefinite: the adjoint's situation (exact Hessian vs the
  // projected Newton matrix, which differ on the projected elements only).
  const int n = 400;
  const SparseMatrix M = laplacian_1d(n, 0.05);
  SparseMatrix A = M;
  std::mt19937 rng(3);
  std::uniform_int_distribution<int> index(0, n - 1);
  for (int k = 0; k < 12; ++k) {
    const int i = index(rng), j = index(rng);
    A.coeffRef(i, j) += 0.4;
    if (i != j) A.coeffRef(j, i) += 0.4;
  }
  A.coeffRef(17, 17) = -1.0;  // a negative curvature direction
  A.makeCompressed();
  SparseCholesky chol;
  ASSERT_TRUE(chol.factorize(M));
  SparseCholesky direct;
  EXPECT_FALSE(direct.factorize(A)) << "the test matrix should be indefinite";
  const VecX b = VecX::LinSpaced(n, -1.0, 1.0);
  VecX x;
  GmresOptions o;
  o.relative_tolerance = 1e-12;
  o.max_iterations = 200;
  o.restart = 40;
  const GmresReport r = preconditioned_gmres([&](const VecX& v) { return VecX(A * v); },
                                             [&](const VecX& v) { return chol.solve(v); }, b, x, o);
  ASSERT_TRUE(r.converged) << r.iterations << " iterations, residual " << r.relative_residual;
  EXPECT_LT((A * x - b).norm(), 1e-11 * b.norm());
  EXPECT_NEAR(r.relative_residual, (A * x - b).norm() / b.norm(), 1e-13);
  EXPECT_GT(r.iterations, 1);
  EXPECT_LE(r.iterations, 2 * 13 + 2) << "a rank-k perturbation needs about k iterations";
}

TEST(PreconditionedGmres, ReportsNonConvergenceWithinTheIterationBudget) {
  const SparseMatrix A = laplacian_1d(300, 1e-4);
  const VecX b = VecX::Ones(300);
  VecX x;
  GmresOptions o;
  o.max_iterations = 5;
  o.restart = 3;
  const GmresReport r = preconditioned_gmres([&](const VecX& v) { return VecX(A * v); },
                                             [](const VecX& v) { return v; }, b, x, o);
  EXPECT_FALSE(r.converged);
  EXPECT_EQ(r.iterations, 5);
  EXPECT_NEAR(r.relative_residual, (A * x - b).norm() / b.norm(), 1e-12);
}

TEST(PreconditionedGmres, ZeroRightHandSideGivesZero) {
  const SparseMatrix A = laplacian_1d(10, 0.1);
  VecX x = VecX::Ones(10);
  const GmresReport r = preconditioned_gmres([&](const VecX& v) { return VecX(A * v); },
                                             [](const VecX& v) { return v; }, VecX::Zero(10), x);
  EXPECT_TRUE(r.converged);
  EXPECT_EQ(x.norm(), 0.0);
}

TEST(FactorizeShifted, ShiftsAnIndefiniteMatrixUntilItFactorizes) {
  SparseMatrix A = laplacian_1d(20, 0.0);
  A.coeffRef(3, 3) = -1.0;
  SparseCholesky chol;
  int count = 0;
  const auto shift = factorize_shifted(chol, A, ShiftSequence{1e-8, 10.0, 30}, count);
  ASSERT_TRUE(shift.has_value());
  EXPECT_GT(*shift, 0.0);
  EXPECT_GT(count, 1);
  int none = 0;
  EXPECT_EQ(*factorize_shifted(chol, laplacian_1d(20, 0.1), ShiftSequence{}, none), 0.0);
  EXPECT_EQ(none, 1);
  // Starting from a shift (Newton's hint after a shifted iteration): A itself is skipped.
  int from_hint = 0;
  const auto hinted = factorize_shifted(chol, laplacian_1d(20, 0.1),
                                        ShiftSequence{1e-4, 10.0, 30, false}, from_hint);
  ASSERT_TRUE(hinted.has_value());
  EXPECT_GT(*hinted, 0.0);
  EXPECT_EQ(from_hint, 1);
}

TEST(FactorizeShifted, AnEstimatedFirstShiftSavesTheClimb) {
  // A negative eigenvalue far below the first shift: the plain sequence climbs a decade
  // per failed factorization; with the Lanczos estimate the first shift is near the
  // one needed.
  SparseMatrix A = laplacian_1d(300, 0.0);
  A.coeffRef(100, 100) = -2.0;
  SparseCholesky chol;
  int climbing = 0, estimated = 0;
  const auto plain = factorize_shifted(chol, A, ShiftSequence{}, climbing);
  ShiftSequence with_estimate;
  with_estimate.estimate_steps = 60;
  const auto shift = factorize_shifted(chol, A, with_estimate, estimated);
  ASSERT_TRUE(plain && shift);
  EXPECT_GE(climbing, 8);
  EXPECT_LE(estimated, 2);  // A itself, then the estimated shift
  // A + δS is positive definite only for δ above −λ_min: the estimate (a bound from
  // above of λ_min) never lands below the shift that is needed.
  const VecX b = VecX::LinSpaced(300, -1.0, 1.0);
  EXPECT_TRUE(chol.solve(b).allFinite());
  SparseCholesky check;
  EXPECT_FALSE(factorize_with_shift(check, A, *shift / with_estimate.estimate_margin / 1.01));
  // Positive definite matrices never reach the estimate.
  int once = 0;
  EXPECT_EQ(*factorize_shifted(chol, laplacian_1d(50, 0.1), with_estimate, once), 0.0);
  EXPECT_EQ(once, 1);
}

TEST(FactorizeShifted, ShiftsEachDofInProportionToItsStiffness) {
  // Newton's unknowns mix units (a garment vertex's surface coordinates, a body vertex's
  // metres): rescaling some unknowns, A -> D A D, must not change which shifts
  // factorize (an identity shift would need a different relative shift for each D).
  SparseMatrix A = laplacian_1d(30, 0.0);
  A.coeffRef(5, 5) = -0.5;
  A.coeffRef(20, 20) = 0.2;
  VecX d = VecX::Ones(30);
  for (int i = 0; i < 30; i += 3) d[i] = 10.0;
  for (int i = 1; i < 30; i += 7) d[i] = 0.1;
  const SparseMatrix B = SparseMatrix(d.asDiagonal() * A * d.asDiagonal());
  SparseCholesky chol;
  int count_a = 0, count_b = 0;
  const auto shift_a = factorize_shifted(chol, A, ShiftSequence{}, count_a);
  const auto shift_b = factorize_shifted(chol, B, ShiftSequence{}, count_b);
  ASSERT_TRUE(shift_a && shift_b);
  EXPECT_GT(count_a, 2);
  EXPECT_EQ(count_a, count_b);
  EXPECT_NEAR(*shift_a / A.diagonal().cwiseAbs().mean(), *shift_b / B.diagonal().cwiseAbs().mean(),
              1e-12 * *shift_a / A.diagonal().cwiseAbs().mean());
}

TEST(FactorizeShifted, TheShiftItReturnedMakesTheSameFactorizationAgain) {
  // A resumed optimization makes a held factorization again from its matrix and shift.
  SparseMatrix A = laplacian_1d(25, 0.0);
  A.coeffRef(7, 7) = -0.7;
  SparseCholesky first, again;
  int count = 0;
  const auto shift = factorize_shifted(first, A, ShiftSequence{}, count);
  ASSERT_TRUE(shift.has_value());
  ASSERT_GT(*shift, 0.0);
  ASSERT_TRUE(factorize_with_shift(again, A, *shift));
  const VecX b = VecX::LinSpaced(25, -1.0, 3.0);
  EXPECT_EQ(first.solve(b), again.solve(b));          // bit for bit
  EXPECT_FALSE(factorize_with_shift(again, A, 0.0));  // A itself is indefinite
  ASSERT_TRUE(factorize_with_shift(again, laplacian_1d(25, 0.1), 0.0));
  // swap hands factorizations over without copying.
  first.swap(again);
  EXPECT_LT((laplacian_1d(25, 0.1) * first.solve(b) - b).norm(), 1e-12 * b.norm());
  int unused = 0;
  SparseCholesky reference;
  ASSERT_TRUE(factorize_shifted(reference, A, ShiftSequence{}, unused));
  EXPECT_EQ(again.solve(b), reference.solve(b));
}

}  // namespace tightfit::preconditioned_gmres_test
