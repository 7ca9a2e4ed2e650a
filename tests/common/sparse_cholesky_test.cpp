#include "tightfit/common/sparse_cholesky.hpp"

#include <gtest/gtest.h>

#include "support/laplacian_1d.hpp"
#include "tightfit/common/error.hpp"

namespace tightfit {
namespace {

using test::laplacian_1d;

TEST(SparseCholesky, SolvesAnSpdSystem) {
  const SparseMatrix A = laplacian_1d(50, 0.1);
  SparseCholesky chol;
  ASSERT_TRUE(chol.factorize(A));
  const VecX b = VecX::LinSpaced(50, -1.0, 2.0);
  const VecX x = chol.solve(b);
  EXPECT_LT((A * x - b).norm(), 1e-12 * b.norm());
  EXPECT_GE(chol.factor_nonzeros(), 50);
}

TEST(SparseCholesky, ReusesSymbolicAnalysisForTheSamePattern) {
  SparseCholesky chol;
  ASSERT_TRUE(chol.factorize(laplacian_1d(30, 0.1)));
  ASSERT_TRUE(chol.factorize(laplacian_1d(30, 0.5)));
  EXPECT_EQ(chol.symbolic_analyses(), 1);
  ASSERT_TRUE(chol.factorize(laplacian_1d(31, 0.5)));
  EXPECT_EQ(chol.symbolic_analyses(), 2);
}

TEST(SparseCholesky, ReportsIndefiniteMatrices) {
  SparseCholesky chol;
  EXPECT_FALSE(chol.factorize(laplacian_1d(20, -3.0)));
  EXPECT_THROW(chol.solve(VecX::Ones(20)), SolverError);
  EXPECT_TRUE(chol.factorize(laplacian_1d(20, 0.0)));
}

}  // namespace
}  // namespace tightfit
