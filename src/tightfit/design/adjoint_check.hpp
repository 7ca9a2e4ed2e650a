#pragma once
/// Checks the adjoint design gradient against finite differences of the whole pipeline
/// p → Xbar(p) → equilibrium q(p) → T: for random directions d,
///   FD = [8(T(p+hd) − T(p−hd)) − (T(p+2hd) − T(p−2hd))] / (12h)
/// (fourth-order central difference), every sample re-solved to the simulation's
/// tolerance warm-started from the equilibrium at p. Used by `tightfit check-gradient`.
#include <vector>

#include "tightfit/design/optimization_problem.hpp"

namespace tightfit {

struct GradientCheckOptions {
  int directions = 3;  ///< random directions, each with unit largest point move
  double step = 0.0;   ///< h (m); 0 → 1e-5 × the mean initial boundary edge length
  unsigned seed = 1;
};

struct DirectionalCheck {
  double adjoint = 0.0;            ///< dT/dp · d
  double finite_difference = 0.0;  ///< FD of T along d
  double relative_error = 0.0;     ///< |adjoint − FD| / |FD| (absolute when FD = 0)
  double hessian_shift = 0.0;      ///< adjoint Hessian shift at p (0: exact)
};

/// A random direction over the design parameters (n even) whose largest 2D point move
/// is 1 (normally distributed entries, reproducible from `seed`).
VecX random_design_direction(Eigen::Index n, unsigned seed);

/// Evaluates and accepts p, then compares the adjoint derivative with FD along
/// `options.directions` directions. Throws SolverError when an evaluation fails (the
/// step is too large for the pattern, or the forward solve fails).
std::vector<DirectionalCheck> check_design_gradient(DesignProblem& problem, const VecX& p,
                                                    const GradientCheckOptions& options = {});

}  // namespace tightfit
