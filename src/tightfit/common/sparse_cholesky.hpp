#pragma once
/// The one wrapper around the sparse Cholesky factorization (CHOLMOD, SuiteSparse).
/// Symmetric positive definite matrices only; the symbolic analysis (fill-reducing
/// ordering, supernode structure) is reused while the sparsity pattern stays the same.
#include <cstdint>
#include <memory>

#include "tightfit/common/types.hpp"

namespace tightfit {

class SparseCholesky {
 public:
  SparseCholesky();
  ~SparseCholesky();
  SparseCholesky(const SparseCholesky&) = delete;
  SparseCholesky& operator=(const SparseCholesky&) = delete;

  /// Factorizes the symmetric matrix `A` (n×n, compressed; only its lower triangle is
  /// read). Returns false when `A` is not positive definite (or the factorization
  /// failed numerically); the previous factor is then unusable.
  bool factorize(const SparseMatrix& A);

  /// Solves A x = b with the last successful factorization. `b` has n rows.
  VecX solve(const VecX& b) const;
  /// Solves A X = B column by column.
  MatX solve_columns(const MatX& B) const;

  /// Number of symbolic analyses done so far (grows only when the pattern changes).
  int symbolic_analyses() const;
  /// Number of stored entries of the Cholesky factor L of the last factorization.
  std::int64_t factor_nonzeros() const;
  /// Dimension n of the last factorized matrix.
  Eigen::Index size() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace tightfit
