#pragma once
/// Preconditioned conjugate gradients truncated at negative curvature (Steihaug), for
/// Newton–Krylov steps: A x = b with A the Newton matrix at the current state (symmetric,
/// positive definite near a stable equilibrium but possibly indefinite far from it) and
/// M⁻¹ a factorization of a nearby Newton matrix. Every iterate x_k (from x_0 = 0) is a
/// descent direction for the quadratic model −bᵀx + ½ xᵀA x, so with b = −∇U the result is
/// a descent direction of U. On a direction of non-positive curvature the iteration stops
/// and returns the last iterate (at the first iteration: the preconditioned direction
/// M⁻¹ b, the chord step).
#include "tightfit/common/preconditioned_gmres.hpp"

namespace tightfit {

struct TruncatedCgOptions {
  double relative_tolerance = 1e-3;  ///< stop when ‖b − A x‖ ≤ this · ‖b‖
  int max_iterations = 20;           ///< products with A
};

struct TruncatedCgReport {
  bool converged = false;           ///< the tolerance was reached
  bool negative_curvature = false;  ///< stopped on a direction p with pᵀA p ≤ 0
  int iterations = 0;               ///< products with A
  double relative_residual = 0.0;   ///< ‖b − A x‖ / ‖b‖ of the returned x (by the CG
                                    ///< recurrence: equal up to round-off)
};

/// Returns x ≈ A⁻¹ b (see above); `preconditioner` applies M⁻¹ (symmetric positive
/// definite). Throws std::invalid_argument for invalid options.
VecX truncated_cg(const LinearOperator& A, const LinearOperator& preconditioner, const VecX& b,
                  TruncatedCgReport& report, const TruncatedCgOptions& options = {});

}  // namespace tightfit
