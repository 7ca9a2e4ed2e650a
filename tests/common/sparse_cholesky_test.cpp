#include "tightfit/common/sparse_cholesky.hpp"

#include <gtest/gtest.h>

#include "support/grid_laplacian_3d.hpp"
#include "support/laplacian_1d.hpp"
#include "tightfit/common/error.hpp"

namespace tightfit::sparse_cholesky_test {

using test::grid_laplacian_3d;
using test::laplacian_1d;

/// The 5-point Laplacian of an m×m grid plus `shift`·I, with extra symmetric couplings
/// −0.1 between the listed pairs of grid nodes (diagonals raised to keep it SPD).
SparseMatrix grid_laplacian(int m, double shift,
                            const std::vector<std::pair<int, int>>& extra = {}) {
  std::vector<Triplet> t;
  auto id = [m](int i, int j) { return i * m + j; };
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j) {
      t.emplace_back(id(i, j), id(i, j), 4.0 + shift);
      if (i + 1 < m) {
        t.emplace_back(id(i, j), id(i + 1, j), -1.0);
        t.emplace_back(id(i + 1, j), id(i, j), -1.0);
      }
      if (j + 1 < m) {
        t.emplace_back(id(i, j), id(i, j + 1), -1.0);
        t.emplace_back(id(i, j + 1), id(i, j), -1.0);
      }
    }
  for (auto [a, b] : extra) {
    t.emplace_back(a, b, -0.1);
    t.emplace_back(b, a, -0.1);
    t.emplace_back(a, a, 0.1);
    t.emplace_back(b, b, 0.1);
  }
  SparseMatrix A(m * m, m * m);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

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

TEST(SparseCholesky, AnalysesANearbyPatternWithAGivenOrdering) {
  const int m = 30;
  SparseCholesky first;
  ASSERT_TRUE(first.factorize(grid_laplacian(m, 0.1)));
  const CholeskyOrdering ordering = first.ordering();
  ASSERT_EQ(static_cast<int>(ordering.permutation.size()), m * m);
  EXPECT_GT(ordering.factor_nonzeros, 0.0);
  EXPECT_EQ(first.ordering_searches(), 1);

  // A pattern with a few more couplings: analysed with the given ordering, no search.
  const SparseMatrix B = grid_laplacian(m, 0.2, {{3, 40}, {100, 161}, {500, 533}});
  SparseCholesky second;
  ASSERT_TRUE(second.factorize(B, &ordering));
  EXPECT_EQ(second.symbolic_analyses(), 1);
  EXPECT_EQ(second.ordering_searches(), 0);
  const VecX b = VecX::LinSpaced(m * m, -1.0, 2.0);
  EXPECT_LT((B * second.solve(b) - b).norm(), 1e-12 * b.norm());

  // The result is a function of the matrix and the ordering: a solver that analysed
  // other patterns before gives the same factor bit for bit.
  SparseCholesky third;
  ASSERT_TRUE(third.factorize(grid_laplacian(m, 0.3)));
  ASSERT_TRUE(third.factorize(B, &ordering));
  EXPECT_EQ(third.solve(b), second.solve(b));
  // The same pattern with and without the ordering are different analyses.
  ASSERT_TRUE(third.factorize(B));
  EXPECT_EQ(third.symbolic_analyses(), 3);
  ASSERT_TRUE(third.factorize(B));
  EXPECT_EQ(third.symbolic_analyses(), 3);
}

TEST(SparseCholesky, SearchesANewOrderingWhenTheGivenOneFillsTooMuch) {
  const int m = 30;
  SparseCholesky nested;
  ASSERT_TRUE(nested.factorize(grid_laplacian(m, 0.1)));
  // The natural (row by row) ordering of a grid fills a band of width m, several
  // times what a nested dissection gives.
  CholeskyOrdering natural;
  natural.factor_nonzeros = nested.ordering().factor_nonzeros;
  for (int i = 0; i < m * m; ++i) natural.permutation.push_back(i);
  SparseCholesky chol;
  ASSERT_TRUE(chol.factorize(grid_laplacian(m, 0.2), &natural));
  EXPECT_EQ(chol.ordering_searches(), 1);
  EXPECT_LT(chol.ordering().factor_nonzeros, 1.25 * natural.factor_nonzeros);
  // With room for the fill, the natural ordering is used.
  SparseCholesky lenient;
  ASSERT_TRUE(lenient.factorize(grid_laplacian(m, 0.2), &natural, 100.0));
  EXPECT_EQ(lenient.ordering_searches(), 0);
  EXPECT_GT(lenient.ordering().factor_nonzeros, 1.25 * natural.factor_nonzeros);
}

TEST(SparseCholesky, FactorizesAPlusADiagonalBitForBitAsTheSum) {
  const SparseMatrix A = grid_laplacian(9, -1.0, {{0, 40}, {7, 70}});
  const VecX d = VecX::LinSpaced(81, 1.0, 2.0);
  SparseMatrix D(81, 81);
  for (Eigen::Index i = 0; i < 81; ++i) D.insert(i, i) = d[i];
  const VecX b = VecX::LinSpaced(81, -1.0, 1.0);
  SparseCholesky sum, plus;
  ASSERT_TRUE(sum.factorize(SparseMatrix(A + D), nullptr));
  ASSERT_TRUE(plus.factorize_plus_diagonal(A, d, nullptr));
  EXPECT_EQ((sum.solve(b) - plus.solve(b)).cwiseAbs().maxCoeff(), 0.0);
  // Without the diagonal the same matrix is not positive definite.
  EXPECT_FALSE(plus.factorize(A));
  // A diagonal entry that A does not store: the sum's pattern has it.
  SparseMatrix gap = A;
  gap.coeffRef(5, 5) = 0.0;
  gap.prune(0.0);
  ASSERT_LT(gap.nonZeros(), A.nonZeros());
  SparseCholesky sum_gap, plus_gap;
  ASSERT_TRUE(sum_gap.factorize(SparseMatrix(gap + D), nullptr));
  ASSERT_TRUE(plus_gap.factorize_plus_diagonal(gap, d, nullptr));
  EXPECT_EQ((sum_gap.solve(b) - plus_gap.solve(b)).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_THROW(plus.factorize_plus_diagonal(A, VecX::Ones(80), nullptr), SolverError);
}

TEST(SparseCholesky, SupernodalFactorizationsGatherThePermutedMatrixOncePerPattern) {
  // Large enough for CHOLMOD to choose a supernodal factor, whose permuted lower triangle
  // tightfit gathers itself from the second factorization of a pattern on: a
  // refactorization of the same pattern, a fresh one, the upper triangle alone and A plus
  // a diagonal must all agree bit for bit.
  const int m = 14, n = m * m * m;
  const SparseMatrix A = grid_laplacian_3d(m, 0.3);
  const SparseMatrix B = grid_laplacian_3d(m, 0.7);
  const VecX b = VecX::LinSpaced(n, -1.0, 2.0);
  SparseCholesky reused, fresh, upper_only;
  ASSERT_TRUE(reused.factorize(A));
  ASSERT_GT(reused.supernodal_view().supernodes, 0);
  EXPECT_LT((A * reused.solve(b) - b).norm(), 1e-12 * b.norm());
  ASSERT_TRUE(reused.factorize(B));
  EXPECT_EQ(reused.symbolic_analyses(), 1);
  ASSERT_TRUE(fresh.factorize(B));
  ASSERT_TRUE(upper_only.factorize(SparseMatrix(B.triangularView<Eigen::Upper>())));
  const VecX x = fresh.solve(b);
  EXPECT_LT((B * x - b).norm(), 1e-12 * b.norm());
  EXPECT_EQ((reused.solve(b) - x).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ((upper_only.solve(b) - x).cwiseAbs().maxCoeff(), 0.0);
  // B = A + 0.4 I, bit for bit as factorize_plus_diagonal(A, 0.4): the first
  // factorization of a pattern (cholmod_factorize) and a later one (gathered).
  SparseCholesky plus;
  ASSERT_TRUE(plus.factorize_plus_diagonal(A, VecX::Constant(n, 0.4), nullptr));
  EXPECT_EQ((plus.solve(b) - x).cwiseAbs().maxCoeff(), 0.0);
  ASSERT_TRUE(reused.factorize_plus_diagonal(A, VecX::Constant(n, 0.4), nullptr));
  EXPECT_EQ((reused.solve(b) - x).cwiseAbs().maxCoeff(), 0.0);
  // After a failed (indefinite) factorization of the same pattern, the next one works.
  EXPECT_FALSE(plus.factorize(grid_laplacian_3d(m, -6.5)));
  EXPECT_THROW(plus.solve(b), SolverError);
  ASSERT_TRUE(plus.factorize(B));
  EXPECT_EQ((plus.solve(b) - x).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ(plus.symbolic_analyses(), 1);
}

TEST(SparseCholesky, ReportsIndefiniteMatrices) {
  SparseCholesky chol;
  EXPECT_FALSE(chol.factorize(laplacian_1d(20, -3.0)));
  EXPECT_THROW(chol.solve(VecX::Ones(20)), SolverError);
  EXPECT_TRUE(chol.factorize(laplacian_1d(20, 0.0)));
}

}  // namespace tightfit::sparse_cholesky_test
