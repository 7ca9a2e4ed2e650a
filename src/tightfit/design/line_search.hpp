#pragma once
/// One iteration's line search of PatternOptimizer: along d = −H ∇T (L-BFGS), backtracking
/// on α ∈ (0, 1] with the Armijo condition T(p + α d) ≤ T(p) + c α ∇T·d, shrinking α by
/// quadratic interpolation clamped to [0.1, 0.5]·α; a trial whose forward solve fails or
/// whose pattern is rejected is halved. When the search fails along an L-BFGS direction,
/// the memory is cleared and steepest descent is tried once more.
///
/// The first trial is bounded before any forward solve is spent on it:
///  * the trust radius: no boundary point moves more than `trust_radius` (m), nor more
///    than `growth_cap` (m; how far the previous iteration's solves followed a step);
///  * compression: no rest triangle's area falls below `max_compression` times its area
///    at the accepted point (the largest such α is exact: areas are quadratic in α), so
///    a step that would invert or crush a triangle is never tried.
#include <functional>
#include <optional>

#include "tightfit/design/optimization_problem.hpp"
#include "tightfit/design/optimization_state.hpp"

namespace tightfit {

struct LineSearchSettings {
  double armijo = 1e-4;
  int max_trials = 30;
  double trust_radius = 0.0;     ///< m, largest boundary-point move of a trial
  double growth_cap = 0.0;       ///< m, 0: none
  double max_compression = 0.5;  ///< in (0, 1); 0: no compression bound
  int memory = 8;                ///< L-BFGS pairs kept
};

struct LineSearchResult {
  bool accepted = false;
  bool stopped = false;    ///< `should_stop` ended the search between two trials
  DesignEvaluation trial;  ///< the accepted trial, with gradient (or the last one tried)
  VecX step;               ///< the accepted α d
  double alpha = 0.0;
  std::optional<SnapRecord> snap;  ///< the snap-through met, if any
  VecX jump_step;                  ///< α d of the shortest snapped trial (empty: none)
};

/// Searches from the accepted point p (value and gradient in `current`) and adds every
/// trial's counters to `record`. Clears `memory` when it gives no descent direction or
/// its direction fails.
LineSearchResult line_search(DesignProblem& problem, const VecX& p, const DesignEvaluation& current,
                             LbfgsMemory& memory, const LineSearchSettings& settings,
                             OptimizationIteration& record,
                             const std::function<bool()>& should_stop);

/// Adds one trial's forward-solve counters and times to `record`.
void add_trial_counters(OptimizationIteration& record, const DesignEvaluation& trial,
                        double seconds);

}  // namespace tightfit
