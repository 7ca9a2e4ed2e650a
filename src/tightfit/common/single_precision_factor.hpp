#pragma once
/// A supernodal Cholesky factor L (A ≈ P'LL'P) with its entries rounded to single
/// precision, for preconditioning: apply() computes (L̃L̃')⁻¹ in the ordering of A, L̃ the
/// rounded L, with double-precision arithmetic. L̃L̃' is symmetric positive definite and
/// within about 1e-7 (relative) of the factorized matrix, so a Krylov method
/// preconditioned with it converges as with the exact factor, while each application
/// reads half the bytes of a double-precision triangular solve — which is bound by
/// memory bandwidth, not arithmetic, at the sizes tightfit factorizes.
#include <cstdint>
#include <vector>

#include "tightfit/common/subtree_partition.hpp"
#include "tightfit/common/types.hpp"

namespace tightfit {

/// The arrays of a supernodal factor as CHOLMOD stores it (cholmod_factor with
/// is_super): supernode s holds columns [super[s], super[s+1]) of L, its row indices
/// rows[row_start[s] .. row_start[s+1]) (the first ones those columns themselves), and a
/// dense column-major block of (row count) × (column count) values from
/// values[value_start[s]]. permutation[k]: the row of A that is row k of L.
struct SupernodalFactorView {
  Eigen::Index n = 0;
  int supernodes = 0;
  const int* super = nullptr;        ///< supernodes + 1 entries
  const int* row_start = nullptr;    ///< supernodes + 1 entries
  const int* value_start = nullptr;  ///< supernodes + 1 entries
  const int* rows = nullptr;
  const double* values = nullptr;
  const int* permutation = nullptr;  ///< n entries
};

/// Which arithmetic kernels apply() uses: the fastest the processor offers (AVX2/FMA
/// where present, chosen at run time), or the portable ones (the same operator up to
/// round-off; for tests).
enum class FactorKernels { kFastest, kPortable };

class SinglePrecisionFactor {
 public:
  SinglePrecisionFactor() = default;
  /// Copies the structure and rounds the values of `factor`. With `threads` > 1 (0:
  /// thread_count()) and a factor of at least kParallelMinimumValues values, the
  /// supernodal elimination tree is split into that many parts of independent subtrees
  /// (partition_subtrees) where that shortens the sweeps' critical path to at most
  /// kParallelWorth of the work; apply() then runs the parts on their own threads.
  explicit SinglePrecisionFactor(const SupernodalFactorView& factor,
                                 FactorKernels kernels = FactorKernels::kFastest, int threads = 0);

  /// x = P'(L̃L̃')⁻¹P b. `b` has n() rows. The result is a function of b and of the
  /// partition made at construction (the same bits on every call, whatever the load).
  VecX apply(const VecX& b) const;
  /// The subtrees apply() runs in parallel (no parts: serial sweeps).
  const SubtreePartition& partition() const { return partition_; }
  static constexpr double kParallelMinimumValues = 262144;
  static constexpr double kParallelWorth = 0.8;
  Eigen::Index n() const { return n_; }
  /// Stored single-precision values (the supernodes' dense blocks).
  std::int64_t stored_values() const { return static_cast<std::int64_t>(values_.size()); }

 private:
  Eigen::Index n_ = 0;
  std::vector<int> super_, row_start_, value_start_, rows_, permutation_;
  std::vector<float> values_;
  /// The parts of the supernodal elimination tree for parallel sweeps.
  SubtreePartition partition_supernodes(int parts) const;
  /// Eliminates supernode s forward in y with workspace w (its row count) and adds what
  /// the rows below receive: to y for rows before `end_column`, else to `beyond`.
  void forward_supernode(int s, VecX& y, double* w, int end_column, VecX& beyond) const;
  /// Back substitution of supernode s in y (its rows below already solved).
  void backward_supernode(int s, VecX& y, double* w) const;

  int max_rows_ = 0;  // the largest supernode's row count (workspace size)
  bool portable_ = false;
  SubtreePartition partition_;
};

}  // namespace tightfit
