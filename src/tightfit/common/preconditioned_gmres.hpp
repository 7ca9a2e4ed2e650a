#pragma once
/// Restarted GMRES with right preconditioning, for linear systems A x = b whose matrix is
/// close to one that is already factorized (the adjoint's exact equilibrium Hessian,
/// preconditioned by the Cholesky factor of Newton's PSD-projected one). A needs not be
/// symmetric or definite; with right preconditioning the residual that is monitored is
/// the true residual ‖b − A x‖ (not a preconditioned one), so the tolerance means what it
/// says.
#include <functional>

#include "tightfit/common/types.hpp"

namespace tightfit {

/// y = Op(x) for vectors of length n.
using LinearOperator = std::function<VecX(const VecX&)>;

struct GmresOptions {
  double relative_tolerance = 1e-12;  ///< stop when ‖b − A x‖ ≤ this · ‖b‖
  int max_iterations = 200;           ///< matrix-vector products with A, in total
  int restart = 40;                   ///< Krylov basis size before a restart
};

struct GmresReport {
  bool converged = false;
  int iterations = 0;              ///< products with A
  double relative_residual = 0.0;  ///< ‖b − A x‖ / ‖b‖ of the returned x (true residual)
};

/// Solves A x = b; `x` holds the initial guess on entry (resized to zero when its size
/// differs from b's) and the solution on return. `preconditioner` applies M⁻¹ ≈ A⁻¹.
/// Throws std::invalid_argument for invalid options.
GmresReport preconditioned_gmres(const LinearOperator& A, const LinearOperator& preconditioner,
                                 const VecX& b, VecX& x, const GmresOptions& options = {});

}  // namespace tightfit
