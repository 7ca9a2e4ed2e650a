#include "tightfit/design/pattern_optimizer.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "tightfit/common/error.hpp"
#include "tightfit/common/stopwatch.hpp"
#include "tightfit/design/lbfgs.hpp"
#include "tightfit/design/line_search.hpp"
#include "tightfit/design/memory_transfer.hpp"

namespace tightfit {
namespace {

/// Iterations without a new attempt after a remeshing that had to be undone.
constexpr int kRemeshRetryGap = 5;

bool remeshed(const OptimizationIteration& it) { return it.remesh && it.remesh->failure.empty(); }

/// T at the point a record leaves the run at (after its remeshing, if one succeeded).
double point_value(const OptimizationIteration& it) {
  return remeshed(it) ? it.remesh->value : it.value;
}

/// Where the last iteration's snap-through happened, for the stop reason.
std::string snap_details(const SnapRecord& snap, int iterations, int jumps, double value) {
  std::ostringstream out;
  out.precision(3);
  out << "in the last " << iterations << " iterations every longer step made the fit jump (T +"
      << snap.rise << ", " << 100.0 * snap.rise / std::max(value, 1e-300)
      << " % of T, for a step of " << 1e3 * snap.step << " mm; garment vertex " << snap.vertex;
  if (!snap.label.empty()) out << " (" << snap.label << ")";
  out << " at (" << snap.position.x() << ", " << snap.position.y() << ", " << snap.position.z()
      << ") m moved " << 1e3 * snap.move << " mm); " << jumps << " jumps made";
  return out.str();
}

}  // namespace

PatternOptimizer::PatternOptimizer(DesignProblem& problem, PatternOptimizerOptions options)
    : problem_(problem), options_(options) {
  if (options_.max_iterations < 0 || options_.memory < 1 || options_.max_line_search < 1 ||
      options_.stall_iterations < 1 || options_.snap_iterations < 0 || options_.snap_jumps < 0)
    throw std::invalid_argument("PatternOptimizer: iteration counts must be positive");
  if (!(options_.armijo > 0.0 && options_.armijo < 0.5))
    throw std::invalid_argument("PatternOptimizer: armijo must be in (0, 0.5)");
  if (!(options_.max_compression >= 0.0 && options_.max_compression < 1.0))
    throw std::invalid_argument("PatternOptimizer: max_compression must be in [0, 1)");
  if (!(options_.max_step >= 0.0) || !(options_.max_step_fraction > 0.0) ||
      !(options_.step_growth >= 0.0) || !(options_.gradient_tolerance >= 0.0) ||
      !(options_.relative_gradient_tolerance >= 0.0) ||
      !(options_.relative_decrease_tolerance >= 0.0) || !(options_.time_limit >= 0.0) ||
      !(options_.gradient_check_tolerance >= 0.0) || std::isnan(options_.value_tolerance))
    throw std::invalid_argument("PatternOptimizer: tolerances and step limits must be >= 0");
}

double PatternOptimizer::max_point_move(const VecX& d) { return tightfit::max_point_move(d); }

void PatternOptimizer::resume(const OptimizationCheckpoint& checkpoint) {
  bool any_remesh = false;
  for (const OptimizationIteration& it : checkpoint.history) any_remesh |= remeshed(it);
  if (any_remesh && !checkpoint.remeshed)
    throw InputError("checkpoint",
                     "its history has a remeshing but it holds no remeshed "
                     "pattern (/remeshed)");
  if (!any_remesh && checkpoint.remeshed)
    throw InputError("checkpoint",
                     "it holds a remeshed pattern (/remeshed) but its history "
                     "has no remeshing");
  if (checkpoint.history.empty())
    throw InputError("checkpoint", "it has no history (not even the initial iteration)");
  const GarmentSimulation& sim = problem_.simulation();
  check_surface_points(checkpoint.state.garment, sim.surface().num_faces(), "checkpoint",
                       "/state/garment");
  if (checkpoint.held_point)  // its sizes: DesignProblem::set_accepted
    check_surface_points(checkpoint.held_point->state.garment, sim.surface().num_faces(),
                         "checkpoint", "/held_point/state/garment");
  if (checkpoint.state.body.rows() != sim.body_positions().rows())
    throw InputError("checkpoint",
                     "its body state has " + std::to_string(checkpoint.state.body.rows()) +
                         " positions, the body has " + std::to_string(sim.body_positions().rows()) +
                         " vertices (another body?)");
  if (checkpoint.remeshed) {
    if (!problem_.can_remesh())
      throw InputError("checkpoint",
                       "it was written after a remeshing, and this problem "
                       "cannot rebuild its objective for a remeshed pattern");
    problem_.restore_remeshed_design(*checkpoint.remeshed, checkpoint.state);
  }
  const Eigen::Index n = problem_.num_parameters();
  if (checkpoint.parameters.size() != n)
    throw InputError("checkpoint", "it has " + std::to_string(checkpoint.parameters.size()) +
                                       " design parameters, the garment needs " +
                                       std::to_string(n) + " (another garment or mesh?)");
  if (checkpoint.memory.s.size() != checkpoint.memory.y.size())
    throw InputError("checkpoint", "its L-BFGS memory has unequal s and y counts");
  for (size_t k = 0; k < checkpoint.memory.s.size(); ++k)
    if (checkpoint.memory.s[k].size() != n || checkpoint.memory.y[k].size() != n)
      throw InputError("checkpoint", "its L-BFGS memory does not match the design parameters");
  if (static_cast<int>(checkpoint.state.garment.size()) !=
      problem_.simulation().garment().num_garment_vertices())
    throw InputError("checkpoint",
                     "its state has " + std::to_string(checkpoint.state.garment.size()) +
                         " garment surface points, the garment has " +
                         std::to_string(problem_.simulation().garment().num_garment_vertices()) +
                         " vertices (another garment or mesh?)");
  problem_.set_accepted(checkpoint.parameters, checkpoint.state, checkpoint.held_ordering,
                        checkpoint.held_point);
  memory_ = checkpoint.memory;
  lbfgs_trim(memory_, options_.memory);
  history_ = checkpoint.history;
  iteration_ = checkpoint.iteration;
  seconds_before_ = history_.back().seconds;
  resumed_ = true;
  jump_target_ = VecX();
}

OptimizationCheckpoint PatternOptimizer::checkpoint() const {
  if (last_checkpoint_) return *last_checkpoint_;
  OptimizationCheckpoint c;
  c.iteration = iteration_;
  c.parameters = problem_.accepted_parameters();
  c.state = problem_.accepted_state();
  c.memory = memory_;
  c.history = history_;
  c.remeshed = problem_.remeshed_design();
  c.held_ordering = problem_.accepted_ordering();
  c.held_point = problem_.accepted_held_point();
  return c;
}

// ---- history-derived counters (the same for a fresh and a resumed run) ----

int PatternOptimizer::snapped_in_a_row() const {
  int n = 0;
  for (auto it = history_.rbegin(); it != history_.rend(); ++it) {
    if (remeshed(*it) || !it->snap) break;
    ++n;
  }
  return n;
}

int PatternOptimizer::jumps_made() const {
  return static_cast<int>(
      std::count_if(history_.begin(), history_.end(), [](const auto& it) { return it.jump; }));
}

int PatternOptimizer::remesh_blocked_until() const {
  for (auto it = history_.rbegin(); it != history_.rend(); ++it)
    if (it->remesh && !it->remesh->failure.empty()) return it->iteration + kRemeshRetryGap;
  return -1;
}

bool PatternOptimizer::no_progress() const {
  const int n = options_.stall_iterations;
  const int last = static_cast<int>(history_.size()) - 1;
  int start = 0;  // the segment since the last remeshing or jump
  for (int k = last; k > 0 && start == 0; --k)
    if (remeshed(history_[static_cast<size_t>(k)]) || history_[static_cast<size_t>(k)].jump)
      start = k;
  if (last - start < n) return false;
  const double before = point_value(history_[static_cast<size_t>(last - n)]);
  const double after = point_value(history_[static_cast<size_t>(last)]);
  return before - after <= options_.relative_decrease_tolerance * std::abs(before);
}

double PatternOptimizer::trust_radius() const {
  return options_.max_step > 0.0 ? options_.max_step
                                 : options_.max_step_fraction * problem_.mean_boundary_edge();
}

double PatternOptimizer::previous_move() const {
  // How far the previous iteration's forward solves followed a step: its largest
  // converged trial, accepted or not (none after a remeshing or a jump: new parameters
  // or another equilibrium). Not the accepted move alone: a step shortened by the
  // sufficient-decrease test says nothing about the solver.
  const OptimizationIteration& last = history_.back();
  if (history_.size() < 2 || remeshed(last) || last.jump) return 0.0;
  return std::max(last.max_solved_move, last.max_point_move);
}

// ---- the best design ----

void PatternOptimizer::note_point(const DesignEvaluation& point, bool after_remesh) {
  if (best_iteration_ >= 0 && !(point.value < best_value_)) {
    at_best_ = false;
    return;
  }
  best_value_ = point.value;
  best_terms_ = point.term_values;
  best_gradient_norm_ = point.gradient.norm();
  best_iteration_ = iteration_;
  best_after_remesh_ = after_remesh;
  at_best_ = true;
  best_snapshot_.reset();
}

void PatternOptimizer::keep_best_before_rise() {
  if (at_best_) best_snapshot_ = std::make_shared<DesignProblem::Snapshot>(problem_.snapshot());
}

void PatternOptimizer::finish_with_best(OptimizationResult& result, double last_value) {
  result.last_value = last_value;
  result.best_iteration = best_iteration_;
  result.best_after_remesh = best_after_remesh_;
  result.final_value = best_value_;
  result.final_terms = best_terms_;
  result.final_gradient_norm = best_gradient_norm_;
  if (at_best_ || !best_snapshot_) return;
  last_checkpoint_ = checkpoint();
  problem_.restore(*best_snapshot_);
  memory_ = {};
  jump_target_ = VecX();
  at_best_ = true;
  result.best_restored = true;
}

// ---- one run ----

void PatternOptimizer::record_point(OptimizationIteration& rec,
                                    const DesignEvaluation& current) const {
  rec.iteration = iteration_;
  rec.value = current.value;
  rec.term_values = current.term_values;
  rec.gradient_norm = current.gradient.norm();
  rec.hessian_shift = current.hessian_shift;
  rec.adjoint_method = adjoint_method_name(current.adjoint_method);
  rec.krylov_iterations = current.krylov_iterations;
}

DesignEvaluation PatternOptimizer::start(const std::function<double()>& elapsed,
                                         const IterationCallback& on_iteration) {
  last_checkpoint_.reset();
  DesignEvaluation current = problem_.evaluate(problem_.accepted_parameters(), true);
  if (!current.ok)
    throw SolverError(
        "initial equilibrium" +
        (resumed_ ? " (resumed at iteration " + std::to_string(iteration_) + ")" : std::string()) +
        ": the starting pattern cannot be evaluated: " + current.failure);
  problem_.accept();
  best_iteration_ = -1;
  best_snapshot_.reset();
  const bool fresh = !resumed_;
  resumed_ = true;  // a second run() continues this one
  if (!fresh) {
    note_point(current, !history_.empty() && remeshed(history_.back()));
    return current;
  }
  history_.clear();
  memory_ = {};
  iteration_ = 0;
  jump_target_ = VecX();
  OptimizationIteration first;
  record_point(first, current);
  add_trial_counters(first, current, current.seconds_forward + current.seconds_objective);
  first.factorizations += current.adjoint_factorizations;
  first.seconds_adjoint = current.seconds_adjoint;
  first.seconds = elapsed();
  history_.push_back(first);
  note_point(current, false);
  if (on_iteration) on_iteration(first);
  return current;
}

std::optional<StopRule> PatternOptimizer::stop_rule(const DesignEvaluation& current,
                                                    double run_seconds,
                                                    const std::function<bool()>& stop_requested,
                                                    std::ostringstream& reason,
                                                    OptimizationResult& result) {
  const double gradient_stop =
      std::max(options_.gradient_tolerance,
               options_.relative_gradient_tolerance * history_.front().gradient_norm);
  const double gnorm = current.gradient.norm();
  if (gnorm <= gradient_stop) {
    reason << "gradient norm " << gnorm << " <= " << gradient_stop;
    return StopRule::kGradient;
  }
  if (current.value <= options_.value_tolerance) {
    reason << "objective " << current.value << " <= " << options_.value_tolerance;
    return StopRule::kTargetValue;
  }
  if (no_progress()) {
    reason << "relative progress below " << options_.relative_decrease_tolerance << " over "
           << options_.stall_iterations << " iterations; ";
    try {
      result.gradient_check =
          check_design_gradient(problem_, problem_.accepted_parameters(), options_.gradient_check);
    } catch (const SolverError& e) {
      reason << "the finite-difference check failed: " << e.what();
      return StopRule::kNoProgress;
    }
    bool agree = true;
    for (size_t k = 0; k < result.gradient_check.size(); ++k) {
      const DirectionalCheck& c = result.gradient_check[k];
      const double d_norm =
          random_design_direction(problem_.num_parameters(),
                                  options_.gradient_check.seed + static_cast<unsigned>(k))
              .norm();
      const double diff = std::abs(c.adjoint - c.finite_difference);
      agree &= diff <= options_.gradient_check_tolerance *
                           std::max(std::abs(c.adjoint), std::abs(c.finite_difference)) ||
               diff <= gradient_stop * d_norm;
      reason << (k ? ", " : "directional derivatives adjoint / finite difference: ") << c.adjoint
             << " / " << c.finite_difference;
    }
    return agree ? StopRule::kStationary : StopRule::kNoProgress;
  }
  if (options_.snap_iterations > 0 && snapped_in_a_row() >= options_.snap_iterations &&
      jumps_made() >= options_.snap_jumps) {
    reason << snap_details(*history_.back().snap, snapped_in_a_row(), jumps_made(), current.value)
           << "; the pattern of iteration " << iteration_ << " is at the edge of that jump";
    return StopRule::kSnapThrough;
  }
  if (iteration_ >= options_.max_iterations) {
    reason << "iteration limit " << options_.max_iterations;
    return StopRule::kIterationLimit;
  }
  if (options_.time_limit > 0.0 && run_seconds >= options_.time_limit) {
    reason << "time limit " << options_.time_limit << " s";
    return StopRule::kTimeLimit;
  }
  if (stop_requested && stop_requested()) {
    reason << "after iteration " << iteration_;
    return StopRule::kInterrupted;
  }
  return std::nullopt;
}

bool PatternOptimizer::jump(VecX& p, DesignEvaluation& current, OptimizationIteration& rec) {
  keep_best_before_rise();
  const VecX target = jump_target_;
  jump_target_ = VecX();
  const auto t0 = SteadyClock::now();
  DesignEvaluation ev = problem_.evaluate(target, true);
  add_trial_counters(rec, ev, seconds_since(t0));
  if (!ev.ok) {
    ++rec.failed_solves;
    problem_.restore_accepted();
    return false;
  }
  problem_.accept();
  memory_ = {};
  const VecX step = target - p;
  p = target;
  current = std::move(ev);
  ++iteration_;
  record_point(rec, current);
  rec.step_norm = step.norm();
  rec.max_point_move = tightfit::max_point_move(step);
  rec.max_solved_move = rec.max_point_move;
  rec.step_factor = 1.0;
  rec.jump = true;
  note_point(current, false);
  return true;
}

bool PatternOptimizer::iterate(VecX& p, DesignEvaluation& current,
                               const std::function<bool()>& should_stop, OptimizationIteration& rec,
                               StopRule& rule, std::ostringstream& reason) {
  LineSearchSettings settings;
  settings.armijo = options_.armijo;
  settings.max_trials = options_.max_line_search;
  settings.trust_radius = trust_radius();
  settings.growth_cap = options_.step_growth * previous_move();
  settings.max_compression = options_.max_compression;
  settings.memory = options_.memory;
  LineSearchResult ls = line_search(problem_, p, current, memory_, settings, rec, should_stop);
  if (ls.stopped || !ls.accepted) {
    problem_.restore_accepted();
    if (ls.stopped) {
      rule = StopRule::kInterrupted;
      reason << "during the line search of iteration " << iteration_ + 1 << " ("
             << rec.line_search_trials << " trials); the pattern of iteration " << iteration_
             << " is kept";
    } else {
      rule = StopRule::kLineSearchFailed;
      reason << "last trial: " << (ls.trial.ok ? "no sufficient decrease" : ls.trial.failure);
    }
    return false;
  }
  lbfgs_push(memory_, ls.step, ls.trial.gradient - current.gradient, options_.memory);
  problem_.accept();
  jump_target_ = ls.jump_step.size() == p.size() ? VecX(p + ls.jump_step) : VecX();
  p += ls.step;
  current = std::move(ls.trial);
  ++iteration_;
  record_point(rec, current);
  rec.step_norm = ls.step.norm();
  rec.max_point_move = tightfit::max_point_move(ls.step);
  rec.step_factor = ls.alpha;
  rec.snap = ls.snap;
  note_point(current, false);
  remesh_if_degraded(p, current, rec);
  return true;
}

void PatternOptimizer::remesh_if_degraded(VecX& p, DesignEvaluation& current,
                                          OptimizationIteration& rec) {
  if (!problem_.options().remesh.enabled || !problem_.can_remesh() ||
      iteration_ <= remesh_blocked_until())
    return;
  const std::vector<int> degraded = problem_.degraded_pieces();
  if (degraded.empty()) return;
  keep_best_before_rise();
  const ParameterPoints before = parameter_points(p, parameter_pieces(problem_.coordinates()));
  RemeshOutcome o;
  try {
    o = problem_.remesh(degraded);
  } catch (const SolverError& e) {
    throw SolverError("remeshing after iteration " + std::to_string(iteration_) + ": " + e.what());
  }
  RemeshRecord r;
  for (int k : o.pieces.empty() ? degraded : o.pieces)
    r.pieces.push_back(problem_.simulation().garment().pattern.pieces[static_cast<size_t>(k)].name);
  r.min_angle_before = o.min_angle_before;
  r.min_angle_after = o.min_angle_after;
  r.newton_iterations = o.evaluation.newton_iterations;
  r.seconds = o.seconds;
  r.failure = o.failure;
  if (o.ok) {
    current = std::move(o.evaluation);
    p = problem_.accepted_parameters();
    // The curvature pairs mapped onto the new boundary points (memory_transfer.hpp).
    memory_ = transfer_memory(memory_, before,
                              parameter_points(p, parameter_pieces(problem_.coordinates())));
    jump_target_ = VecX();
    note_point(current, true);
  }
  r.value = current.value;
  r.term_values = current.term_values;
  r.gradient_norm = current.gradient.norm();
  r.parameters = o.ok ? o.parameters_after : o.parameters_before;
  r.garment_vertices = o.ok ? o.garment_vertices_after : o.garment_vertices_before;
  rec.remesh = std::move(r);
}

OptimizationResult PatternOptimizer::run(const IterationCallback& on_iteration,
                                         const std::function<bool()>& stop_requested) {
  const auto t_start = SteadyClock::now();
  auto elapsed = [&] { return seconds_before_ + seconds_since(t_start); };
  auto time_up = [&] {
    return options_.time_limit > 0.0 && seconds_since(t_start) >= options_.time_limit;
  };
  auto should_stop = [&] { return (stop_requested && stop_requested()) || time_up(); };
  OptimizationResult result;
  DesignEvaluation current = start(elapsed, on_iteration);
  result.initial_value = history_.front().value;
  VecX p = problem_.accepted_parameters();
  std::ostringstream reason;
  reason.precision(4);
  for (;;) {
    if (const auto rule =
            stop_rule(current, seconds_since(t_start), stop_requested, reason, result)) {
      result.rule = *rule;
      break;
    }
    OptimizationIteration rec;
    const bool want_jump = options_.snap_iterations > 0 &&
                           snapped_in_a_row() >= options_.snap_iterations &&
                           jump_target_.size() == p.size();
    if (want_jump && !jump(p, current, rec)) {
      result.rule = StopRule::kSnapThrough;
      reason << "the jump through the snap-through failed: "
             << "the equilibrium beyond it could not be evaluated";
      break;
    }
    if (!want_jump && !iterate(p, current, should_stop, rec, result.rule, reason)) {
      if (result.rule == StopRule::kInterrupted && time_up()) result.rule = StopRule::kTimeLimit;
      break;
    }
    rec.seconds = elapsed();
    history_.push_back(rec);
    if (on_iteration) on_iteration(rec);
  }
  result.converged = stop_rule_converged(result.rule);
  result.interrupted = result.rule == StopRule::kInterrupted;
  result.stop_reason = stop_rule_words(result.rule) + " (" + reason.str() + ")";
  result.iterations = iteration_;
  finish_with_best(result, current.value);
  result.seconds = seconds_since(t_start);
  return result;
}

}  // namespace tightfit
