#include "tightfit/common/truncated_cg.hpp"

#include <gtest/gtest.h>

#include "support/laplacian_1d.hpp"
#include "tightfit/common/sparse_cholesky.hpp"

namespace tightfit::truncated_cg_test {

using test::laplacian_1d;

LinearOperator product(const SparseMatrix& A) {
  return [&A](const VecX& v) { return VecX(A * v); };
}

TEST(TruncatedCg, ReachesTheToleranceOnAPositiveDefiniteSystem) {
  const SparseMatrix A = laplacian_1d(60, 0.05);
  const VecX b = VecX::LinSpaced(60, -1.0, 2.0);
  TruncatedCgReport r;
  const VecX x = truncated_cg(product(A), [](const VecX& v) { return v; }, b, r, {1e-8, 200});
  EXPECT_TRUE(r.converged);
  EXPECT_FALSE(r.negative_curvature);
  EXPECT_GT(r.iterations, 1);
  EXPECT_LE((A * x - b).norm(), 1e-8 * b.norm());
  EXPECT_NEAR(r.relative_residual, (A * x - b).norm() / b.norm(), 1e-10);
}

TEST(TruncatedCg, AnExactPreconditionerConvergesInOneProduct) {
  const SparseMatrix A = laplacian_1d(60, 0.05);
  SparseCholesky chol;
  ASSERT_TRUE(chol.factorize(A));
  const VecX b = VecX::LinSpaced(60, -1.0, 2.0);
  TruncatedCgReport r;
  const VecX x = truncated_cg(
      product(A), [&](const VecX& v) { return chol.solve(v); }, b, r);
  EXPECT_TRUE(r.converged);
  EXPECT_EQ(r.iterations, 1);
  EXPECT_LE((A * x - b).norm(), 1e-10 * b.norm());
}

TEST(TruncatedCg, StopsOnNegativeCurvatureWithADescentDirection) {
  // A indefinite (one negative eigenvalue), preconditioned by a positive definite M:
  // the result x is a descent direction of ½xᵀAx − bᵀx from 0 (bᵀx > 0).
  SparseMatrix A = laplacian_1d(40, 0.0);
  A.coeffRef(20, 20) = -3.0;
  const SparseMatrix M = laplacian_1d(40, 0.5);
  SparseCholesky chol;
  ASSERT_TRUE(chol.factorize(M));
  const VecX b = VecX::LinSpaced(40, 1.0, 2.0);
  TruncatedCgReport r;
  const VecX x =
      truncated_cg(product(A), [&](const VecX& v) { return chol.solve(v); }, b, r, {1e-10, 100});
  EXPECT_TRUE(r.negative_curvature);
  EXPECT_FALSE(r.converged);
  EXPECT_GT(b.dot(x), 0.0);
}

TEST(TruncatedCg, NegativeCurvatureAtOnceGivesThePreconditionedDirection) {
  SparseMatrix A(3, 3);
  A.setIdentity();
  A *= -1.0;
  const VecX b = VecX::Constant(3, 2.0);
  TruncatedCgReport r;
  const VecX x = truncated_cg(
      product(A), [](const VecX& v) { return VecX(0.5 * v); }, b, r);
  EXPECT_TRUE(r.negative_curvature);
  EXPECT_LT((x - VecX::Constant(3, 1.0)).norm(), 1e-15);
}

TEST(TruncatedCg, RejectsInvalidOptions) {
  const SparseMatrix A = laplacian_1d(5, 1.0);
  TruncatedCgReport r;
  const auto identity = [](const VecX& v) { return v; };
  EXPECT_THROW(truncated_cg(product(A), identity, VecX::Ones(5), r, {0.0, 10}),
               std::invalid_argument);
  EXPECT_THROW(truncated_cg(product(A), identity, VecX::Ones(5), r, {1e-3, 0}),
               std::invalid_argument);
}

}  // namespace tightfit::truncated_cg_test
