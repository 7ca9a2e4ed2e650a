#include "tightfit/common/single_precision_factor.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>

#include "support/grid_laplacian_3d.hpp"
#include "tightfit/common/sparse_cholesky.hpp"

namespace tightfit::single_precision_factor_test {

using test::grid_laplacian_3d;

/// A hand-made supernodal factor of n = 14 in three supernodes (3, 2 and 9 columns, 11, 4
/// and 9 rows: block heights that are and are not multiples of the kernels' 8 lanes)
/// whose values are exactly representable in single precision, so that the rounded
/// factor is the factor itself.
struct HandMadeFactor {
  static constexpr int n = 14;
  std::vector<int> super{0, 3, 5, 14};
  std::vector<int> rows;
  std::vector<int> row_start{0};
  std::vector<int> value_start{0};
  std::vector<double> values;
  std::vector<int> permutation;
  MatX L = MatX::Zero(n, n);  // the same factor, dense, in the permuted ordering

  HandMadeFactor() {
    const std::vector<std::vector<int>> supernode_rows{
        {0, 1, 2, 5, 6, 7, 8, 9, 10, 11, 13}, {3, 4, 9, 12}, {5, 6, 7, 8, 9, 10, 11, 12, 13}};
    double next = 0.125;
    for (std::size_t s = 0; s < supernode_rows.size(); ++s) {
      const std::vector<int>& r = supernode_rows[s];
      rows.insert(rows.end(), r.begin(), r.end());
      row_start.push_back(static_cast<int>(rows.size()));
      const int columns = super[s + 1] - super[s];
      for (int j = 0; j < columns; ++j)
        for (std::size_t i = 0; i < r.size(); ++i) {
          double v = 0.0;
          if (static_cast<int>(i) == j) {
            v = 2.0 + 0.25 * j;
          } else if (static_cast<int>(i) > j) {
            v = next;
            next = next >= 0.5 ? -0.375 : next + 0.125;
          }
          values.push_back(v);
          if (static_cast<int>(i) >= j) L(r[i], super[s] + j) = v;
        }
      value_start.push_back(static_cast<int>(values.size()));
    }
    permutation.resize(n);
    std::iota(permutation.begin(), permutation.end(), 0);
    std::reverse(permutation.begin(), permutation.begin() + 9);
    std::swap(permutation[3], permutation[12]);
  }

  SupernodalFactorView view() const {
    SupernodalFactorView v;
    v.n = n;
    v.supernodes = 3;
    v.super = super.data();
    v.row_start = row_start.data();
    v.value_start = value_start.data();
    v.rows = rows.data();
    v.values = values.data();
    v.permutation = permutation.data();
    return v;
  }

  /// A = P'LL'P: row k of L is row permutation[k] of A.
  MatX matrix() const {
    const MatX LLt = L * L.transpose();
    MatX A(n, n);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) A(permutation[i], permutation[j]) = LLt(i, j);
    return A;
  }
};

TEST(SinglePrecisionFactor, SolvesWithARepresentableFactorExactly) {
  const HandMadeFactor f;
  const SinglePrecisionFactor single(f.view());
  EXPECT_EQ(single.n(), HandMadeFactor::n);
  EXPECT_EQ(single.stored_values(), static_cast<std::int64_t>(f.values.size()));
  const MatX A = f.matrix();
  const VecX b = VecX::LinSpaced(HandMadeFactor::n, -1.0, 3.0);
  const VecX x = single.apply(b);
  EXPECT_LT((A * x - b).norm(), 1e-13 * b.norm());
  EXPECT_LT((x - A.ldlt().solve(b)).norm(), 1e-12 * x.norm());
  EXPECT_THROW(single.apply(VecX::Ones(3)), std::invalid_argument);
  const SinglePrecisionFactor portable(f.view(), FactorKernels::kPortable);
  EXPECT_LT((portable.apply(b) - x).norm(), 1e-14 * x.norm());
}

TEST(SinglePrecisionFactor, PreconditionsLikeTheExactFactor) {
  const SparseMatrix A = grid_laplacian_3d(14, 0.5);
  SparseCholesky chol;
  ASSERT_TRUE(chol.factorize(A));
  const Eigen::Index n = A.rows();
  VecX b(n), c(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    b[i] = std::sin(0.37 * static_cast<double>(i)) + 0.1;
    c[i] = std::cos(0.11 * static_cast<double>(i));
  }
  const VecX exact = chol.solve(b);
  const VecX rounded = chol.solve_preconditioner(b);
  // The rounding of L moves the solution by a few single-precision ulps times the
  // condition number (here about 25), and by more than double-precision round-off.
  const double change = (rounded - exact).norm() / exact.norm();
  EXPECT_LT(change, 1e-5);
  EXPECT_GT(change, 1e-13);
  // A symmetric operator, as conjugate gradients needs: c'Mb = b'Mc.
  const VecX mc = chol.solve_preconditioner(c);
  EXPECT_NEAR(c.dot(rounded), b.dot(mc), 1e-12 * std::abs(b.dot(mc)));
  // Made again after a new factorization.
  ASSERT_TRUE(chol.factorize(SparseMatrix(2.0 * A)));
  EXPECT_LT((2.0 * chol.solve_preconditioner(b) - exact).norm(), 1e-5 * exact.norm());
}

// The sweeps split over threads (subtrees of the elimination tree on their own threads)
// give the serial sweeps' result up to round-off, and the same bits on every call.
TEST(SinglePrecisionFactor, ParallelSweepsAgreeWithSerialOnes) {
  const SparseMatrix A = grid_laplacian_3d(16, 0.5);
  SparseCholesky chol;
  ASSERT_TRUE(chol.factorize(A));
  const VecX b = VecX::LinSpaced(A.rows(), -1.0, 2.0).array().sin();
  // The view of CHOLMOD's factor, through the preconditioner the factorization made.
  const VecX reference = chol.solve_preconditioner(b);
  const SupernodalFactorView view = chol.supernodal_view();
  ASSERT_GT(view.supernodes, 0);
  const SinglePrecisionFactor serial(view, FactorKernels::kFastest, 1);
  const SinglePrecisionFactor parallel(view, FactorKernels::kFastest, 2);
  EXPECT_TRUE(serial.partition().parts.empty());
  ASSERT_EQ(parallel.partition().parts.size(), 2u);
  EXPECT_LT(parallel.partition().critical_fraction, SinglePrecisionFactor::kParallelWorth);
  const VecX xs = serial.apply(b);
  const VecX xp = parallel.apply(b);
  EXPECT_LT((xp - xs).norm(), 1e-13 * xs.norm());
  EXPECT_LT((reference - xs).norm(), 1e-13 * xs.norm());
  for (int call = 0; call < 3; ++call) EXPECT_EQ(parallel.apply(b), xp);
  // The parallel operator solves the rounded system as the serial one does.
  EXPECT_LT((A * xp - b).norm(), 1e-5 * b.norm());
}

}  // namespace tightfit::single_precision_factor_test
