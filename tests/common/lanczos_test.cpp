#include "tightfit/common/lanczos.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <stdexcept>

#include "support/laplacian_1d.hpp"

namespace tightfit::lanczos_test {

using test::laplacian_1d;

/// λ_min of S^{−1/2} A S^{−1/2} by a dense eigen-solve.
double lowest_eigenvalue(const SparseMatrix& A, const VecX& scaling) {
  const VecX s = scaling.cwiseSqrt().cwiseInverse();
  const MatX B = s.asDiagonal() * MatX(A) * s.asDiagonal();
  return Eigen::SelfAdjointEigenSolver<MatX>(B, Eigen::EigenvaluesOnly).eigenvalues().minCoeff();
}

TEST(LowestRitzValue, BoundsTheLowestEigenvalueFromAboveAndReachesIt) {
  // A 1D Laplacian with one strongly negative diagonal entry: an isolated negative
  // eigenvalue below a dense positive spectrum, as in an indefinite Newton matrix.
  SparseMatrix A = laplacian_1d(200, 0.0);
  A.coeffRef(57, 57) = -3.0;
  const VecX scaling = VecX::Ones(200);
  const double exact = lowest_eigenvalue(A, scaling);
  ASSERT_LT(exact, -1.0);
  double previous = lowest_ritz_value(A, scaling, 2);
  EXPECT_GE(previous, exact - 1e-10);
  for (int steps : {5, 10, 20, 40}) {
    const double theta = lowest_ritz_value(A, scaling, steps);
    EXPECT_GE(theta, exact - 1e-10) << steps;
    EXPECT_LE(theta, previous + 1e-10) << steps;  // more steps: never a worse bound
    previous = theta;
  }
  EXPECT_NEAR(previous, exact, 1e-8 * std::abs(exact));
}

TEST(LowestRitzValue, MeasuresTheEigenvalueInTheMetricOfTheScaling) {
  // With S = diag(A) the value is that of the Jacobi-scaled matrix, so rescaling the
  // unknowns (A -> D A D, S -> D S D) leaves it unchanged.
  SparseMatrix A = laplacian_1d(60, 0.0);
  A.coeffRef(10, 10) = -1.5;
  VecX d = VecX::Ones(60);
  for (int i = 0; i < 60; i += 4) d[i] = 30.0;
  const SparseMatrix B = SparseMatrix(d.asDiagonal() * A * d.asDiagonal());
  const VecX scaling_a = A.diagonal().cwiseAbs();
  const VecX scaling_b = B.diagonal().cwiseAbs();
  const double exact = lowest_eigenvalue(A, scaling_a);
  EXPECT_NEAR(lowest_eigenvalue(B, scaling_b), exact, 1e-10);
  EXPECT_NEAR(lowest_ritz_value(A, scaling_a, 60), exact, 1e-8);
  EXPECT_NEAR(lowest_ritz_value(B, scaling_b, 60), exact, 1e-8);
}

TEST(LowestRitzValue, IsRepeatableAndStopsOnAnInvariantSubspace) {
  SparseMatrix A = laplacian_1d(40, 0.3);
  const VecX scaling = VecX::Constant(40, 2.0);
  EXPECT_EQ(lowest_ritz_value(A, scaling, 15), lowest_ritz_value(A, scaling, 15));
  // More steps than unknowns: the Krylov space is the whole space, θ = λ_min.
  EXPECT_NEAR(lowest_ritz_value(A, scaling, 100), lowest_eigenvalue(A, scaling), 1e-10);
  SparseMatrix I(5, 5);
  I.setIdentity();
  EXPECT_NEAR(lowest_ritz_value(3.0 * I, VecX::Ones(5), 10), 3.0, 1e-14);
}

TEST(LowestRitzValue, RejectsInvalidArguments) {
  const SparseMatrix A = laplacian_1d(10, 0.1);
  EXPECT_THROW(lowest_ritz_value(A, VecX::Ones(9), 5), std::invalid_argument);
  EXPECT_THROW(lowest_ritz_value(A, VecX::Ones(10), 0), std::invalid_argument);
  VecX zero_scale = VecX::Ones(10);
  zero_scale[3] = 0.0;
  EXPECT_THROW(lowest_ritz_value(A, zero_scale, 5), std::invalid_argument);
}

}  // namespace tightfit::lanczos_test
