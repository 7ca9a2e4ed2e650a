#include "tightfit/solve/newton_solver.hpp"

#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>

#include "tightfit/common/error.hpp"

namespace tightfit {
namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

}  // namespace

double NewtonSolver::factorize_regularized(const SparseMatrix& H, int& factorizations) {
  const ShiftSequence shifts{options_.initial_regularization, options_.regularization_growth,
                             options_.max_regularizations};
  double last = 0.0;
  if (const auto shift = factorize_shifted(cholesky_, H, shifts, factorizations, &last))
    return *shift;
  throw SolverError("Newton: Hessian could not be factorized even with diagonal shift " +
                    std::to_string(last));
}

NewtonReport NewtonSolver::solve(NewtonProblem& problem, const SparseCholesky* held) {
  const auto t_start = Clock::now();
  NewtonReport report;
  report.tolerance = std::max(options_.absolute_force_tolerance,
                              options_.relative_force_tolerance * problem.force_scale());
  double energy = problem.energy();
  if (!std::isfinite(energy))
    throw SolverError("Newton: the initial state is inadmissible (energy is not finite)");
  bool chord = held && held->size() == problem.num_dofs() && options_.max_chord_steps > 0;
  double previous_force = 0.0;

  for (int it = 0;; ++it) {
    NewtonIteration record;
    auto t0 = Clock::now();
    const VecX g = problem.gradient();
    record.energy = energy;
    record.force_norm = problem.force_norm(g);
    if (!std::isfinite(record.force_norm))
      throw SolverError("Newton: the gradient is not finite at iteration " + std::to_string(it));
    report.final_energy = energy;
    report.final_force_norm = record.force_norm;
    report.iterations = it;
    if (record.force_norm <= report.tolerance) {
      report.converged = true;
      report.message = "converged";
      break;
    }
    if (it >= options_.max_iterations) {
      report.message = "iteration limit reached";
      break;
    }
    if (chord && (report.chord_steps >= options_.max_chord_steps ||
                  (report.chord_steps > 0 &&
                   record.force_norm > options_.chord_contraction * previous_force)))
      chord = false;
    previous_force = record.force_norm;
    const SparseCholesky* factor = &cholesky_;
    if (chord) {
      factor = held;
      record.chord = true;
      record.seconds_assembly = seconds_since(t0);
    } else {
      const SparseMatrix H = problem.hessian();
      record.seconds_assembly = seconds_since(t0);
      report.hessian_nonzeros = H.nonZeros();
      t0 = Clock::now();
      record.regularization = factorize_regularized(H, report.factorizations);
      record.seconds_factorization = seconds_since(t0);
      report.factor_nonzeros = cholesky_.factor_nonzeros();
    }

    t0 = Clock::now();
    const VecX dq = factor->solve(VecX(-g));
    record.seconds_solve = seconds_since(t0);

    t0 = Clock::now();
    const double slope = g.dot(dq);
    double alpha = 1.0;
    bool accepted = false;
    double new_energy = energy;
    // A chord step that needs much backtracking is not worth its trials: Newton's own
    // Hessian is then the better direction.
    const int halvings = record.chord ? 3 : options_.max_line_search_halvings;
    for (int k = 0; k <= halvings; ++k, alpha *= 0.5) {
      if (!problem.set_step(dq, alpha)) continue;
      new_energy = problem.energy();
      // Sufficient decrease, with a round-off allowance so that steps taken at the
      // noise floor of the energy near convergence are not rejected.
      const double allowance = 1e-14 * std::abs(energy);
      if (std::isfinite(new_energy) &&
          new_energy <= energy + options_.armijo * alpha * slope + allowance) {
        accepted = true;
        break;
      }
    }
    record.seconds_line_search = seconds_since(t0);
    if (!accepted && record.chord) {
      // The held factorization gave no descent here: go on with Newton's own.
      problem.set_step(dq, 0.0);
      chord = false;
      report.history.push_back(record);
      continue;
    }
    if (!accepted) {
      problem.set_step(dq, 0.0);
      report.history.push_back(record);
      report.message = "line search failed to decrease the energy";
      break;
    }
    problem.commit();
    energy = new_energy;
    record.step_size = alpha;
    if (record.chord) ++report.chord_steps;
    report.history.push_back(record);
  }
  report.seconds_total = seconds_since(t_start);
  if (!report.converged && options_.throw_on_failure) {
    std::ostringstream msg;
    msg << "Newton did not converge: " << report.message << " after " << report.iterations
        << " iterations; force residual " << report.final_force_norm << " N > tolerance "
        << report.tolerance << " N";
    throw SolverError(msg.str());
  }
  return report;
}

}  // namespace tightfit
