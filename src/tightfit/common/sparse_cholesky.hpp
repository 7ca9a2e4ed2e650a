#pragma once
/// The one wrapper around the sparse Cholesky factorization (CHOLMOD, SuiteSparse).
/// Symmetric positive definite matrices only; the symbolic analysis (fill-reducing
/// ordering, supernode structure) is reused while the sparsity pattern stays the same.
/// A matrix whose pattern differs only a little from one already analysed (a Newton
/// Hessian after garment vertices slid onto other faces) can be analysed with that
/// analysis' ordering instead of a new one (METIS and AMD are the costly part).
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "tightfit/common/single_precision_factor.hpp"
#include "tightfit/common/types.hpp"

namespace tightfit {

/// A fill-reducing ordering found by a symbolic analysis: the permutation (CHOLMOD's
/// final one, postordered) and the number of nonzeros of L it gave, for judging it on
/// another pattern.
struct CholeskyOrdering {
  std::vector<int> permutation;  ///< n entries, a permutation of 0 … n−1
  double factor_nonzeros = 0.0;  ///< nnz(L) of the analysis that found it
};

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
  /// As factorize(A); when A's pattern needs a new symbolic analysis and `ordering` is
  /// given (and of A's size), the analysis uses `ordering.permutation` instead of
  /// searching one — unless L would get more than `max_fill_growth` times the
  /// nonzeros that ordering gave on its own pattern, then a new ordering is searched.
  /// The result is a function of A and `ordering` only (not of earlier calls).
  bool factorize(const SparseMatrix& A, const CholeskyOrdering* ordering,
                 double max_fill_growth = 1.25);
  /// As factorize(A, ordering, max_fill_growth) for A + diag(d) (d: n entries), bit for
  /// bit, without forming that sum: d is added to the diagonal of the copy of A's upper
  /// triangle that the factorization makes anyway.
  bool factorize_plus_diagonal(const SparseMatrix& A, const VecX& d,
                               const CholeskyOrdering* ordering, double max_fill_growth = 1.25);

  /// Solves A x = b with the last successful factorization. `b` has n rows.
  VecX solve(const VecX& b) const;
  /// Applies the last successful factorization with its factor rounded to single
  /// precision (SinglePrecisionFactor): a fixed symmetric positive definite operator
  /// within about 1e-7 of A⁻¹, at about half the memory traffic of solve(): for
  /// preconditioning Krylov methods. Equals solve() where CHOLMOD chose a simplicial
  /// factor (small matrices). Made on the first call after a factorization; safe to call
  /// from several threads.
  VecX solve_preconditioner(const VecX& b) const;
  /// The arrays of the last successful factorization's supernodal factor, valid until
  /// the next factorization (empty: none, or CHOLMOD chose a simplicial factor).
  SupernodalFactorView supernodal_view() const;
  /// Solves A X = B column by column.
  MatX solve_columns(const MatX& B) const;

  /// Number of symbolic analyses done so far (grows only when the pattern changes).
  int symbolic_analyses() const;
  /// Of them: analyses that searched a new fill-reducing ordering (METIS/AMD).
  int ordering_searches() const;
  /// The ordering of the current symbolic analysis (empty permutation before the first).
  const CholeskyOrdering& ordering() const;
  /// Number of stored entries of the Cholesky factor L of the last factorization.
  std::int64_t factor_nonzeros() const;
  /// Dimension n of the last factorized matrix.
  Eigen::Index size() const;
  /// Exchanges factorizations (and symbolic analyses) with `other`, copying nothing.
  void swap(SparseCholesky& other) noexcept { impl_.swap(other.impl_); }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;

  /// Factorizes A, or A + diag(*diagonal) when `diagonal` is given.
  bool factorize_matrix(const SparseMatrix& A, const VecX* diagonal,
                        const CholeskyOrdering* ordering, double max_fill_growth);
  /// A new symbolic analysis of the pattern of impl_->upper (with `ordering` when given).
  void analyze(const CholeskyOrdering* ordering, double max_fill_growth);
};

/// The growing diagonal shifts tried when a matrix is not positive definite:
/// A + δ_k S with δ_k = initial · mean|diag(A)| · growth^k, k = 0 … attempts − 1, and
/// S = diag(max(|A_ii|, diagonal_floor · mean|diag(A)|)) / mean|diag(A)|: each DOF is
/// shifted in proportion to its own stiffness (Levenberg–Marquardt scaling), δ_k being
/// the shift of a DOF of mean stiffness.
struct ShiftSequence {
  double initial = 1e-8;  ///< relative to mean |diag(A)|
  double growth = 10.0;
  int attempts = 30;
  bool try_unshifted = true;     ///< try A itself before the first shift
  double diagonal_floor = 1e-6;  ///< smallest |A_ii| a shift is scaled by, relative to the mean
  /// When > 0 and A itself was tried and is not positive definite: the first shift is
  /// at least `estimate_margin` · (−θ), θ the lowest Ritz value of `estimate_steps`
  /// Lanczos steps on S^{−1/2} A S^{−1/2} (lanczos.hpp; A + δS is positive definite only
  /// for δ > −θ), instead of climbing there from `initial` one failed factorization per
  /// decade. 0: no estimate.
  int estimate_steps = 0;
  double estimate_margin = 2.0;
};

/// Factorizes A (when shifts.try_unshifted), or else A + δS with the smallest δ of
/// `shifts` that succeeds. Returns
/// δ (0 when A itself was positive definite), or nullopt when every shift failed (the
/// factor is then unusable; `last_shift` receives the largest δ tried). `factorizations`
/// counts the attempts.
/// `ordering` (optional) is passed to SparseCholesky::factorize.
std::optional<double> factorize_shifted(SparseCholesky& cholesky, const SparseMatrix& A,
                                        const ShiftSequence& shifts, int& factorizations,
                                        double* last_shift = nullptr,
                                        const CholeskyOrdering* ordering = nullptr);

/// Factorizes A + shift·S, S the scaling of ShiftSequence with `diagonal_floor`: the
/// matrix factorize_shifted() factorized when it returned `shift` (bit for bit), so a
/// shifted factorization can be made again from its matrix and shift alone. shift = 0
/// factorizes A. Returns false when that matrix is not positive definite.
bool factorize_with_shift(SparseCholesky& cholesky, const SparseMatrix& A, double shift,
                          const CholeskyOrdering* ordering = nullptr,
                          double diagonal_floor = ShiftSequence{}.diagonal_floor);

}  // namespace tightfit
