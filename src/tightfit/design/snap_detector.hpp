#pragma once
/// Detects, within one line search, that the objective is discontinuous along the search
/// direction: the fit snaps to another equilibrium (a fold of the equilibrium branch,
/// e.g. a garment point balanced on a ridge of the body) for every step beyond some
/// length. A continuous T with T'(0) < 0 rises over T(0) by at most O(α²) as the step α
/// shrinks; two trials whose rises stay within a factor kRiseRatio of each other while
/// the step shrank by kStepRatio or more cannot both lie on the branch of the accepted
/// equilibrium. Both are then counted as snapped. No physical scale enters the test.
#include <optional>
#include <vector>

#include "tightfit/design/optimization_problem.hpp"
#include "tightfit/design/optimization_state.hpp"

namespace tightfit {

class SnapDetector {
 public:
  /// A pair of rising trials is a snap when the later step is at most this fraction of
  /// the earlier one (a smooth rise would shrink at least 16-fold: quadratically) ...
  static constexpr double kStepRatio = 0.25;
  /// ... and its rise at least this fraction of the earlier trial's.
  static constexpr double kRiseRatio = 0.5;

  /// Starts a new search direction (forgets the trials of the previous one).
  void reset() { trials_.clear(); }
  /// A converged trial at step factor `alpha` (> 0) whose objective rose by `rise` > 0
  /// over the accepted one; `step`: its largest boundary-point move (m); `trial`: its
  /// evaluation (equilibrium_move and moved_vertex*). Other trials are not passed.
  void add_rising_trial(double alpha, double step, double rise, const DesignEvaluation& trial);
  /// The snap met since reset(), if any: the count of snapped trials and the shortest
  /// snapped trial's rise, step and equilibrium move.
  std::optional<SnapRecord> record() const;
  /// The step factor of the shortest snapped trial (nullopt: no snap): a step that lands
  /// on the other equilibrium (PatternOptimizer jumps there when the snaps persist).
  std::optional<double> shortest_snapped_alpha() const;

 private:
  struct Trial {
    double alpha = 0.0;
    bool snapped = false;
    SnapRecord fields;  // trials = 1
  };
  std::vector<Trial> trials_;
};

}  // namespace tightfit
