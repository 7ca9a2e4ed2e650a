#include "tightfit/common/sparse_cholesky.hpp"

#include <cholmod.h>

#include <algorithm>
#include <cmath>
#include <mutex>
#include <vector>

#include "tightfit/common/error.hpp"
#include "tightfit/common/lanczos.hpp"
#include "tightfit/common/parallel.hpp"
#include "tightfit/common/single_precision_factor.hpp"

namespace tightfit {
namespace {

/// CHOLMOD's view of a compressed symmetric n×n matrix, one triangle stored (stype 1:
/// upper, −1: lower), its row indices sorted within columns or not.
cholmod_sparse symmetric_view(Eigen::Index n, std::size_t nonzeros, int* outer, int* inner,
                              double* values, int stype, bool sorted) {
  cholmod_sparse s{};
  s.nrow = static_cast<size_t>(n);
  s.ncol = static_cast<size_t>(n);
  s.nzmax = nonzeros;
  s.p = outer;
  s.i = inner;
  s.x = values;
  s.stype = stype;
  s.itype = CHOLMOD_INT;
  s.xtype = CHOLMOD_REAL;
  s.dtype = CHOLMOD_DOUBLE;
  s.sorted = sorted ? 1 : 0;
  s.packed = 1;
  return s;
}

/// Below this many entries the permuted copy of a matrix is gathered on one thread.
constexpr std::int64_t kParallelGatherMinimum = 65536;

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
  // The pattern of the matrix the current analysis was made for (as given: both
  // triangles, or one).
  std::vector<int> pattern_outer;
  std::vector<int> pattern_inner;
  bool full_diagonal = false;  // every diagonal entry is in that pattern
  Eigen::Index n = 0;
  int analyses = 0;
  int searches = 0;
  // The ordering the current analysis was asked to use (empty: none; it may have
  // searched its own when that one filled too much), and the ordering it produced.
  std::vector<int> requested;
  CholeskyOrdering found;
  bool factor_valid = false;
  // Upper triangle of the matrix (the analysis, and the simplicial factorization, read
  // it). Upper, not lower: CHOLMOD factorizes tril(PAPᵀ), one transpose away from triu(A)
  // but two from tril(A) (cholmod_factorize.c: "the fastest option").
  SparseMatrix upper;
  // For a supernodal factor, tril(PAPᵀ) itself (P the analysis' permutation), the matrix
  // cholmod_factorize would make by a serial permuted transpose on every call: its
  // pattern is made once per analysis (at its second factorization; empty before), and
  // its values are gathered from A's in parallel, lower_values[k] =
  // A.valuePtr()[lower_source[k]]; lower_diagonal[j] is the slot of A's diagonal entry
  // (j, j) (for factorize_plus_diagonal).
  std::vector<int> lower_outer, lower_inner, lower_source, lower_diagonal;
  std::vector<double> lower_values;
  bool pattern_factorized = false;  // the current analysis has been factorized before
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

  cholmod_sparse upper_view() {
    return symmetric_view(upper.cols(), static_cast<std::size_t>(upper.nonZeros()),
                          upper.outerIndexPtr(), upper.innerIndexPtr(), upper.valuePtr(), 1, true);
  }
  cholmod_sparse lower_view() {
    return symmetric_view(n, lower_values.size(), lower_outer.data(), lower_inner.data(),
                          lower_values.data(), -1, false);
  }

  bool same_pattern(const SparseMatrix& A) const {
    if (!factor || A.rows() != n) return false;
    if (pattern_inner.size() != static_cast<std::size_t>(A.nonZeros())) return false;
    return std::equal(pattern_outer.begin(), pattern_outer.end(), A.outerIndexPtr()) &&
           std::equal(pattern_inner.begin(), pattern_inner.end(), A.innerIndexPtr());
  }

  void build_permuted_lower(const SparseMatrix& A);
  void gather_permuted_lower(const SparseMatrix& A, const VecX* diagonal);
};

void SparseCholesky::Impl::build_permuted_lower(const SparseMatrix& A) {
  const auto* perm = static_cast<const int*>(factor->Perm);
  std::vector<int> inverse(static_cast<std::size_t>(n));
  for (int k = 0; k < static_cast<int>(n); ++k) inverse[static_cast<std::size_t>(perm[k])] = k;
  const int* outer = A.outerIndexPtr();
  const int* inner = A.innerIndexPtr();
  // A's upper entries (i ≤ j: the first of each sorted column) go to column
  // min(inverse[i], inverse[j]), row max(…), in the order met (cholmod_super_numeric
  // assigns each entry to its place in L: the order within a column does not matter).
  lower_outer.assign(static_cast<std::size_t>(n) + 1, 0);
  for (int j = 0; j < static_cast<int>(n); ++j) {
    const int b = inverse[static_cast<std::size_t>(j)];
    for (int p = outer[j]; p < outer[j + 1] && inner[p] <= j; ++p)
      ++lower_outer[static_cast<std::size_t>(
                        std::min(inverse[static_cast<std::size_t>(inner[p])], b)) +
                    1];
  }
  for (std::size_t c = 0; c < static_cast<std::size_t>(n); ++c)
    lower_outer[c + 1] += lower_outer[c];
  const auto entries = static_cast<std::size_t>(lower_outer.back());
  lower_inner.resize(entries);
  lower_source.resize(entries);
  lower_values.resize(entries);
  lower_diagonal.assign(static_cast<std::size_t>(n), -1);
  std::vector<int> next(lower_outer.begin(), lower_outer.end() - 1);
  for (int j = 0; j < static_cast<int>(n); ++j) {
    const int b = inverse[static_cast<std::size_t>(j)];
    for (int p = outer[j]; p < outer[j + 1] && inner[p] <= j; ++p) {
      const int a = inverse[static_cast<std::size_t>(inner[p])];
      const auto slot = static_cast<std::size_t>(next[static_cast<std::size_t>(std::min(a, b))]++);
      lower_inner[slot] = std::max(a, b);
      lower_source[slot] = p;
      if (inner[p] == j) lower_diagonal[static_cast<std::size_t>(j)] = static_cast<int>(slot);
    }
  }
}

void SparseCholesky::Impl::gather_permuted_lower(const SparseMatrix& A, const VecX* diagonal) {
  const double* values = A.valuePtr();
  parallel_for(
      static_cast<std::int64_t>(lower_values.size()),
      [&](std::int64_t k) {
        lower_values[static_cast<std::size_t>(k)] =
            values[lower_source[static_cast<std::size_t>(k)]];
      },
      kParallelGatherMinimum);
  if (diagonal)
    for (Eigen::Index j = 0; j < n; ++j)
      lower_values[static_cast<std::size_t>(lower_diagonal[static_cast<std::size_t>(j)])] +=
          (*diagonal)[j];
}

SparseCholesky::SparseCholesky() : impl_(std::make_unique<Impl>()) {}
SparseCholesky::~SparseCholesky() = default;

bool SparseCholesky::factorize(const SparseMatrix& A) { return factorize(A, nullptr); }

bool SparseCholesky::factorize(const SparseMatrix& A, const CholeskyOrdering* ordering,
                               double max_fill_growth) {
  return factorize_matrix(A, nullptr, ordering, max_fill_growth);
}

bool SparseCholesky::factorize_plus_diagonal(const SparseMatrix& A, const VecX& d,
                                             const CholeskyOrdering* ordering,
                                             double max_fill_growth) {
  if (d.size() != A.rows()) throw SolverError("SparseCholesky: diagonal has the wrong size");
  return factorize_matrix(A, &d, ordering, max_fill_growth);
}

bool SparseCholesky::factorize_matrix(const SparseMatrix& A, const VecX* diagonal,
                                      const CholeskyOrdering* ordering, double max_fill_growth) {
  if (A.rows() != A.cols()) throw SolverError("SparseCholesky: matrix is not square");
  if (!A.isCompressed()) {
    SparseMatrix compressed = A;
    compressed.makeCompressed();
    return factorize_matrix(compressed, diagonal, ordering, max_fill_growth);
  }
  auto& d = *impl_;
  {
    const std::lock_guard<std::mutex> lock(d.single_mutex);
    d.single.reset();
  }
  d.factor_valid = false;
  const Eigen::Index n = A.rows();
  if (ordering && static_cast<Eigen::Index>(ordering->permutation.size()) != n) ordering = nullptr;
  const std::vector<int> no_ordering;
  const std::vector<int>& wanted = ordering ? ordering->permutation : no_ordering;
  const bool new_pattern = !d.same_pattern(A);
  bool full_diagonal = d.full_diagonal;
  if (new_pattern) {
    full_diagonal = true;
    for (Eigen::Index j = 0; j < n && full_diagonal; ++j) {
      const int* first = A.innerIndexPtr() + A.outerIndexPtr()[j];
      const int* last = A.innerIndexPtr() + A.outerIndexPtr()[j + 1];
      full_diagonal = std::binary_search(first, last, static_cast<int>(j));
    }
  }
  if (diagonal && !full_diagonal)
    // A diagonal entry is not stored: the sum's pattern has one more entry.
    return factorize(SparseMatrix(A + diagonal_matrix(*diagonal)), ordering, max_fill_growth);
  const auto copy_upper = [&] {
    d.upper = A.triangularView<Eigen::Upper>();
    d.upper.makeCompressed();
  };
  const bool analyse = new_pattern || d.requested != wanted;
  if (analyse) {
    copy_upper();
    d.requested = wanted;
    analyze(ordering, max_fill_growth);
    d.pattern_outer.assign(A.outerIndexPtr(), A.outerIndexPtr() + n + 1);
    d.pattern_inner.assign(A.innerIndexPtr(), A.innerIndexPtr() + A.nonZeros());
    d.full_diagonal = full_diagonal;
    d.n = n;
    d.lower_outer.clear();
    d.pattern_factorized = false;
  }
  int ok = 0;
  // The first factorization of a pattern goes through cholmod_factorize (a pattern is
  // often factorized once: garment vertices slide onto other faces between Newton
  // steps); from the second on, a supernodal factorization gathers tril(PAPᵀ) itself.
  if (d.factor->is_super && d.pattern_factorized) {
    if (d.lower_outer.empty()) {
      d.build_permuted_lower(A);
      d.upper = SparseMatrix();
    }
    d.gather_permuted_lower(A, diagonal);
    cholmod_sparse lower = d.lower_view();
    double zero[2] = {0.0, 0.0};
    ok = cholmod_super_numeric(&lower, nullptr, zero, d.factor, &d.common);
  } else {
    if (!analyse) copy_upper();
    if (diagonal)
      // In a compressed upper triangle with sorted rows the diagonal entry ends its column.
      for (Eigen::Index j = 0; j < n; ++j)
        d.upper.valuePtr()[d.upper.outerIndexPtr()[j + 1] - 1] += (*diagonal)[j];
    cholmod_sparse upper = d.upper_view();
    ok = cholmod_factorize(&upper, d.factor, &d.common);
  }
  d.pattern_factorized = true;
  d.factor_valid = ok && d.common.status == CHOLMOD_OK && d.factor->minor == d.factor->n;
  return d.factor_valid;
}

void SparseCholesky::analyze(const CholeskyOrdering* ordering, double max_fill_growth) {
  auto& d = *impl_;
  cholmod_sparse s = d.upper_view();
  if (d.factor) cholmod_free_factor(&d.factor, &d.common);
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
  ++d.analyses;
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
