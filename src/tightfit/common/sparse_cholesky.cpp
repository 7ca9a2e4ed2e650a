#include "tightfit/common/sparse_cholesky.hpp"

#include <cholmod.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "tightfit/common/error.hpp"
#include "tightfit/common/lanczos.hpp"

namespace tightfit {
namespace {

/// A search orders the graph of supervariables when there are at most this fraction of
/// the columns of them (with more, the smaller graph would save too little).
constexpr double kCompressionWorthwhile = 0.8;

/// CHOLMOD's view of a compressed symmetric matrix stored by its upper triangle (n×n,
/// `nonzeros` entries; `values` null: the pattern only). Nothing is copied.
cholmod_sparse upper_triangle_view(std::size_t n, std::size_t nonzeros, int* outer, int* inner,
                                   double* values) {
  cholmod_sparse s{};
  s.nrow = s.ncol = n;
  s.nzmax = nonzeros;
  s.p = outer;
  s.i = inner;
  s.x = values;
  s.stype = 1;
  s.itype = CHOLMOD_INT;
  s.xtype = values ? CHOLMOD_REAL : CHOLMOD_PATTERN;
  s.dtype = CHOLMOD_DOUBLE;
  s.sorted = 1;
  s.packed = 1;
  return s;
}

/// The analysis of a search and the nonzeros of its L.
struct Analysis {
  cholmod_factor* factor = nullptr;
  double factor_nonzeros = 0.0;
};

/// CHOLMOD's symbolic analysis of `a` with the given permutation (method 0 only; CHOLMOD
/// reads the permutation and does not write it).
Analysis analyze_with(cholmod_sparse& a, const std::vector<int>& permutation,
                      cholmod_common& common) {
  const int methods = common.nmethods;
  common.nmethods = 1;
  Analysis result{cholmod_analyze_p(&a, const_cast<int*>(permutation.data()), nullptr, 0, &common),
                  0.0};
  common.nmethods = methods;
  if (result.factor) result.factor_nonzeros = common.lnz;
  return result;
}

/// A fill-reducing ordering searched on the graph of supervariables: runs of
/// consecutive columns with the same pattern (the 3 DOFs of a body vertex, the 2 of a
/// garment vertex) become one node, so AMD and METIS see a graph with ~1/7 of the edges
/// (CHOLMOD orders the scalar graph: at full-body size its METIS search took as long as
/// the numeric factorization). CHOLMOD's strategy otherwise: AMD, then METIS when AMD's
/// ordering fills much (fl/lnz ≥ 500 and lnz/anz ≥ 5), the one with fewer nonzeros in L
/// kept. Patterns that hardly compress get CHOLMOD's own search.
Analysis search_ordering(cholmod_sparse& a, cholmod_common& common) {
  const auto n = static_cast<int>(a.ncol);
  cholmod_sparse* full = cholmod_copy(&a, 0, 0, &common);  // both triangles, pattern only
  if (!full) return {};
  const int* fp = static_cast<const int*>(full->p);
  const int* fi = static_cast<const int*>(full->i);
  std::vector<int> first;  // first column of each supervariable, then n
  std::vector<int> group(static_cast<size_t>(n));
  for (int j = 0; j < n; ++j) {
    const bool same = j > 0 && fp[j + 1] - fp[j] == fp[j] - fp[j - 1] &&
                      std::equal(fi + fp[j], fi + fp[j + 1], fi + fp[j - 1]);
    if (!same) first.push_back(j);
    group[static_cast<size_t>(j)] = static_cast<int>(first.size()) - 1;
  }
  const int groups = static_cast<int>(first.size());
  first.push_back(n);
  if (groups > kCompressionWorthwhile * n) {
    cholmod_free_sparse(&full, &common);
    Analysis own{cholmod_analyze(&a, &common), 0.0};
    if (own.factor) own.factor_nonzeros = common.lnz;
    return own;
  }
  // The upper triangle of the supervariable graph.
  std::vector<int> cp(static_cast<size_t>(groups) + 1, 0), ci;
  std::vector<int> seen(static_cast<size_t>(groups), -1);
  for (int g = 0; g < groups; ++g) {
    const int j = first[static_cast<size_t>(g)];
    for (int k = fp[j]; k < fp[j + 1]; ++k) {
      const int h = group[static_cast<size_t>(fi[k])];
      if (h <= g && seen[static_cast<size_t>(h)] != g) {
        seen[static_cast<size_t>(h)] = g;
        ci.push_back(h);
      }
    }
    std::sort(ci.begin() + cp[static_cast<size_t>(g)], ci.end());
    cp[static_cast<size_t>(g) + 1] = static_cast<int>(ci.size());
  }
  cholmod_free_sparse(&full, &common);
  cholmod_sparse graph =
      upper_triangle_view(static_cast<size_t>(groups), ci.size(), cp.data(), ci.data(), nullptr);

  // A supervariable ordering, expanded to the columns, analysed.
  const auto analyze_order = [&](bool metis) -> Analysis {
    std::vector<int> order(static_cast<size_t>(groups));
    const int ok = metis ? cholmod_metis(&graph, nullptr, 0, 0, order.data(), &common)
                         : cholmod_amd(&graph, nullptr, 0, order.data(), &common);
    if (!ok) return {};
    std::vector<int> permutation;
    permutation.reserve(static_cast<size_t>(n));
    for (int g : order)
      for (int j = first[static_cast<size_t>(g)]; j < first[static_cast<size_t>(g) + 1]; ++j)
        permutation.push_back(j);
    return analyze_with(a, permutation, common);
  };
  Analysis best = analyze_order(false);
  if (!best.factor) return best;
  const double flops = common.fl;
  const double anz = static_cast<double>(a.nzmax);
  if (flops / best.factor_nonzeros >= 500.0 && best.factor_nonzeros / anz >= 5.0) {
    Analysis nested = analyze_order(true);
    if (nested.factor && nested.factor_nonzeros < best.factor_nonzeros) std::swap(best, nested);
    if (nested.factor) cholmod_free_factor(&nested.factor, &common);
  }
  return best;
}

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
    return upper_triangle_view(static_cast<size_t>(upper.rows()),
                               static_cast<size_t>(upper.nonZeros()), upper.outerIndexPtr(),
                               upper.innerIndexPtr(), upper.valuePtr());
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
  cholmod_sparse s = d.view();
  if (ordering && static_cast<Eigen::Index>(ordering->permutation.size()) != n) ordering = nullptr;
  const std::vector<int> no_ordering;
  const std::vector<int>& wanted = ordering ? ordering->permutation : no_ordering;
  if (!d.same_pattern() || d.requested != wanted) {
    if (d.factor) cholmod_free_factor(&d.factor, &d.common);
    d.requested = wanted;
    Analysis analysis;
    if (ordering) {
      // Only the given permutation (CHOLMOD's method 0), then the etree postorder.
      analysis = analyze_with(s, ordering->permutation, d.common);
      if (analysis.factor &&
          !(analysis.factor_nonzeros <= max_fill_growth * ordering->factor_nonzeros))
        cholmod_free_factor(&analysis.factor, &d.common);
    }
    if (!analysis.factor) {
      analysis = search_ordering(s, d.common);
      ++d.searches;
    }
    d.factor = analysis.factor;
    if (!d.factor) throw SolverError("SparseCholesky: symbolic analysis failed");
    d.found.permutation.assign(static_cast<const int*>(d.factor->Perm),
                               static_cast<const int*>(d.factor->Perm) + d.factor->n);
    d.found.factor_nonzeros = analysis.factor_nonzeros;
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
