#pragma once
/// L-BFGS on the pattern design parameters (paper Sec. 4: "L-BFGS and line search for
/// robustness") over a DesignProblem.
///
/// Why our own loop rather than LBFGSpp: every function evaluation is a full forward
/// equilibrium solve that can fail (SolverError, flipped rest triangles) and must
/// never be accepted unconverged; LBFGSpp's line searches expect a finite f(x) at every
/// trial and throw on their own failures. The loop also has to (a) warm-start each trial
/// from the last ACCEPTED equilibrium and commit only accepted ones, (b) report every
/// accepted iteration (progress, history, checkpoints), and (c) save and restore its
/// curvature memory for --resume; LBFGSpp exposes none of these.
///
/// Iteration k: d = −H_k ∇T (two-loop recursion over the last `memory` pairs, initial
/// scaling γ = sᵀy / yᵀy; steepest descent when the memory is empty), capped so that no
/// boundary point moves more than `max_step` (m), nor more than `step_growth` times as
/// far as in the previous iteration's farthest trial whose forward solve converged
/// (OptimizationIteration::max_solved_move). Backtracking line search on α ∈ (0, 1]
/// with the Armijo condition T(p + α d) ≤ T(p) + c α ∇T·d (c = `armijo`), shrinking α
/// by quadratic interpolation clamped to [0.1, 0.5]·α; a trial whose forward solve
/// fails or whose pattern is rejected counts as "too far" and is halved. Accepted steps
/// therefore decrease T strictly (monotone). A pair (s, y) enters the memory only when
/// sᵀy > 1e-12 ‖s‖‖y‖ (no Wolfe condition is enforced, so curvature is checked). When the
/// line search fails along an L-BFGS direction the memory is cleared and steepest
/// descent is tried once more before giving up.
///
/// Remeshing: after each accepted step, when the problem has an objective factory and
/// options().remesh.enabled, pieces whose rest mesh degraded
/// (DesignProblem::degraded_pieces) are remeshed (DesignProblem::remesh): the run
/// continues from the remeshed pattern's equilibrium with an empty L-BFGS memory, and
/// the iteration's record carries a RemeshRecord. A remeshing that fails is undone
/// (recorded with its failure) and not tried again for 5 iterations; one that produces
/// a NaN or infinity ends the run with a SolverError "remeshing after iteration N: …". A checkpoint
/// written after a remeshing carries the remeshed design (RemeshedDesign); resume()
/// restores it (DesignProblem::restore_remeshed_design) before the parameters, so the
/// run continues on the remeshed pattern with the same coordinates and reference. The
/// stall count and the wait after a failed remeshing are recomputed from the history.
///
/// Stopping (checked on each accepted point): ‖∇T‖ ≤ max(gradient_tolerance,
/// relative_gradient_tolerance·‖∇T_0‖); T ≤ value_tolerance (range objectives reach 0
/// exactly); `stall_iterations` consecutive steps with relative decrease below
/// relative_decrease_tolerance; `snap_iterations` consecutive iterations whose line
/// search met a snap-through (the stop reason says where); max_iterations; or a failed
/// line search.
#include <functional>
#include <string>

#include "tightfit/design/optimization_problem.hpp"
#include "tightfit/design/optimization_state.hpp"

namespace tightfit {

struct PatternOptimizerOptions {
  int max_iterations = 100;
  int memory = 8;                             ///< L-BFGS pairs kept
  double gradient_tolerance = 0.0;            ///< absolute, units of T per m
  double relative_gradient_tolerance = 1e-6;  ///< relative to the initial gradient norm
  double value_tolerance = 0.0;               ///< stop once T ≤ this
  double relative_decrease_tolerance = 1e-9;  ///< per-iteration (T_k−1 − T_k) / T_k−1
  int stall_iterations = 3;
  /// Largest move of one boundary point per iteration (m); 0 → max_step_fraction × the
  /// mean initial boundary edge length.
  double max_step = 0.0;
  double max_step_fraction = 0.5;
  /// The first trial of an iteration moves no boundary point more than this factor
  /// times the largest move of the previous iteration's trials whose forward solve
  /// converged (0: no such cap). A step that can only grow gradually rarely sends the
  /// forward solve somewhere it cannot converge, so most iterations accept their first
  /// trial; a step shortened only by the sufficient-decrease test does not shrink the cap.
  double step_growth = 2.0;
  double armijo = 1e-4;
  int max_line_search = 30;  ///< trials per line search
  /// Stop after this many consecutive iterations whose line search met a snap-through
  /// (design/snap_detector.hpp: the fit jumps to another equilibrium with a higher
  /// objective for every step beyond a short one); 0: never stop for that. Such a run
  /// creeps along the edge of the jump with steps of micrometres and costly trials.
  int snap_iterations = 3;
};

struct OptimizationResult {
  bool converged = false;    ///< stopped by a tolerance (not by the iteration limit/failure)
  bool interrupted = false;  ///< stopped because `stop_requested` said so
  std::string stop_reason;
  int iterations = 0;  ///< last accepted iteration
  double initial_value = 0.0;
  double final_value = 0.0;
  double seconds = 0.0;  ///< wall time of this run (s)
};

/// Called after each accepted iteration (and for iteration 0, the initial pattern, when
/// a run starts fresh). The optimizer's checkpoint() is current during the call.
using IterationCallback = std::function<void(const OptimizationIteration&)>;

class PatternOptimizer {
 public:
  /// Throws std::invalid_argument for invalid options.
  PatternOptimizer(DesignProblem& problem, PatternOptimizerOptions options = {});

  /// Continues from a checkpoint instead of the problem's initial parameters (puts the
  /// simulation at the saved equilibrium; after a remeshing, on the saved remeshed
  /// pattern). Call before run(), on a problem built from the scene. Throws InputError
  /// when the checkpoint does not fit the problem.
  void resume(const OptimizationCheckpoint& checkpoint);

  /// Runs until a stopping criterion (see the header comment), or until
  /// `stop_requested` (polled before each iteration, after the previous one was accepted
  /// and reported, and between the trials of a line search) returns true: the state is
  /// then that of the last accepted iteration.
  /// Throws SolverError when the starting point itself cannot be evaluated ("initial
  /// equilibrium…: …", e.g. a state that is not finite) or a remeshing produced a
  /// non-finite pattern ("remeshing after iteration N: …"); the state is then that of
  /// the last accepted iteration, whose checkpoint() is still valid.
  OptimizationResult run(const IterationCallback& on_iteration = {},
                         const std::function<bool()>& stop_requested = {});

  /// The state after the last accepted iteration.
  OptimizationCheckpoint checkpoint() const;
  const std::vector<OptimizationIteration>& history() const { return history_; }
  const PatternOptimizerOptions& options() const { return options_; }

  /// Largest 2D move of one parameter point for a step d over p (m).
  static double max_point_move(const VecX& d);

 private:
  VecX direction(const VecX& g) const;
  void push_pair(const VecX& s, const VecX& y);
  /// The stall and remeshing counters after iteration `record`, whose objective was
  /// `value_before` before its step: the one rule for run() and resume().
  void update_counters(double value_before, const OptimizationIteration& record);

  DesignProblem& problem_;
  PatternOptimizerOptions options_;
  LbfgsMemory memory_;
  std::vector<OptimizationIteration> history_;
  int iteration_ = 0;
  double seconds_before_ = 0.0;  // wall time of earlier runs (resume)
  bool resumed_ = false;
  int stalled_ = 0;                // consecutive steps below the relative decrease tolerance
  int snapped_ = 0;                // consecutive iterations whose line search met a snap
  int remesh_blocked_until_ = -1;  // no remeshing attempt up to this iteration
};

}  // namespace tightfit
