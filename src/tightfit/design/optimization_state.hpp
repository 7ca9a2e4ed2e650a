#pragma once
/// Records of a pattern optimization run: one entry per accepted L-BFGS iteration, the
/// L-BFGS memory, and the checkpoint that lets a run continue where it stopped.
#include <string>
#include <vector>

#include "tightfit/common/types.hpp"
#include "tightfit/solve/embedded_equilibrium.hpp"

namespace tightfit {

/// One accepted iteration (iteration 0 is the initial pattern).
struct OptimizationIteration {
  int iteration = 0;
  double value = 0.0;               ///< T = Σ w_j T_j
  std::vector<double> term_values;  ///< w_j T_j, in the objective's entry order
  double gradient_norm = 0.0;       ///< ‖dT/dp‖₂ (units of T per m)
  double step_norm = 0.0;           ///< ‖Δp‖₂ (m) of the accepted step
  double max_point_move = 0.0;      ///< largest move of one boundary point (m)
  double step_factor = 0.0;         ///< accepted line-search factor α
  int line_search_trials = 0;       ///< forward solves tried for this step
  int failed_solves = 0;            ///< of them: rejected patterns / unconverged solves
  int newton_iterations = 0;        ///< forward Newton iterations of this iteration
  double hessian_shift = 0.0;       ///< adjoint Hessian shift (0: exact gradient)
  double seconds = 0.0;             ///< wall time since the run started (s)
};

/// L-BFGS curvature pairs, oldest first: s_k = p_{k+1} − p_k (m), y_k = ∇T_{k+1} − ∇T_k.
struct LbfgsMemory {
  std::vector<VecX> s;
  std::vector<VecX> y;
};

/// Everything needed to continue a run: the accepted parameters and equilibrium, the
/// L-BFGS memory and the history so far.
struct OptimizationCheckpoint {
  int iteration = 0;    ///< last accepted iteration
  VecX parameters;      ///< p (m)
  EmbeddedState state;  ///< equilibrium at p
  LbfgsMemory memory;
  std::vector<OptimizationIteration> history;
};

}  // namespace tightfit
