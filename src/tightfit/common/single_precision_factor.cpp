#include "tightfit/common/single_precision_factor.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "tightfit/common/parallel.hpp"

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#define TIGHTFIT_X86_KERNELS 1
#endif

namespace tightfit {
namespace {

// The kernels of the triangular solves, on four columns of a supernode's block at once
// (c[0..3], single precision) against the double-precision work vector w:
// w -= Σ_k a_k c_k (forward) and out_k = c_k · w (backward). Portable loops, and
// AVX2/FMA versions chosen at run time where the processor has them: the build targets
// baseline x86-64, whose SSE2 conversions and multiplications are too slow to gain from
// the halved memory traffic.
using Columns = const float* const*;

void subtract_columns_portable(int m, Columns c, const double* a, double* w) {
  for (int i = 0; i < m; ++i)
    w[i] -= (a[0] * static_cast<double>(c[0][i]) + a[1] * static_cast<double>(c[1][i])) +
            (a[2] * static_cast<double>(c[2][i]) + a[3] * static_cast<double>(c[3][i]));
}

void dot_columns_portable(int m, Columns c, const double* w, double* out) {
  for (int k = 0; k < 4; ++k) {
    double sum = 0.0;
    for (int i = 0; i < m; ++i) sum += static_cast<double>(c[k][i]) * w[i];
    out[k] = sum;
  }
}

#ifdef TIGHTFIT_X86_KERNELS
__attribute__((target("avx2,fma"))) void subtract_columns_avx2(int m, Columns c, const double* a,
                                                               double* w) {
  const __m256d a0 = _mm256_set1_pd(a[0]), a1 = _mm256_set1_pd(a[1]);
  const __m256d a2 = _mm256_set1_pd(a[2]), a3 = _mm256_set1_pd(a[3]);
  int i = 0;
  for (; i + 4 <= m; i += 4) {
    __m256d s = _mm256_mul_pd(a0, _mm256_cvtps_pd(_mm_loadu_ps(c[0] + i)));
    s = _mm256_fmadd_pd(a1, _mm256_cvtps_pd(_mm_loadu_ps(c[1] + i)), s);
    __m256d t = _mm256_mul_pd(a2, _mm256_cvtps_pd(_mm_loadu_ps(c[2] + i)));
    t = _mm256_fmadd_pd(a3, _mm256_cvtps_pd(_mm_loadu_ps(c[3] + i)), t);
    _mm256_storeu_pd(w + i, _mm256_sub_pd(_mm256_loadu_pd(w + i), _mm256_add_pd(s, t)));
  }
  for (; i < m; ++i)
    w[i] -= (a[0] * static_cast<double>(c[0][i]) + a[1] * static_cast<double>(c[1][i])) +
            (a[2] * static_cast<double>(c[2][i]) + a[3] * static_cast<double>(c[3][i]));
}

__attribute__((target("avx2,fma"))) void dot_columns_avx2(int m, Columns c, const double* w,
                                                          double* out) {
  __m256d s0 = _mm256_setzero_pd(), s1 = _mm256_setzero_pd();
  __m256d s2 = _mm256_setzero_pd(), s3 = _mm256_setzero_pd();
  int i = 0;
  for (; i + 4 <= m; i += 4) {
    const __m256d x = _mm256_loadu_pd(w + i);
    s0 = _mm256_fmadd_pd(_mm256_cvtps_pd(_mm_loadu_ps(c[0] + i)), x, s0);
    s1 = _mm256_fmadd_pd(_mm256_cvtps_pd(_mm_loadu_ps(c[1] + i)), x, s1);
    s2 = _mm256_fmadd_pd(_mm256_cvtps_pd(_mm_loadu_ps(c[2] + i)), x, s2);
    s3 = _mm256_fmadd_pd(_mm256_cvtps_pd(_mm_loadu_ps(c[3] + i)), x, s3);
  }
  // Horizontal sums of the four accumulators: out = (Σ s0, Σ s1, Σ s2, Σ s3).
  const __m256d h01 = _mm256_hadd_pd(s0, s1), h23 = _mm256_hadd_pd(s2, s3);
  const __m256d sums =
      _mm256_add_pd(_mm256_permute2f128_pd(h01, h23, 0x20), _mm256_permute2f128_pd(h01, h23, 0x31));
  _mm256_storeu_pd(out, sums);
  for (; i < m; ++i)
    for (int k = 0; k < 4; ++k) out[k] += static_cast<double>(c[k][i]) * w[i];
}

#endif

struct Kernels {
  void (*subtract_columns)(int, Columns, const double*, double*) = subtract_columns_portable;
  void (*dot_columns)(int, Columns, const double*, double*) = dot_columns_portable;
};

Kernels choose_kernels() {
  Kernels k;
#ifdef TIGHTFIT_X86_KERNELS
  __builtin_cpu_init();
  if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma")) {
    k.subtract_columns = subtract_columns_avx2;
    k.dot_columns = dot_columns_avx2;
  }
#endif
  return k;
}

const Kernels& kernels(bool portable) {
  static const Kernels fastest = choose_kernels();
  static const Kernels portable_kernels;
  return portable ? portable_kernels : fastest;
}

/// Columns of a supernode's block are eliminated in groups of this many.
constexpr int kGroup = 4;

/// The group of `group` (≤ kGroup) columns from column j0 of a supernode's block of
/// `rows` rows, each from row `below` on; the kernels' missing columns repeat the last.
void group_columns(const float* block, int rows, int j0, int group, int below,
                   const float* (&c)[kGroup]) {
  for (int g = 0; g < kGroup; ++g)
    c[g] = block + static_cast<std::ptrdiff_t>(j0 + std::min(g, group - 1)) * rows + below;
}

/// Forward elimination of one supernode in w (its rows, w[j] for its columns first):
/// w[j] /= L_jj, then the rows below subtract L_ij w[j], four columns at a time.
void eliminate_forward(const Kernels& k, const float* block, int rows, int columns, double* w) {
  for (int j0 = 0; j0 < columns; j0 += kGroup) {
    const int group = std::min(kGroup, columns - j0);
    // Within the group: the small triangle, one column after the other.
    for (int j = j0; j < j0 + group; ++j) {
      const float* column = block + static_cast<std::ptrdiff_t>(j) * rows;
      w[j] /= static_cast<double>(column[j]);
      for (int i = j + 1; i < j0 + group; ++i) w[i] -= static_cast<double>(column[i]) * w[j];
    }
    // Below the group: all its columns at once (missing ones with zero weight).
    const int below = j0 + group;
    if (below < rows) {
      const float* c[kGroup];
      group_columns(block, rows, j0, group, below, c);
      double a[kGroup];
      for (int g = 0; g < kGroup; ++g) a[g] = g < group ? w[j0 + g] : 0.0;
      k.subtract_columns(rows - below, c, a, w + below);
    }
  }
}

/// Back substitution of one supernode in w (its rows; the rows below its columns hold
/// the solution already): w[j] = (w[j] − Σ_{i>j} L_ij w[i]) / L_jj, last group first.
void eliminate_backward(const Kernels& k, const float* block, int rows, int columns, double* w) {
  const int groups = (columns + kGroup - 1) / kGroup;
  for (int gi = groups - 1; gi >= 0; --gi) {
    const int j0 = gi * kGroup, group = std::min(kGroup, columns - j0), below = j0 + group;
    double dots[kGroup] = {0.0, 0.0, 0.0, 0.0};
    if (below < rows) {
      const float* c[kGroup];
      group_columns(block, rows, j0, group, below, c);
      k.dot_columns(rows - below, c, w + below, dots);
    }
    for (int j = below - 1; j >= j0; --j) {
      const float* column = block + static_cast<std::ptrdiff_t>(j) * rows;
      double sum = dots[j - j0];
      for (int i = j + 1; i < below; ++i) sum += static_cast<double>(column[i]) * w[i];
      w[j] = (w[j] - sum) / static_cast<double>(column[j]);
    }
  }
}

}  // namespace

SinglePrecisionFactor::SinglePrecisionFactor(const SupernodalFactorView& f, FactorKernels kernels,
                                             int threads)
    : n_(f.n), portable_(kernels == FactorKernels::kPortable) {
  if (f.n < 0 || f.supernodes < 0 ||
      (f.supernodes > 0 &&
       (!f.super || !f.row_start || !f.value_start || !f.rows || !f.values || !f.permutation)))
    throw std::invalid_argument("SinglePrecisionFactor: incomplete supernodal factor");
  const auto ns = static_cast<std::size_t>(f.supernodes);
  super_.assign(f.super, f.super + ns + 1);
  row_start_.assign(f.row_start, f.row_start + ns + 1);
  value_start_.assign(f.value_start, f.value_start + ns + 1);
  rows_.assign(f.rows, f.rows + row_start_[ns]);
  permutation_.assign(f.permutation, f.permutation + f.n);
  // CHOLMOD's value_start[supernodes] is the end of the last block.
  values_.resize(static_cast<std::size_t>(value_start_[ns]));
  parallel_for(
      static_cast<std::int64_t>(values_.size()),
      [&](std::int64_t k) {
        values_[static_cast<std::size_t>(k)] = static_cast<float>(f.values[k]);
      },
      static_cast<std::int64_t>(kParallelMinimumValues));
  for (std::size_t s = 0; s < ns; ++s)
    max_rows_ = std::max(max_rows_, row_start_[s + 1] - row_start_[s]);
  partition_ = partition_supernodes(threads > 0 ? threads : thread_count());
}

SubtreePartition SinglePrecisionFactor::partition_supernodes(int parts) const {
  const int supernodes = static_cast<int>(super_.size()) - 1;
  // The supernode holding each column, then each supernode's parent: the one holding
  // its first row below its own columns.
  std::vector<int> supernode_of(static_cast<std::size_t>(n_));
  for (int s = 0; s < supernodes; ++s)
    std::fill(supernode_of.begin() + super_[s], supernode_of.begin() + super_[s + 1], s);
  std::vector<int> parent(static_cast<std::size_t>(supernodes), -1);
  std::vector<double> work(static_cast<std::size_t>(supernodes));
  for (int s = 0; s < supernodes; ++s) {
    const int columns = super_[s + 1] - super_[s];
    const int rows = row_start_[s + 1] - row_start_[s];
    if (rows > columns)
      parent[static_cast<std::size_t>(s)] =
          supernode_of[static_cast<std::size_t>(rows_[row_start_[s] + columns])];
    // Both sweeps read the block and its row indices once.
    work[static_cast<std::size_t>(s)] =
        static_cast<double>(value_start_[s + 1] - value_start_[s]) + static_cast<double>(rows);
  }
  return partition_subtrees(parent, work, parts, kParallelMinimumValues, kParallelWorth);
}

void SinglePrecisionFactor::forward_supernode(int s, VecX& y, double* w, int end_column,
                                              VecX& beyond) const {
  const Kernels& k = kernels(portable_);
  const int first = super_[s], columns = super_[s + 1] - first;
  const int* row = rows_.data() + row_start_[s];
  const int rows = row_start_[s + 1] - row_start_[s];
  std::copy(y.data() + first, y.data() + first + columns, w);
  std::fill(w + columns, w + rows, 0.0);
  eliminate_forward(k, values_.data() + value_start_[s], rows, columns, w);
  std::copy(w, w + columns, y.data() + first);
  for (int i = columns; i < rows; ++i) (row[i] < end_column ? y : beyond)[row[i]] += w[i];
}

void SinglePrecisionFactor::backward_supernode(int s, VecX& y, double* w) const {
  const Kernels& k = kernels(portable_);
  const int first = super_[s], columns = super_[s + 1] - first;
  const int* row = rows_.data() + row_start_[s];
  const int rows = row_start_[s + 1] - row_start_[s];
  std::copy(y.data() + first, y.data() + first + columns, w);
  for (int i = columns; i < rows; ++i) w[i] = y[row[i]];
  eliminate_backward(k, values_.data() + value_start_[s], rows, columns, w);
  std::copy(w, w + columns, y.data() + first);
}

VecX SinglePrecisionFactor::apply(const VecX& b) const {
  if (b.size() != n_) throw std::invalid_argument("SinglePrecisionFactor: wrong right-hand side");
  VecX y(n_);
  for (Eigen::Index i = 0; i < n_; ++i) y[i] = b[permutation_[static_cast<std::size_t>(i)]];
  std::vector<double> w(static_cast<std::size_t>(max_rows_));
  const auto& parts = partition_.parts;
  const int part_count = static_cast<int>(parts.size());
  // Forward substitution L̃ z = y, supernode by supernode: the dense block's columns
  // eliminate into a local copy w of the supernode's rows, added back at the end. The
  // parts' subtrees first, each part on its own thread; what they add to rows of the top
  // goes to the part's own carry vector, summed into y in part order before the top.
  std::vector<VecX> carry(static_cast<std::size_t>(part_count));
  if (part_count > 0)
    run_on_threads(part_count, [&](int p) {
      VecX& mine = carry[static_cast<std::size_t>(p)];
      mine.setZero(n_);
      std::vector<double> work_rows(static_cast<std::size_t>(max_rows_));
      for (const SubtreeRange& range : parts[static_cast<std::size_t>(p)]) {
        const int end_column = super_[range.last + 1];
        for (int s = range.first; s <= range.last; ++s)
          forward_supernode(s, y, work_rows.data(), end_column, mine);
      }
    });
  for (const int s : partition_.top) {
    for (const VecX& c : carry)
      for (int j = super_[s]; j < super_[s + 1]; ++j) y[j] += c[j];
    forward_supernode(s, y, w.data(), static_cast<int>(n_), y);
  }
  // Back substitution L̃' x = z, in reverse: the top, then the parts' subtrees.
  for (auto s = partition_.top.rbegin(); s != partition_.top.rend(); ++s)
    backward_supernode(*s, y, w.data());
  if (part_count > 0)
    run_on_threads(part_count, [&](int p) {
      std::vector<double> work_rows(static_cast<std::size_t>(max_rows_));
      const auto& ranges = parts[static_cast<std::size_t>(p)];
      for (auto range = ranges.rbegin(); range != ranges.rend(); ++range)
        for (int s = range->last; s >= range->first; --s)
          backward_supernode(s, y, work_rows.data());
    });
  VecX x(n_);
  for (Eigen::Index i = 0; i < n_; ++i) x[permutation_[static_cast<std::size_t>(i)]] = y[i];
  return x;
}

}  // namespace tightfit
