#pragma once
/// The one wrapper around the sparse Cholesky factorization (CHOLMOD, SuiteSparse).
/// Symmetric positive definite matrices only; the symbolic analysis (fill-reducing
/// ordering, supernode structure) is reused while the sparsity pattern stays the same.
#include <cstdint>
#include <memory>
#include <optional>

#include "tightfit/common/types.hpp"

namespace tightfit {

class SparseCholesky {
 public:
  SparseCholesky();
  ~SparseCholesky();
  SparseCholesky(const SparseCholesky&) = delete;
  SparseCholesky& operator=(const SparseCholesky&) = delete;

  /// Factorizes the symmetric matrix `A` (n×n, compressed; only its upper triangle is
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

/// The growing diagonal shifts tried when a matrix is not positive definite:
/// δ_k = initial · mean|diag(A)| · growth^k, k = 0 … attempts − 1.
struct ShiftSequence {
  double initial = 1e-8;  ///< relative to mean |diag(A)|
  double growth = 10.0;
  int attempts = 30;
  bool try_unshifted = true;  ///< try A itself before the first shift
};

/// Factorizes A (when shifts.try_unshifted), or else A + δI with the smallest δ of
/// `shifts` that succeeds. Returns
/// δ (0 when A itself was positive definite), or nullopt when every shift failed (the
/// factor is then unusable; `last_shift` receives the largest δ tried). `factorizations`
/// counts the attempts.
std::optional<double> factorize_shifted(SparseCholesky& cholesky, const SparseMatrix& A,
                                        const ShiftSequence& shifts, int& factorizations,
                                        double* last_shift = nullptr);

}  // namespace tightfit
