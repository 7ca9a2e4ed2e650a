#include "tightfit/common/sparse_cholesky.hpp"

#include <cholmod.h>

#include <cmath>
#include <mutex>
#include <vector>

#include "tightfit/common/error.hpp"
#include "tightfit/common/lanczos.hpp"
#include "tightfit/common/single_precision_factor.hpp"

namespace tightfit {
namespace {

SparseMatrix diagonal_matrix(const VecX& d) {
  SparseMatrix D(d.size(), d.size());
  D.reserve(Eigen::VectorXi::Constant(d.size(), 1));
  for (Eigen::Index i = 0; i < d.size(); ++i) D.insert(i, i) = d[i];
  return D;
}

}  // namespace

struct SparseCholesky::Impl {
  cholmod_common common{};
  cholmod_factor* factor = nullptr;
  std::vector<int> pattern_outer;
  std::vector<int> pattern_inner;
  Eigen::Index n = 0;
  int analyses = 0;
  int searches = 0;
  // The ordering the current analysis was asked to use (empty: none; it may have
  // searched its own when that one filled too much), and the ordering it produced.
  std::vector<int> requested;
  CholeskyOrdering found;
  bool factor_valid = false;
  // Upper triangle of the last matrix, kept alive for CHOLMOD's view. Upper, not lower:
  // CHOLMOD's permuted supernodal factorization needs tril(PAPᵀ), one transpose away
  // from triu(A) but two from tril(A) (cholmod_factorize.c: "the fastest option").
  SparseMatrix upper;
  // The factor rounded to single precision (solve_preconditioner), made when first asked
  // for after a factorization.
  mutable std::mutex single_mutex;
  mutable std::unique_ptr<SinglePrecisionFactor> single;

  Impl() {
    cholmod_start(&common);
    common.print = 0;
    common.error_handler = nullptr;
    common.final_ll = 1;  // keep L as LL^T (not LDL^T) so the factor size is comparable
  }
  ~Impl() {
    if (factor) cholmod_free_factor(&factor, &common);
    cholmod_finish(&common);
  }

  cholmod_sparse view() {
    cholmod_sparse s{};
    s.nrow = static_cast<size_t>(upper.rows());
    s.ncol = static_cast<size_t>(upper.cols());
    s.nzmax = static_cast<size_t>(upper.nonZeros());
    s.p = upper.outerIndexPtr();
    s.i = upper.innerIndexPtr();
    s.nz = nullptr;
    s.x = upper.valuePtr();
    s.z = nullptr;
    s.stype = 1;  // symmetric, upper triangle stored
    s.itype = CHOLMOD_INT;
    s.xtype = CHOLMOD_REAL;
    s.dtype = CHOLMOD_DOUBLE;
    s.sorted = 1;
    s.packed = 1;
    return s;
  }

  bool same_pattern() const {
    if (!factor || upper.rows() != n) return false;
    const auto nnz = static_cast<size_t>(upper.nonZeros());
    if (pattern_inner.size() != nnz) return false;
    return std::equal(pattern_outer.begin(), pattern_outer.end(), upper.outerIndexPtr()) &&
           std::equal(pattern_inner.begin(), pattern_inner.end(), upper.innerIndexPtr());
  }
};

SparseCholesky::SparseCholesky() : impl_(std::make_unique<Impl>()) {}
SparseCholesky::~SparseCholesky() = default;

bool SparseCholesky::factorize(const SparseMatrix& A) { return factorize(A, nullptr); }

bool SparseCholesky::factorize(const SparseMatrix& A, const CholeskyOrdering* ordering,
                               double max_fill_growth) {
  if (A.rows() != A.cols()) throw SolverError("SparseCholesky: matrix is not square");
  impl_->upper = A.triangularView<Eigen::Upper>();
  impl_->upper.makeCompressed();
  return factorize_upper(A.rows(), ordering, max_fill_growth);
}

bool SparseCholesky::factorize_plus_diagonal(const SparseMatrix& A, const VecX& d,
                                             const CholeskyOrdering* ordering,
                                             double max_fill_growth) {
  if (A.rows() != A.cols()) throw SolverError("SparseCholesky: matrix is not square");
  if (d.size() != A.rows()) throw SolverError("SparseCholesky: diagonal has the wrong size");
  SparseMatrix& upper = impl_->upper;
  upper = A.triangularView<Eigen::Upper>();
  upper.makeCompressed();
  // In a compressed upper triangle with sorted rows the diagonal entry ends its column.
  for (Eigen::Index j = 0; j < upper.cols(); ++j) {
    const int end = upper.outerIndexPtr()[j + 1];
    if (end == upper.outerIndexPtr()[j] || upper.innerIndexPtr()[end - 1] != j) {
      // A diagonal entry is not stored: the sum's pattern has one more entry.
      return factorize(SparseMatrix(A + diagonal_matrix(d)), ordering, max_fill_growth);
    }
    upper.valuePtr()[end - 1] += d[j];
  }
  return factorize_upper(A.rows(), ordering, max_fill_growth);
}

bool SparseCholesky::factorize_upper(Eigen::Index n, const CholeskyOrdering* ordering,
                                     double max_fill_growth) {
  auto& d = *impl_;
  {
    const std::lock_guard<std::mutex> lock(d.single_mutex);
    d.single.reset();
  }
  cholmod_sparse s = d.view();
  if (ordering && static_cast<Eigen::Index>(ordering->permutation.size()) != n) ordering = nullptr;
  const std::vector<int> no_ordering;
  const std::vector<int>& wanted = ordering ? ordering->permutation : no_ordering;
  if (!d.same_pattern() || d.requested != wanted) {
    if (d.factor) cholmod_free_factor(&d.factor, &d.common);
    d.requested = wanted;
    if (ordering) {
      // Only the given permutation (CHOLMOD's method 0), then the etree postorder.
      const int methods = d.common.nmethods;
      d.common.nmethods = 1;
      d.factor = cholmod_analyze_p(&s, const_cast<int*>(ordering->permutation.data()), nullptr, 0,
                                   &d.common);
      d.common.nmethods = methods;
      if (d.factor && !(d.common.lnz <= max_fill_growth * ordering->factor_nonzeros))
        cholmod_free_factor(&d.factor, &d.common);
    }
    if (!d.factor) {
      d.factor = cholmod_analyze(&s, &d.common);
      ++d.searches;
    }
    if (!d.factor) throw SolverError("SparseCholesky: symbolic analysis failed");
    d.found.permutation.assign(static_cast<const int*>(d.factor->Perm),
                               static_cast<const int*>(d.factor->Perm) + d.factor->n);
    d.found.factor_nonzeros = d.common.lnz;
    d.pattern_outer.assign(d.upper.outerIndexPtr(), d.upper.outerIndexPtr() + d.upper.cols() + 1);
    d.pattern_inner.assign(d.upper.innerIndexPtr(), d.upper.innerIndexPtr() + d.upper.nonZeros());
    d.n = n;
    ++d.analyses;
  }
  const int ok = cholmod_factorize(&s, d.factor, &d.common);
  d.factor_valid = ok && d.common.status == CHOLMOD_OK && d.factor->minor == d.factor->n;
  return d.factor_valid;
}

VecX SparseCholesky::solve(const VecX& b) const {
  auto& d = *impl_;
  if (!d.factor_valid) throw SolverError("SparseCholesky: solve without a valid factorization");
  if (b.size() != d.n) throw SolverError("SparseCholesky: right-hand side has the wrong size");
  cholmod_dense rhs{};
  rhs.nrow = static_cast<size_t>(b.size());
  rhs.ncol = 1;
  rhs.nzmax = rhs.nrow;
  rhs.d = rhs.nrow;
  rhs.x = const_cast<double*>(b.data());
  rhs.z = nullptr;
  rhs.xtype = CHOLMOD_REAL;
  rhs.dtype = CHOLMOD_DOUBLE;
  cholmod_dense* x = cholmod_solve(CHOLMOD_A, d.factor, &rhs, &d.common);
  if (!x) throw SolverError("SparseCholesky: solve failed");
  VecX out = Eigen::Map<const VecX>(static_cast<const double*>(x->x), b.size());
  cholmod_free_dense(&x, &d.common);
  return out;
}

VecX SparseCholesky::solve_preconditioner(const VecX& b) const {
  auto& d = *impl_;
  if (!d.factor_valid) throw SolverError("SparseCholesky: solve without a valid factorization");
  if (!d.factor->is_super) return solve(b);
  if (b.size() != d.n) throw SolverError("SparseCholesky: right-hand side has the wrong size");
  const SinglePrecisionFactor* single = nullptr;
  {
    const std::lock_guard<std::mutex> lock(d.single_mutex);
    if (!d.single) d.single = std::make_unique<SinglePrecisionFactor>(supernodal_view());
    single = d.single.get();
  }
  return single->apply(b);
}

SupernodalFactorView SparseCholesky::supernodal_view() const {
  const auto& d = *impl_;
  SupernodalFactorView view;
  if (!d.factor_valid || !d.factor->is_super) return view;
  const cholmod_factor& f = *d.factor;
  view.n = static_cast<Eigen::Index>(f.n);
  view.supernodes = static_cast<int>(f.nsuper);
  view.super = static_cast<const int*>(f.super);
  view.row_start = static_cast<const int*>(f.pi);
  view.value_start = static_cast<const int*>(f.px);
  view.rows = static_cast<const int*>(f.s);
  view.values = static_cast<const double*>(f.x);
  view.permutation = static_cast<const int*>(f.Perm);
  return view;
}

MatX SparseCholesky::solve_columns(const MatX& B) const {
  MatX X(B.rows(), B.cols());
  for (Eigen::Index j = 0; j < B.cols(); ++j) X.col(j) = solve(VecX(B.col(j)));
  return X;
}

int SparseCholesky::symbolic_analyses() const { return impl_->analyses; }
int SparseCholesky::ordering_searches() const { return impl_->searches; }
const CholeskyOrdering& SparseCholesky::ordering() const { return impl_->found; }

std::int64_t SparseCholesky::factor_nonzeros() const {
  const auto* f = impl_->factor;
  if (!f) return 0;
  return static_cast<std::int64_t>(f->is_super ? f->xsize : f->nzmax);
}

Eigen::Index SparseCholesky::size() const { return impl_->n; }

namespace {

/// The diagonal of S of ShiftSequence, max(|A_ii|, floor · mean|A_ii|) / mean|A_ii|, and
/// that mean.
VecX shift_scaling_diagonal(const SparseMatrix& A, double diagonal_floor, double& mean_diag) {
  const VecX diag = A.diagonal().cwiseAbs();
  mean_diag = diag.mean();
  if (!(mean_diag > 0.0) || !std::isfinite(mean_diag)) mean_diag = 1.0;
  // The shift of DOF i is δ·max(|A_ii|, floor)/mean|A_ii|: each DOF is shifted relative to
  // its own stiffness (Levenberg–Marquardt scaling), so that soft DOFs (a garment
  // sliding on a body many times stiffer) are not swamped by a shift sized for the
  // stiff ones; δ is the shift at a DOF of mean stiffness.
  VecX scaling(A.rows());
  for (Eigen::Index i = 0; i < A.rows(); ++i)
    scaling[i] =
        std::isfinite(diag[i]) ? std::max(diag[i], diagonal_floor * mean_diag) / mean_diag : 1.0;
  return scaling;
}

}  // namespace

std::optional<double> factorize_shifted(SparseCholesky& cholesky, const SparseMatrix& A,
                                        const ShiftSequence& shifts, int& factorizations,
                                        double* last_shift, const CholeskyOrdering* ordering) {
  if (shifts.try_unshifted) {
    ++factorizations;
    if (cholesky.factorize(A, ordering)) return 0.0;
  }
  double mean_diag = 1.0;
  const VecX scaling_diagonal = shift_scaling_diagonal(A, shifts.diagonal_floor, mean_diag);
  double shift = shifts.initial * mean_diag;
  if (shifts.try_unshifted && shifts.estimate_steps > 0) {
    const double theta = lowest_ritz_value(A, scaling_diagonal, shifts.estimate_steps);
    if (std::isfinite(theta)) shift = std::max(shift, -shifts.estimate_margin * theta);
  }
  for (int k = 0; k < shifts.attempts; ++k) {
    if (last_shift) *last_shift = shift;
    ++factorizations;
    if (cholesky.factorize_plus_diagonal(A, shift * scaling_diagonal, ordering)) return shift;
    shift *= shifts.growth;
  }
  return std::nullopt;
}

bool factorize_with_shift(SparseCholesky& cholesky, const SparseMatrix& A, double shift,
                          const CholeskyOrdering* ordering, double diagonal_floor) {
  if (shift == 0.0) return cholesky.factorize(A, ordering);
  double mean_diag = 1.0;
  return cholesky.factorize_plus_diagonal(
      A, shift * shift_scaling_diagonal(A, diagonal_floor, mean_diag), ordering);
}

}  // namespace tightfit
