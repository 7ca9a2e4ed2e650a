#include "tightfit/design/pattern_optimizer.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "tightfit/common/error.hpp"
#include "tightfit/common/stopwatch.hpp"
#include "tightfit/design/snap_detector.hpp"

namespace tightfit {
namespace {

/// Iterations without a new attempt after a remeshing that had to be undone.
constexpr int kRemeshRetryGap = 5;

/// Why a run stopped at a snap-through, and where (the last iteration's SnapRecord).
std::string snap_stop_reason(const SnapRecord& snap, int iterations, int iteration, double value) {
  std::ostringstream out;
  out.precision(3);
  out << "snap-through: in the last " << iterations
      << " iterations every longer step made the fit jump to another equilibrium with a "
         "higher objective (by "
      << snap.rise << ", " << 100.0 * snap.rise / std::max(value, 1e-300)
      << " % of T, for a step of " << 1e3 * snap.step << " mm; garment vertex " << snap.vertex;
  if (!snap.label.empty()) out << " (" << snap.label << ")";
  out << " at (" << snap.position.x() << ", " << snap.position.y() << ", " << snap.position.z()
      << ") m moved " << 1e3 * snap.move << " mm); the pattern of iteration " << iteration
      << " is at the edge of that jump";
  return out.str();
}

}  // namespace

PatternOptimizer::PatternOptimizer(DesignProblem& problem, PatternOptimizerOptions options)
    : problem_(problem), options_(options) {
  if (options_.max_iterations < 0 || options_.memory < 1 || options_.max_line_search < 1 ||
      options_.stall_iterations < 1)
    throw std::invalid_argument("PatternOptimizer: iteration counts must be positive");
  if (!(options_.armijo > 0.0 && options_.armijo < 0.5))
    throw std::invalid_argument("PatternOptimizer: armijo must be in (0, 0.5)");
  if (!(options_.max_step >= 0.0) || !(options_.max_step_fraction > 0.0) ||
      !(options_.step_growth >= 0.0) || !(options_.gradient_tolerance >= 0.0) ||
      !(options_.relative_gradient_tolerance >= 0.0) ||
      !(options_.relative_decrease_tolerance >= 0.0) || std::isnan(options_.value_tolerance))
    throw std::invalid_argument("PatternOptimizer: tolerances and step limits must be >= 0");
}

double PatternOptimizer::max_point_move(const VecX& d) {
  double m = 0.0;
  for (Eigen::Index i = 0; i + 1 < d.size(); i += 2) m = std::max(m, std::hypot(d[i], d[i + 1]));
  return m;
}

VecX PatternOptimizer::direction(const VecX& g) const {
  const int m = static_cast<int>(memory_.s.size());
  if (m == 0) return -g;
  VecX q = g;
  std::vector<double> alpha(m), rho(m);
  for (int i = m - 1; i >= 0; --i) {
    rho[i] = 1.0 / memory_.y[i].dot(memory_.s[i]);
    alpha[i] = rho[i] * memory_.s[i].dot(q);
    q -= alpha[i] * memory_.y[i];
  }
  const double gamma = memory_.s[m - 1].dot(memory_.y[m - 1]) / memory_.y[m - 1].squaredNorm();
  q *= gamma;
  for (int i = 0; i < m; ++i) {
    const double beta = rho[i] * memory_.y[i].dot(q);
    q += (alpha[i] - beta) * memory_.s[i];
  }
  return -q;
}

void PatternOptimizer::push_pair(const VecX& s, const VecX& y) {
  if (!(s.dot(y) > 1e-12 * s.norm() * y.norm())) return;
  memory_.s.push_back(s);
  memory_.y.push_back(y);
  if (static_cast<int>(memory_.s.size()) > options_.memory) {
    memory_.s.erase(memory_.s.begin());
    memory_.y.erase(memory_.y.begin());
  }
}

void PatternOptimizer::resume(const OptimizationCheckpoint& checkpoint) {
  bool remeshed = false;
  for (const OptimizationIteration& it : checkpoint.history)
    remeshed = remeshed || (it.remesh && it.remesh->failure.empty());
  if (remeshed && !checkpoint.remeshed)
    throw InputError("checkpoint",
                     "its history has a remeshing but it holds no remeshed "
                     "pattern (/remeshed)");
  if (!remeshed && checkpoint.remeshed)
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
  while (static_cast<int>(memory_.s.size()) > options_.memory) {
    memory_.s.erase(memory_.s.begin());
    memory_.y.erase(memory_.y.begin());
  }
  history_ = checkpoint.history;
  iteration_ = checkpoint.iteration;
  seconds_before_ = history_.back().seconds;
  resumed_ = true;
  // The loop's counters as they were after the last record: replayed by the rule run()
  // applies after each iteration.
  stalled_ = 0;
  remesh_blocked_until_ = -1;
  for (size_t k = 1; k < history_.size(); ++k) {
    const OptimizationIteration& prev = history_[k - 1];
    const double before =
        prev.remesh && prev.remesh->failure.empty() ? prev.remesh->value : prev.value;
    update_counters(before, history_[k]);
  }
}

void PatternOptimizer::update_counters(double value_before, const OptimizationIteration& record) {
  const double decrease = value_before - record.value;
  stalled_ =
      decrease <= options_.relative_decrease_tolerance * std::abs(value_before) ? stalled_ + 1 : 0;
  snapped_ = record.snap ? snapped_ + 1 : 0;
  if (const auto& r = record.remesh) {
    if (r->failure.empty()) {
      stalled_ = 0;
      snapped_ = 0;
    } else {
      remesh_blocked_until_ = record.iteration + kRemeshRetryGap;
    }
  }
}

OptimizationCheckpoint PatternOptimizer::checkpoint() const {
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

OptimizationResult PatternOptimizer::run(const IterationCallback& on_iteration,
                                         const std::function<bool()>& stop_requested) {
  const auto t_start = SteadyClock::now();
  auto elapsed = [&] { return seconds_before_ + seconds_since(t_start); };
  OptimizationResult result;

  VecX p = problem_.accepted_parameters();
  DesignEvaluation current = problem_.evaluate(p, true);
  if (!current.ok)
    throw SolverError(
        "initial equilibrium" +
        (resumed_ ? " (resumed at iteration " + std::to_string(iteration_) + ")" : std::string()) +
        ": the starting pattern cannot be evaluated: " + current.failure);
  problem_.accept();
  if (!resumed_) {
    history_.clear();
    memory_ = {};
    iteration_ = 0;
    OptimizationIteration first;
    first.value = current.value;
    first.term_values = current.term_values;
    first.gradient_norm = current.gradient.norm();
    first.line_search_trials = 1;
    first.newton_iterations = current.newton_iterations;
    first.chord_steps = current.chord_steps;
    first.force_accepted_steps = current.force_accepted_steps;
    first.factorizations = current.factorizations + current.adjoint_factorizations;
    first.adjoint_method = adjoint_method_name(current.adjoint_method);
    first.krylov_iterations = current.krylov_iterations;
    first.seconds_assembly = current.seconds_assembly;
    first.seconds_factorization = current.seconds_factorization;
    first.hessian_shift = current.hessian_shift;
    first.seconds_forward = current.seconds_forward;
    first.seconds_objective = current.seconds_objective;
    first.seconds_adjoint = current.seconds_adjoint;
    first.seconds = elapsed();
    history_.push_back(first);
    stalled_ = 0;
    snapped_ = 0;
    remesh_blocked_until_ = -1;
    if (on_iteration) on_iteration(first);
  }
  resumed_ = true;  // a second run() continues this one
  result.initial_value = history_.front().value;

  const double gradient_stop =
      std::max(options_.gradient_tolerance,
               options_.relative_gradient_tolerance * history_.front().gradient_norm);
  std::ostringstream reason;
  for (;;) {
    const double gnorm = current.gradient.norm();
    if (gnorm <= gradient_stop) {
      reason << "gradient norm " << gnorm << " <= " << gradient_stop;
      result.converged = true;
      break;
    }
    if (current.value <= options_.value_tolerance) {
      reason << "objective " << current.value << " <= " << options_.value_tolerance;
      result.converged = true;
      break;
    }
    if (stalled_ >= options_.stall_iterations) {
      reason << "relative decrease below " << options_.relative_decrease_tolerance << " for "
             << stalled_ << " iterations";
      result.converged = true;
      break;
    }
    if (options_.snap_iterations > 0 && snapped_ >= options_.snap_iterations) {
      reason << snap_stop_reason(*history_.back().snap, snapped_, iteration_, current.value);
      break;
    }
    if (iteration_ >= options_.max_iterations) {
      reason << "iteration limit " << options_.max_iterations << " reached";
      break;
    }
    if (stop_requested && stop_requested()) {
      reason << "interrupted after iteration " << iteration_;
      result.interrupted = true;
      break;
    }

    const double max_step = options_.max_step > 0.0
                                ? options_.max_step
                                : options_.max_step_fraction * problem_.mean_boundary_edge();
    // How far the previous iteration's forward solves followed a step: its largest
    // converged trial, accepted or not (none after a remeshing: the parameters are new).
    // Not the accepted move alone: a step shortened by the sufficient-decrease test says
    // nothing about the solver, and capping by it would shrink the steps geometrically
    // once a few line searches backtrack (the run then stops as "stalled").
    const OptimizationIteration& last = history_.back();
    const double previous_move =
        history_.size() > 1 && !(last.remesh && last.remesh->failure.empty())
            ? std::max(last.max_solved_move, last.max_point_move)
            : 0.0;
    OptimizationIteration rec;
    DesignEvaluation trial;
    VecX d;
    double alpha = 0.0;
    bool accepted = false;
    bool stopped_in_line_search = false;
    SnapDetector snaps;
    for (int attempt = 0; attempt < 2 && !accepted && !stopped_in_line_search; ++attempt) {
      snaps.reset();
      if (attempt == 1) {
        if (memory_.s.empty()) break;  // steepest descent already failed
        memory_ = {};
      }
      d = direction(current.gradient);
      double slope = current.gradient.dot(d);
      if (!(slope < 0.0)) {  // not a descent direction: drop the memory
        memory_ = {};
        d = -current.gradient;
        slope = -gnorm * gnorm;
      }
      const double move = max_point_move(d);
      if (!(move > 0.0)) break;
      alpha = memory_.s.empty() || move > max_step ? max_step / move : 1.0;
      if (const double cap = options_.step_growth * previous_move; cap > 0.0 && alpha * move > cap)
        alpha = cap / move;
      for (int t = 0; t < options_.max_line_search; ++t) {
        // A stop request ends the iteration between two trials: a hard line search can
        // take minutes, and the last accepted iteration is what a stop keeps anyway.
        if (t > 0 && stop_requested && stop_requested()) {
          stopped_in_line_search = true;
          break;
        }
        ++rec.line_search_trials;
        const auto t_trial = SteadyClock::now();
        trial = problem_.evaluate(p + alpha * d, false);
        rec.seconds_forward += seconds_since(t_trial) - trial.seconds_objective;
        rec.seconds_objective += trial.seconds_objective;
        rec.newton_iterations += trial.newton_iterations;
        rec.chord_steps += trial.chord_steps;
        rec.force_accepted_steps += trial.force_accepted_steps;
        rec.factorizations += trial.factorizations;
        rec.seconds_assembly += trial.seconds_assembly;
        rec.seconds_factorization += trial.seconds_factorization;
        if (!trial.ok) {
          ++rec.failed_solves;
          alpha *= 0.5;
          continue;
        }
        // The same computation as the accepted step's max_point_move below (not
        // alpha · move, which differs from it by round-off).
        rec.max_solved_move = std::max(rec.max_solved_move, max_point_move(VecX(alpha * d)));
        if (trial.value <= current.value + options_.armijo * alpha * slope) {
          const auto t_gradient = SteadyClock::now();
          const bool gradient_ok = problem_.add_gradient(trial);
          rec.seconds_adjoint += seconds_since(t_gradient);
          rec.factorizations += trial.adjoint_factorizations;
          if (gradient_ok) {
            accepted = true;
            break;
          }
          ++rec.failed_solves;
          alpha *= 0.5;
          continue;
        }
        if (const double rise = trial.value - current.value; rise > 0.0)
          snaps.add_rising_trial(alpha, max_point_move(VecX(alpha * d)), rise, trial);
        // Minimizer of the quadratic through T(0), T'(0) and T(α), kept in [0.1, 0.5]·α.
        const double curvature = 2.0 * (trial.value - current.value - alpha * slope);
        const double next = curvature > 0.0 ? -slope * alpha * alpha / curvature : 0.5 * alpha;
        alpha = std::clamp(next, 0.1 * alpha, 0.5 * alpha);
      }
    }
    if (stopped_in_line_search) {
      problem_.restore_accepted();
      reason << "interrupted during the line search of iteration " << iteration_ + 1 << " ("
             << rec.line_search_trials << " trials); the pattern of iteration " << iteration_
             << " is kept";
      result.interrupted = true;
      break;
    }
    if (!accepted) {
      problem_.restore_accepted();
      reason << "line search failed (no decrease of the objective; last trial: "
             << (trial.ok ? "no sufficient decrease" : trial.failure) << ")";
      break;
    }

    const VecX step = alpha * d;
    push_pair(step, trial.gradient - current.gradient);
    problem_.accept();
    p += step;
    const double value_before = current.value;
    current = std::move(trial);
    ++iteration_;

    rec.iteration = iteration_;
    rec.value = current.value;
    rec.term_values = current.term_values;
    rec.gradient_norm = current.gradient.norm();
    rec.step_norm = step.norm();
    rec.max_point_move = max_point_move(step);
    rec.step_factor = alpha;
    rec.hessian_shift = current.hessian_shift;
    rec.adjoint_method = adjoint_method_name(current.adjoint_method);
    rec.krylov_iterations = current.krylov_iterations;
    rec.snap = snaps.record();

    if (problem_.options().remesh.enabled && problem_.can_remesh() &&
        iteration_ > remesh_blocked_until_) {
      const std::vector<int> degraded = problem_.degraded_pieces();
      if (!degraded.empty()) {
        RemeshOutcome o;
        try {
          o = problem_.remesh(degraded);
        } catch (const SolverError& e) {
          throw SolverError("remeshing after iteration " + std::to_string(iteration_) + ": " +
                            e.what());
        }
        RemeshRecord r;
        for (int k : o.pieces.empty() ? degraded : o.pieces)
          r.pieces.push_back(
              problem_.simulation().garment().pattern.pieces[static_cast<size_t>(k)].name);
        r.min_angle_before = o.min_angle_before;
        r.min_angle_after = o.min_angle_after;
        r.newton_iterations = o.evaluation.newton_iterations;
        r.seconds = o.seconds;
        r.failure = o.failure;
        if (o.ok) {
          current = std::move(o.evaluation);
          p = problem_.accepted_parameters();
          memory_ = {};
          r.value = current.value;
          r.term_values = current.term_values;
          r.gradient_norm = current.gradient.norm();
          r.parameters = o.parameters_after;
          r.garment_vertices = o.garment_vertices_after;
        } else {
          r.value = current.value;
          r.term_values = current.term_values;
          r.gradient_norm = current.gradient.norm();
          r.parameters = o.parameters_before;
          r.garment_vertices = o.garment_vertices_before;
        }
        rec.remesh = std::move(r);
      }
    }
    update_counters(value_before, rec);
    rec.seconds = elapsed();
    history_.push_back(rec);
    if (on_iteration) on_iteration(rec);
  }
  result.stop_reason = reason.str();
  result.iterations = iteration_;
  result.final_value = current.value;
  result.seconds = seconds_since(t_start);
  return result;
}

}  // namespace tightfit
