#pragma once
/// Lanczos estimates of the lowest eigenvalue of a symmetric matrix, for choosing the
/// diagonal shift that makes an indefinite Newton matrix positive definite without a
/// search of failed factorizations (sparse_cholesky.hpp: ShiftSequence).
#include "tightfit/common/types.hpp"

namespace tightfit {

/// The smallest Ritz value θ of `steps` Lanczos steps on B = S^{−1/2} A S^{−1/2}, with A
/// symmetric (n×n, both triangles stored) and S = diag(`scaling`) (n, all > 0). θ is an
/// upper bound of the lowest eigenvalue of B (up to round-off) and tends to it as
/// `steps` grows, fastest when that eigenvalue is well separated from the rest:
/// A + δ S is positive definite only if δ > −θ. The start vector is fixed (no random
/// numbers), so the result is a function of A, S and `steps`. Stops early when the
/// Krylov space is invariant. Throws std::invalid_argument for mismatched sizes,
/// steps < 1 or a non-positive scaling.
double lowest_ritz_value(const SparseMatrix& A, const VecX& scaling, int steps);

}  // namespace tightfit
