#include "tightfit/solve/newton_solver.hpp"

#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>
#include <utility>

#include "tightfit/common/error.hpp"
#include "tightfit/common/stopwatch.hpp"
#include "tightfit/common/truncated_cg.hpp"

namespace tightfit {

double NewtonSolver::factorize_regularized(const SparseMatrix& H, int& factorizations,
                                           const CholeskyOrdering* ordering) {
  ShiftSequence shifts = options_.shift_sequence();
  // After a shifted iteration, start one step below the shift that worked (the
  // unshifted matrix has just failed nearby; each failed attempt is a factorization).
  if (shift_hint_ > 0.0) {
    double mean_diag = H.diagonal().cwiseAbs().mean();
    if (!(mean_diag > 0.0) || !std::isfinite(mean_diag)) mean_diag = 1.0;
    const double start = shift_hint_ / options_.regularization_growth / mean_diag;
    if (start > shifts.initial) {
      shifts.initial = start;
      shifts.try_unshifted = false;
    }
  }
  double last = 0.0;
  if (const auto shift = factorize_shifted(cholesky_, H, shifts, factorizations, &last, ordering)) {
    shift_hint_ = *shift;
    return *shift;
  }
  throw SolverError("Newton: Hessian could not be factorized even with diagonal shift " +
                    std::to_string(last));
}

bool NewtonSolver::accept_by_force(NewtonProblem& problem, double energy, double new_energy,
                                   double force_norm) const {
  if (!(options_.force_merit_contraction > 0.0)) return false;
  if (new_energy - energy > options_.energy_precision * std::abs(energy)) return false;
  return problem.force_norm(problem.gradient()) <= options_.force_merit_contraction * force_norm;
}

double NewtonSolver::krylov_tolerance(double force, double previous_force,
                                      double previous_tolerance) const {
  const double gamma = options_.krylov_forcing;
  if (!(gamma > 0.0) || !(previous_force > 0.0)) return options_.krylov_tolerance;
  const double ratio = force / previous_force;
  double eta = gamma * ratio * ratio;
  if (const double safeguard = gamma * previous_tolerance * previous_tolerance; safeguard > 0.1)
    eta = std::max(eta, safeguard);
  return std::clamp(eta, options_.krylov_tolerance,
                    std::max(options_.krylov_tolerance, options_.krylov_max_tolerance));
}

/// The state of one solve() between its steps.
struct NewtonSolver::SolveRun {
  SolveRun(NewtonProblem& p, ChordSteps c) : problem(p), chords(std::move(c)) {}

  NewtonProblem& problem;
  ChordSteps chords;
  SteadyClock::time_point start = SteadyClock::now();
  NewtonReport report;
  double energy = 0.0;  ///< at the last accepted state
  /// The factorization steps are taken with: the held one, then Newton's own. It is
  /// reused for chord steps while they contract the force norm fast enough.
  const SparseCholesky* factor = nullptr;
  bool reuse = false;           ///< the next step may use `factor` without refactorizing
  int chord_run = 0;            ///< consecutive chord steps with `factor`
  bool last_was_chord = false;  ///< the last accepted step was a chord step
  int failed_chords = 0;        ///< chord steps without descent (taken back)
  double previous_force = 0.0;
  double previous_tolerance = 0.0;
  /// The current step solves a positive definite model of the energy at this state.
  bool convex_model = false;
};

NewtonReport NewtonSolver::solve(NewtonProblem& problem, ChordSteps chords) {
  SolveRun run{problem, std::move(chords)};
  run.report.tolerance = options_.force_tolerance(problem.force_scale());
  run.energy = problem.energy();
  if (!std::isfinite(run.energy))
    throw SolverError("Newton: the initial state is inadmissible (energy is not finite)");
  const SparseCholesky* held = run.chords.held;
  run.factor =
      held && held->size() == problem.num_dofs() && options_.max_chord_steps > 0 ? held : nullptr;
  run.reuse = run.factor != nullptr;
  run.previous_tolerance = options_.krylov_tolerance;
  shift_hint_ = 0.0;

  for (int it = 0;; ++it) {
    NewtonIteration record;
    const auto t0 = SteadyClock::now();
    const VecX g = problem.gradient();
    if (stops_before_step(run, it, g, record)) break;
    prepare_factorization(run, record, t0);
    const VecX dq = step_direction(run, record, g);
    if (line_search(run, record, g, dq)) {
      problem.commit();
      if (record.chord) ++run.report.chord_steps;
      if (record.accepted_by_force) ++run.report.force_accepted_steps;
      run.report.history.push_back(record);
      if (options_.on_step) options_.on_step(record, seconds_since(run.start));
      continue;
    }
    problem.set_step(dq, 0.0);
    run.report.history.push_back(record);
    if (!record.chord) {
      run.report.message = "line search failed to decrease the energy";
      break;
    }
    // The reused factorization gave no descent here: factorize at this state.
    run.reuse = false;
    run.last_was_chord = false;
    ++run.failed_chords;
  }
  run.report.seconds_total = seconds_since(run.start);
  if (!run.report.converged && !run.report.stopped_after_predictor && options_.throw_on_failure)
    throw_not_converged(problem, run.report);
  return run.report;
}

bool NewtonSolver::stops_before_step(SolveRun& run, int it, const VecX& g,
                                     NewtonIteration& record) const {
  NewtonReport& report = run.report;
  record.energy = run.energy;
  record.force_norm = run.problem.force_norm(g);
  if (!std::isfinite(record.force_norm))
    throw SolverError("Newton: the gradient is not finite at iteration " + std::to_string(it));
  report.final_energy = run.energy;
  report.final_force_norm = record.force_norm;
  report.iterations = it;
  if (record.force_norm <= report.tolerance) {
    report.converged = true;
    report.message = "converged";
    return true;
  }
  if (run.chords.stop_after_poor_predictor && report.history.size() == 1 &&
      report.history.front().chord) {
    const NewtonIteration& predictor = report.history.front();
    const double left = record.force_norm / predictor.force_norm;
    if (predictor.step_size < 1.0 || left > options_.chord_contraction) {
      report.stopped_after_predictor = true;
      report.message = "the predictor step (length " + std::to_string(predictor.step_size) +
                       ") left " + std::to_string(left) + " of the force";
      return true;
    }
  }
  // The limit counts steps that factorized a Hessian; chord steps come on top (at most
  // max_chord_steps after each factorization, so the total stays bounded).
  if (it - report.chord_steps - run.failed_chords >= options_.max_iterations) {
    report.message = "iteration limit reached";
    return true;
  }
  return false;
}

void NewtonSolver::prepare_factorization(SolveRun& run, NewtonIteration& record,
                                         SteadyClock::time_point t0) {
  if (run.last_was_chord && record.force_norm > options_.chord_contraction * run.previous_force)
    run.reuse = false;
  record.krylov_tolerance =
      krylov_tolerance(record.force_norm, run.previous_force, run.previous_tolerance);
  run.previous_tolerance = record.krylov_tolerance;
  run.previous_force = record.force_norm;
  if (run.reuse && run.factor && run.chord_run < options_.max_chord_steps) {
    record.chord = true;
    ++run.chord_run;
    record.seconds_assembly = seconds_since(t0);
  } else {
    const SparseMatrix H = run.problem.hessian();
    record.seconds_assembly = seconds_since(t0);
    run.report.hessian_nonzeros = H.nonZeros();
    t0 = SteadyClock::now();
    const SparseCholesky* held = run.chords.held;
    record.regularization =
        factorize_regularized(H, run.report.factorizations, held ? &held->ordering() : nullptr);
    record.seconds_factorization = seconds_since(t0);
    factorization_shift_ = record.regularization;
    if (run.chords.on_factorized) run.chords.on_factorized();
    run.report.factor_nonzeros = cholesky_.factor_nonzeros();
    run.factor = &cholesky_;
    run.reuse = run.chords.reuse_own && options_.max_chord_steps > 0;
    run.chord_run = 0;
  }
  run.last_was_chord = record.chord;
}

VecX NewtonSolver::step_direction(SolveRun& run, NewtonIteration& record, const VecX& g) {
  VecX dq;
  run.convex_model = !record.chord && record.regularization == 0.0;
  auto t0 = SteadyClock::now();
  if (record.chord && options_.krylov_chords) {
    // Newton–Krylov: the Newton system at this state, solved by conjugate gradients
    // preconditioned with the held factorization.
    const std::optional<LinearOperator> H = run.problem.hessian_operator();
    record.seconds_assembly += seconds_since(t0);
    t0 = SteadyClock::now();
    if (H) {
      TruncatedCgReport cg;
      const SparseCholesky* factor = run.factor;
      dq = truncated_cg(*H, [&](const VecX& r) { return factor->solve_preconditioner(r); },
                        VecX(-g), cg, {record.krylov_tolerance, options_.krylov_iterations});
      record.krylov_iterations = cg.iterations;
      run.report.krylov_iterations += cg.iterations;
      // The held factorization no longer preconditions well: factorize next time.
      if (!cg.converged) run.reuse = false;
      run.convex_model = cg.converged && !cg.negative_curvature;
    } else {
      dq = run.factor->solve(VecX(-g));
    }
  } else {
    dq = run.factor->solve(VecX(-g));
  }
  record.seconds_solve = seconds_since(t0);
  return dq;
}

bool NewtonSolver::line_search(SolveRun& run, NewtonIteration& record, const VecX& g,
                               const VecX& dq) {
  const auto t0 = SteadyClock::now();
  const double slope = g.dot(dq);
  const double energy = run.energy;
  double alpha = 1.0;
  bool accepted = false;
  double new_energy = energy;
  // A chord step that needs much backtracking is not worth its trials: Newton's own
  // Hessian is then the better direction.
  const int halvings = record.chord ? 3 : options_.max_line_search_halvings;
  for (int k = 0; k <= halvings; ++k, alpha *= 0.5) {
    if (!run.problem.set_step(dq, alpha)) continue;
    new_energy = run.problem.energy();
    // Sufficient decrease, with a round-off allowance so that steps taken at the
    // noise floor of the energy near convergence are not rejected.
    const double allowance = 1e-14 * std::abs(energy);
    if (std::isfinite(new_energy) &&
        new_energy <= energy + options_.armijo * alpha * slope + allowance) {
      accepted = true;
      break;
    }
    if (k == 0 && run.convex_model && std::isfinite(new_energy) &&
        accept_by_force(run.problem, energy, new_energy, record.force_norm)) {
      accepted = true;
      record.accepted_by_force = true;
      break;
    }
  }
  record.seconds_line_search = seconds_since(t0);
  if (accepted) {
    run.energy = new_energy;
    record.step_size = alpha;
  }
  return accepted;
}

void NewtonSolver::throw_not_converged(NewtonProblem& problem, const NewtonReport& report) const {
  std::ostringstream msg;
  msg << "Newton did not converge: " << report.message << " after " << report.iterations
      << " iterations; force residual " << report.final_force_norm << " N > tolerance "
      << report.tolerance << " N";
  // The last accepted state (a failed step was taken back): where to look.
  if (const std::string where = problem.locate_largest_force(problem.gradient()); !where.empty())
    msg << "; largest force " << where;
  throw SolverError(msg.str());
}

}  // namespace tightfit
