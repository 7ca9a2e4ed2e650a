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
/// Iteration k: the line search of design/line_search.hpp along d = −H_k ∇T, its first
/// trial bounded by the trust radius (max_step, or max_step_fraction × the mean initial
/// boundary edge length), by `step_growth` times the previous iteration's farthest
/// converged trial, and by the compression bound (no rest triangle shrinks below
/// `max_compression` of its area in one step). Accepted steps decrease T (Armijo), except
/// a jump through a snap-through (below).
///
/// Snap-throughs: a line search whose longer trials make the fit jump to another
/// equilibrium with a higher objective records a SnapRecord. After `snap_iterations`
/// such iterations in a row the run jumps: it accepts the shortest snapped trial (T
/// rises), clears the L-BFGS memory and continues from the new equilibrium, at most
/// `snap_jumps` times; then it stops (StopRule::kSnapThrough).
///
/// Remeshing: after each accepted step, when the problem has an objective factory and
/// options().remesh.enabled, pieces whose rest mesh degraded are remeshed
/// (DesignProblem::remesh); the run continues from the remeshed pattern's equilibrium
/// with its L-BFGS pairs carried onto the new boundary points (memory_transfer.hpp). A remeshing
/// that fails is undone and not tried again for 5 iterations; one that produces a NaN or infinity
/// ends the run with a SolverError "remeshing after iteration N: …". A checkpoint written after a
/// remeshing carries the remeshed design; resume() restores it before the parameters.
///
/// Stopping (StopRule, checked on each accepted point, in this order): ‖∇T‖ ≤
/// max(gradient_tolerance, relative_gradient_tolerance·‖∇T_0‖) (converged); T ≤
/// value_tolerance (converged); less than relative_decrease_tolerance relative progress
/// over the last `stall_iterations` iterations (since the last remeshing or jump): the
/// adjoint gradient is then checked against finite differences (design/adjoint_check.hpp)
/// and the run is converged when they agree (kStationary), not when they disagree
/// (kNoProgress); snap-throughs with no jump left; max_iterations; time_limit (s, this
/// run's wall time); a stop request; a failed line search.
///
/// Best design: the run returns the best design it visited. When a remeshing or a jump
/// raised T and the run never got back below its best, run() puts the best accepted
/// point back into the problem (its garment, parameters and equilibrium) before it
/// returns; OptimizationResult::best_iteration names it and checkpoint() still describes
/// the last accepted iteration (where a resumed run continues).
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "tightfit/design/adjoint_check.hpp"
#include "tightfit/design/optimization_problem.hpp"
#include "tightfit/design/optimization_state.hpp"
#include "tightfit/design/stop_rule.hpp"

namespace tightfit {

struct PatternOptimizerOptions {
  int max_iterations = 100;
  int memory = 8;                             ///< L-BFGS pairs kept
  double gradient_tolerance = 0.0;            ///< absolute, units of T per m
  double relative_gradient_tolerance = 1e-3;  ///< relative to the initial gradient norm
  double value_tolerance = 0.0;               ///< stop once T ≤ this
  /// Relative progress (T_{k−n} − T_k) / |T_{k−n}| over n = stall_iterations iterations
  /// below which the run checks its gradient and stops.
  double relative_decrease_tolerance = 1e-9;
  int stall_iterations = 20;
  /// The adjoint and finite-difference derivatives agree along a direction d when they
  /// differ by at most this fraction of the larger, or by less than the converged
  /// gradient level (the gradient tolerance times ‖d‖).
  double gradient_check_tolerance = 0.05;
  GradientCheckOptions gradient_check;  ///< directions and step of that check
  double time_limit = 0.0;              ///< s of wall time for this run; 0: none
  /// Trust radius: largest move of one boundary point per iteration (m); 0 →
  /// max_step_fraction × the mean initial boundary edge length.
  double max_step = 0.0;
  double max_step_fraction = 0.5;
  /// The first trial of an iteration moves no boundary point more than this factor
  /// times the largest move of the previous iteration's trials whose forward solve
  /// converged (0: no such cap).
  double step_growth = 2.0;
  /// No trial shrinks a rest triangle below this fraction of its area at the accepted
  /// point (0: no such bound); the hard floor is DesignProblemOptions::min_area_ratio.
  double max_compression = 0.5;
  double armijo = 1e-4;
  int max_line_search = 30;  ///< trials per line search
  /// Snap-through iterations in a row before the run jumps (0: never jumps nor stops
  /// for snaps).
  int snap_iterations = 3;
  int snap_jumps = 3;  ///< jumps through a snap-through per run before it stops there
};

struct OptimizationResult {
  StopRule rule = StopRule::kIterationLimit;
  bool converged = false;    ///< stop_rule_converged(rule)
  bool interrupted = false;  ///< rule == kInterrupted
  std::string stop_reason;   ///< stop_rule_words(rule) and the numbers behind it
  int iterations = 0;        ///< last accepted iteration
  double initial_value = 0.0;
  double final_value = 0.0;          ///< T of the returned (best) design
  int best_iteration = 0;            ///< the iteration whose design is returned
  bool best_after_remesh = false;    ///< ... after that iteration's remeshing
  bool best_restored = false;        ///< the returned design is not the last accepted one
  std::vector<double> final_terms;   ///< w_j T_j of the returned design
  double final_gradient_norm = 0.0;  ///< ‖∇T‖ of the returned design
  double last_value = 0.0;           ///< T at the last accepted iteration
  /// The finite-difference check of the no-progress rule (empty when not made).
  std::vector<DirectionalCheck> gradient_check;
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

  /// Runs until a stopping rule (see the header comment), or until `stop_requested`
  /// (polled before each iteration and between the trials of a line search) returns
  /// true. Returns with the problem at the best design visited.
  /// Throws SolverError when the starting point itself cannot be evaluated ("initial
  /// equilibrium…: …") or a remeshing produced a non-finite pattern ("remeshing after
  /// iteration N: …"); the state is then that of the last accepted iteration, whose
  /// checkpoint() is still valid.
  OptimizationResult run(const IterationCallback& on_iteration = {},
                         const std::function<bool()>& stop_requested = {});

  /// The state after the last accepted iteration (also after run() restored a better
  /// earlier design: a resumed run continues where this one stopped).
  OptimizationCheckpoint checkpoint() const;
  const std::vector<OptimizationIteration>& history() const { return history_; }
  const PatternOptimizerOptions& options() const { return options_; }

  /// Largest 2D move of one parameter point for a step d over p (m).
  static double max_point_move(const VecX& d);

 private:
  /// Evaluates the starting point; records iteration 0 on a fresh start.
  DesignEvaluation start(const std::function<double()>& elapsed,
                         const IterationCallback& on_iteration);
  /// The rule that ends the run at the accepted point `current`, if any.
  std::optional<StopRule> stop_rule(const DesignEvaluation& current, double run_seconds,
                                    const std::function<bool()>& stop_requested,
                                    std::ostringstream& reason, OptimizationResult& result);
  /// The no-progress test (over the history since the last remeshing or jump).
  bool no_progress() const;
  /// Line search, acceptance and remeshing of one iteration; false when the line search
  /// found no step (`rule` says why).
  bool iterate(VecX& p, DesignEvaluation& current, const std::function<bool()>& should_stop,
               OptimizationIteration& rec, StopRule& rule, std::ostringstream& reason);
  /// Accepts the shortest snapped trial of the last iteration (a jump); false when it
  /// cannot be evaluated.
  bool jump(VecX& p, DesignEvaluation& current, OptimizationIteration& rec);
  /// Remeshes degraded pieces after an accepted step (a RemeshRecord in `rec`).
  void remesh_if_degraded(VecX& p, DesignEvaluation& current, OptimizationIteration& rec);
  /// Fills the record of an accepted point.
  void record_point(OptimizationIteration& rec, const DesignEvaluation& current) const;
  /// Tracks the best point (`after_remesh`: the point is the remeshed pattern of the
  /// current iteration); keep_best_before_rise() snapshots it before a remeshing or a
  /// jump may raise T.
  void note_point(const DesignEvaluation& point, bool after_remesh);
  void keep_best_before_rise();
  /// Puts the best design back when the last point is worse; fills the result's fields.
  void finish_with_best(OptimizationResult& result, double last_value);
  int snapped_in_a_row() const;
  int jumps_made() const;
  int remesh_blocked_until() const;
  double trust_radius() const;
  double previous_move() const;

  DesignProblem& problem_;
  PatternOptimizerOptions options_;
  LbfgsMemory memory_;
  std::vector<OptimizationIteration> history_;
  int iteration_ = 0;
  double seconds_before_ = 0.0;  // wall time of earlier runs (resume)
  bool resumed_ = false;
  VecX jump_target_;  // p of the last iteration's shortest snapped trial (empty: none)
  // The best point: its value, terms, iteration, and a snapshot once the run left it.
  double best_value_ = 0.0;
  std::vector<double> best_terms_;
  double best_gradient_norm_ = 0.0;
  int best_iteration_ = -1;
  bool best_after_remesh_ = false;
  bool at_best_ = false;
  std::shared_ptr<const DesignProblem::Snapshot> best_snapshot_;
  std::optional<OptimizationCheckpoint> last_checkpoint_;  // set when the best was restored
};

}  // namespace tightfit
